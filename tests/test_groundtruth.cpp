// Ray-traced ground truth (libshadowlab_groundtruth.so, loaded as the host loads it): the hard
// reference of a box on a plane against the analytic shadow polygon, absence of acne at grazing
// light, determinism across runs and thread counts, soft penumbrae, coloured transmission; the
// soft reference's own sampling error against the closed-form shadow of a sphere, and the
// adaptive soft reference against the uniform one.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "groundtruth/groundtruth.h"
#include "groundtruth/metrics.h"
#include "scene/scene.h"

using namespace shadowlab;

namespace {

GroundTruthPtr loadOrFail() {
    std::string error;
    GroundTruthPtr groundTruth = loadGroundTruth(error);
    EXPECT_TRUE(groundTruth) << error;
    return groundTruth;
}

Scene planeScene(float size = 20.0f) {
    Scene scene;
    scene.name = "test";
    scene.materials = {Material{}};
    scene.meshes.push_back(makePlane(size, size, 4));
    SceneObject ground;
    ground.name = "ground";
    ground.isPlane = true;
    scene.objects.push_back(ground);
    return scene;
}

// The box of the analytic test: size, rotation about y and position chosen so that no edge of
// its shadow lines up with the pixel grid.
const glm::vec3 kBoxSize(1.0f, 1.5f, 0.8f);
glm::mat4 boxTransform() {
    return glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.75f, -0.2f)), 0.5f, glm::vec3(0, 1, 0));
}

Scene boxOnPlane() {
    Scene scene = planeScene();
    scene.meshes.push_back(makeBox(kBoxSize));
    SceneObject box;
    box.name = "box";
    box.mesh = 1;
    box.transform = boxTransform();
    scene.objects.push_back(box);
    return scene;
}

struct View {
    int width = 320, height = 240;
    glm::vec3 eye{2.0f, 5.0f, 6.5f};
    glm::vec3 target{0.6f, 0.0f, 0.4f};
    glm::mat4 viewProjection() const {
        return glm::perspective(0.9f, static_cast<float>(width) / static_cast<float>(height), 0.1f, 100.0f) *
               glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    }
};

struct GBuffer {
    int width = 0, height = 0;
    std::vector<glm::vec4> positions, normals;
    GBufferView view() const { return {width, height, positions.data(), normals.data()}; }
};

GBuffer primary(IGroundTruth& groundTruth, const View& view) {
    GBuffer g;
    g.width = view.width;
    g.height = view.height;
    groundTruth.tracePrimary(view.viewProjection(), view.eye, view.width, view.height, g.positions, g.normals);
    return g;
}

// A top-down grid of ground points (y = 0, normal +y), spacing `step`, from (x0, z0): a
// G-buffer in world units, for measuring penumbrae.
GBuffer groundGrid(float x0, float z0, float step, int width, int height) {
    GBuffer g;
    g.width = width;
    g.height = height;
    for (int j = 0; j < height; ++j)
        for (int i = 0; i < width; ++i) {
            g.positions.emplace_back(x0 + step * static_cast<float>(i), 0.0f, z0 + step * static_cast<float>(j), 1.0f);
            g.normals.emplace_back(0.0f, 1.0f, 0.0f, 0.0f);
        }
    return g;
}

std::vector<glm::vec3> trace(IGroundTruth& groundTruth, const GBuffer& g, const LightInfo& light,
                             ReferenceOptions options = {}) {
    std::vector<glm::vec3> visibility;
    groundTruth.trace(g.view(), light, options, visibility);
    return visibility;
}

bool identical(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// --- analytic shadow of the box -------------------------------------------------------------

// Where the light projects a point onto the ground plane y = 0.
glm::vec2 projectToGround(const LightInfo& light, glm::vec3 c) {
    if (light.type == LightType::Directional) {
        const glm::vec3 p = c + light.direction * (-c.y / light.direction.y);
        return {p.x, p.z};
    }
    const glm::vec3 p = light.position + (c - light.position) * (light.position.y / (light.position.y - c.y));
    return {p.x, p.z};
}

float cross2(glm::vec2 o, glm::vec2 a, glm::vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Andrew's monotone chain; counter-clockwise, no repeated point.
std::vector<glm::vec2> convexHull(std::vector<glm::vec2> points) {
    std::sort(points.begin(), points.end(), [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    std::vector<glm::vec2> hull(2 * points.size());
    size_t k = 0;
    for (size_t i = 0; i < points.size(); ++i) {
        while (k >= 2 && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    for (size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
        while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
        hull[k++] = points[i];
    }
    hull.resize(k - 1);
    return hull;
}

bool insideConvex(const std::vector<glm::vec2>& hull, glm::vec2 p) {
    for (size_t i = 0; i < hull.size(); ++i)
        if (cross2(hull[i], hull[(i + 1) % hull.size()], p) < 0) return false;
    return true;
}

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    const glm::vec2 ab = b - a;
    const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f);
    return glm::length(p - (a + t * ab));
}

struct AnalyticCheck {
    int groundInside = 0, groundOutside = 0, boxLit = 0;
    int wrongInside = 0, wrongOutside = 0, wrongBox = 0;
};

// Classifies every compared pixel: ground pixels farther than one pixel (screen space) from the
// box's shadow polygon must be 0 inside and 1 outside; box pixels facing the light must be lit
// (the box is convex and the ground lies below it).
AnalyticCheck checkAgainstPolygon(IGroundTruth& groundTruth, const LightInfo& light, const View& view) {
    const Scene scene = boxOnPlane();
    groundTruth.setScene(scene);
    const GBuffer g = primary(groundTruth, view);
    const std::vector<glm::vec3> reference = trace(groundTruth, g, light);
    const std::vector<uint8_t> mask = compareMask(g.view(), light);

    std::vector<glm::vec2> shadow;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 local((corner & 1 ? 0.5f : -0.5f) * kBoxSize.x, (corner & 2 ? 0.5f : -0.5f) * kBoxSize.y,
                              (corner & 4 ? 0.5f : -0.5f) * kBoxSize.z);
        shadow.push_back(projectToGround(light, glm::vec3(boxTransform() * glm::vec4(local, 1.0f))));
    }
    const std::vector<glm::vec2> hull = convexHull(shadow);
    const glm::mat4 viewProjection = view.viewProjection();
    std::vector<glm::vec2> hullOnScreen;
    for (glm::vec2 p : hull) {
        const glm::vec4 clip = viewProjection * glm::vec4(p.x, 0.0f, p.y, 1.0f);
        EXPECT_GT(clip.w, 0.0f) << "shadow polygon behind the camera";
        const glm::vec2 ndc = glm::vec2(clip) / clip.w;
        hullOnScreen.push_back((ndc * 0.5f + 0.5f) * glm::vec2(static_cast<float>(view.width), static_cast<float>(view.height)));
    }

    AnalyticCheck check;
    for (int y = 0; y < g.height; ++y)
        for (int x = 0; x < g.width; ++x) {
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(g.width) + static_cast<size_t>(x);
            if (!mask[i]) {
                EXPECT_EQ(reference[i], glm::vec3(0.0f)) << "excluded pixel " << x << "," << y << " not 0";
                continue;
            }
            const glm::vec3 p(g.positions[i]);
            EXPECT_TRUE(reference[i] == glm::vec3(0.0f) || reference[i] == glm::vec3(1.0f)) << "hard reference not binary";
            const bool ground = std::abs(p.y) < 1e-4f && g.normals[i].y > 0.999f;
            if (!ground) {
                ++check.boxLit;
                if (reference[i].x != 1.0f) ++check.wrongBox;
                continue;
            }
            const glm::vec2 pixel(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
            float distance = std::numeric_limits<float>::infinity();
            for (size_t e = 0; e < hullOnScreen.size(); ++e)
                distance = std::min(distance, distanceToSegment(pixel, hullOnScreen[e], hullOnScreen[(e + 1) % hullOnScreen.size()]));
            if (distance <= 1.0f) continue;
            if (insideConvex(hull, glm::vec2(p.x, p.z))) {
                ++check.groundInside;
                if (reference[i].x != 0.0f) ++check.wrongInside;
            } else {
                ++check.groundOutside;
                if (reference[i].x != 1.0f) ++check.wrongOutside;
            }
        }
    return check;
}

void expectMatchesPolygon(const AnalyticCheck& c) {
    EXPECT_GT(c.groundInside, 500) << "the view should show the shadow";
    EXPECT_GT(c.groundOutside, 5000);
    EXPECT_GT(c.boxLit, 100) << "the view should show lit box faces";
    EXPECT_EQ(c.wrongInside, 0) << "lit pixels inside the shadow polygon (leaks)";
    EXPECT_EQ(c.wrongOutside, 0) << "shadowed pixels outside the shadow polygon";
    EXPECT_EQ(c.wrongBox, 0) << "box faces facing the light not lit (acne)";
}

LightInfo directional(glm::vec3 direction, float size = 0.0f) {
    LightInfo light;
    light.type = LightType::Directional;
    light.direction = glm::normalize(direction);
    light.size = size;
    return light;
}

// A point or spot light above and beside the box; the spot aims past the box at its shadow.
LightInfo lampNearBox(LightType type) {
    LightInfo light;
    light.type = type;
    light.position = glm::vec3(-1.5f, 4.0f, -1.2f);
    light.direction = glm::normalize(glm::vec3(1.0f, 0.0f, 0.8f) - light.position);
    light.spotOuterAngle = 0.6f;
    light.spotInnerAngle = 0.5f;
    return light;
}

} // namespace

TEST(GroundTruth, LoadsModule) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    std::vector<glm::vec3> visibility;
    EXPECT_THROW(groundTruth->trace(GBufferView{}, LightInfo{}, ReferenceOptions{}, visibility), std::logic_error);
    groundTruth->setScene(boxOnPlane());
    EXPECT_GT(groundTruth->rayOffset(), 0.0f);
    EXPECT_LT(groundTruth->rayOffset(), 0.01f);
}

TEST(GroundTruth, PrimaryGBufferFollowsGlRowOrder) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(boxOnPlane());
    const View view;
    const GBuffer g = primary(*groundTruth, view);
    // Row 0 is the bottom of the image: the ground nearest the camera.
    const size_t bottom = static_cast<size_t>(view.width / 2);
    const size_t top = static_cast<size_t>(view.height - 1) * static_cast<size_t>(view.width) + bottom;
    ASSERT_EQ(g.positions[bottom].w, 1.0f);
    if (g.positions[top].w == 1.0f) {
        EXPECT_LT(glm::length(glm::vec3(g.positions[bottom]) - view.eye), glm::length(glm::vec3(g.positions[top]) - view.eye));
    }
    for (size_t i = 0; i < g.positions.size(); ++i) {
        if (g.positions[i].w == 1.0f) {
            EXPECT_NEAR(glm::length(glm::vec3(g.normals[i])), 1.0f, 1e-5f);
        }
    }
}

TEST(GroundTruth, HardDirectionalMatchesShadowPolygon) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    expectMatchesPolygon(checkAgainstPolygon(*groundTruth, directional({0.5f, -1.0f, 0.35f}), View{}));
}

TEST(GroundTruth, HardPointMatchesShadowPolygon) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    expectMatchesPolygon(checkAgainstPolygon(*groundTruth, lampNearBox(LightType::Point), View{}));
}

TEST(GroundTruth, HardSpotMatchesShadowPolygonInsideItsCone) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    const LightInfo light = lampNearBox(LightType::Spot);
    expectMatchesPolygon(checkAgainstPolygon(*groundTruth, light, View{}));

    // The cone leaves part of the ground out of the comparison.
    const GBuffer g = primary(*groundTruth, View{});
    const std::vector<uint8_t> mask = compareMask(g.view(), light);
    size_t ground = 0, compared = 0;
    for (size_t i = 0; i < mask.size(); ++i) {
        ground += g.positions[i].w == 1.0f;
        compared += mask[i];
    }
    EXPECT_LT(compared, ground * 9 / 10);
}

// A plane under light 5 degrees above the horizon: every compared pixel lit, also with the
// position noise of a float G-buffer read back from the GPU.
TEST(GroundTruth, NoAcneAtGrazingLight) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(planeScene());
    const float elevation = 5.0f * std::numbers::pi_v<float> / 180.0f;
    const LightInfo sun = directional({std::cos(elevation) * 0.8f, -std::sin(elevation), std::cos(elevation) * 0.6f});
    LightInfo lamp;
    lamp.type = LightType::Point;
    lamp.position = glm::vec3(-9.0f, 0.3f, -9.0f); // low over a corner: grazing across the plane

    GBuffer g = primary(*groundTruth, View{});
    GBuffer noisy = g;
    for (size_t i = 0; i < noisy.positions.size(); ++i) // deterministic +-1e-4 noise
        noisy.positions[i] += glm::vec4(glm::vec3(static_cast<float>((i * 7919u) % 201u) - 100.0f) * 1e-6f, 0.0f);

    for (const LightInfo& light : {sun, lamp})
        for (const GBuffer* gbuffer : {&g, &noisy}) {
            const std::vector<glm::vec3> reference = trace(*groundTruth, *gbuffer, light);
            const std::vector<uint8_t> mask = compareMask(gbuffer->view(), light);
            size_t compared = 0, shadowed = 0;
            for (size_t i = 0; i < mask.size(); ++i) {
                compared += mask[i];
                shadowed += mask[i] && reference[i] != glm::vec3(1.0f);
            }
            EXPECT_GT(compared, mask.size() / 2);
            EXPECT_EQ(shadowed, 0u) << "acne on a plane at grazing light";
        }

    // A box under the same elevation from the other side (its 17-unit shadow then runs away from
    // the camera): its top face sees the light at 5 degrees too, and the shadow still matches.
    const LightInfo sunBehind = directional({-std::cos(elevation) * 0.8f, -std::sin(elevation), -std::cos(elevation) * 0.6f});
    expectMatchesPolygon(checkAgainstPolygon(*groundTruth, sunBehind, View{}));
}

TEST(GroundTruth, DeterministicAcrossRunsAndThreadCounts) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    const Scene scene = boxOnPlane();
    groundTruth->setScene(scene);
    const GBuffer g = primary(*groundTruth, View{});
    LightInfo light = directional({0.5f, -1.0f, 0.35f}, 0.08f);

    ReferenceOptions hard;
    hard.threads = 1;
    const auto hard1 = trace(*groundTruth, g, light, hard);
    hard.threads = 3;
    EXPECT_TRUE(identical(hard1, trace(*groundTruth, g, light, hard)));

    ReferenceOptions soft;
    soft.mode = ReferenceOptions::Mode::Soft;
    soft.samplesPerPixel = 9;
    soft.threads = 1;
    const auto soft1 = trace(*groundTruth, g, light, soft);
    soft.threads = 2;
    EXPECT_TRUE(identical(soft1, trace(*groundTruth, g, light, soft)));
    soft.threads = 0;
    EXPECT_TRUE(identical(soft1, trace(*groundTruth, g, light, soft)));
    EXPECT_FALSE(identical(hard1, soft1));

    // A fresh instance (its own BVH build) gives the same images.
    auto other = loadOrFail();
    ASSERT_TRUE(other);
    other->setScene(scene);
    const GBuffer g2 = primary(*other, View{});
    EXPECT_TRUE(g.positions == g2.positions && g.normals == g2.normals);
    EXPECT_TRUE(identical(hard1, trace(*other, g2, light, hard)));
    EXPECT_TRUE(identical(soft1, trace(*other, g2, light, soft)));

    // The seed is what varies the noise.
    soft.seed = 2;
    EXPECT_FALSE(identical(soft1, trace(*groundTruth, g, light, soft)));
}

// A tall box under a sun of angular radius 0.1 rad: the penumbra along the side of the shadow
// widens with the distance to the occluding edge, the umbra is 0, open ground 1.
TEST(GroundTruth, SoftPenumbraWidensAwayFromContact) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    Scene scene = planeScene();
    scene.meshes.push_back(makeBox(glm::vec3(1.0f, 3.0f, 1.0f)));
    SceneObject box;
    box.name = "box";
    box.mesh = 1;
    box.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.5f, 0.0f));
    scene.objects.push_back(box);
    groundTruth->setScene(scene);

    // Light travels towards +x and down (2 in y per 1 in x): the shadow spans x in [0.5, 2].
    const LightInfo sun = directional({0.5f, -1.0f, 0.0f}, 0.1f);
    const float step = 0.01f, x0 = -1.0f, z0 = -1.5f;
    const GBuffer g = groundGrid(x0, z0, step, 350, 300);
    ReferenceOptions options;
    options.mode = ReferenceOptions::Mode::Soft;
    options.samplesPerPixel = 64;
    const std::vector<glm::vec3> v = trace(*groundTruth, g, sun, options);

    auto at = [&](float x, float z) {
        const int i = static_cast<int>(std::lround((x - x0) / step));
        const int j = static_cast<int>(std::lround((z - z0) / step));
        return v[static_cast<size_t>(j) * static_cast<size_t>(g.width) + static_cast<size_t>(i)];
    };
    for (const glm::vec3& value : v) {
        EXPECT_GE(value.x, 0.0f);
        EXPECT_LE(value.x, 1.0f);
        EXPECT_EQ(value.x, value.y);
        EXPECT_EQ(value.x, value.z);
    }
    EXPECT_EQ(at(1.0f, 0.0f), glm::vec3(0.0f)) << "umbra";
    EXPECT_EQ(at(-0.8f, 0.0f), glm::vec3(1.0f)) << "open ground before the box";
    EXPECT_EQ(at(1.0f, 1.2f), glm::vec3(1.0f)) << "open ground beside the shadow";

    // Penumbra width across the side boundary (z = 0.5), in samples of `step`.
    auto penumbraWidth = [&](float x) {
        int count = 0;
        for (float z = 0.0f; z < 1.49f; z += step)
            if (const float value = at(x, z).x; value > 0.02f && value < 0.98f) ++count;
        return count;
    };
    const int nearContact = penumbraWidth(0.6f), middle = penumbraWidth(1.0f), far = penumbraWidth(1.4f);
    EXPECT_GT(nearContact, 0);
    EXPECT_GT(middle, nearContact + 5);
    EXPECT_GT(far, middle + 5);
    // Blocker 0.9 * sqrt(5) = 2.0 away at x = 1.4: width about 2 * 2.0 * tan(0.1) = 0.4.
    EXPECT_NEAR(far * step, 0.4f, 0.12f);
}

TEST(GroundTruth, SoftWithoutEmitterSizeIsHard) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(boxOnPlane());
    const GBuffer g = primary(*groundTruth, View{});
    const LightInfo light = directional({0.5f, -1.0f, 0.35f}, 0.0f);
    ReferenceOptions soft;
    soft.mode = ReferenceOptions::Mode::Soft;
    EXPECT_TRUE(identical(trace(*groundTruth, g, light), trace(*groundTruth, g, light, soft)));
}

TEST(GroundTruth, SoftPointLightUmbraAndLit) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    Scene scene = planeScene();
    scene.meshes.push_back(makeBox(glm::vec3(2.0f, 0.2f, 2.0f)));
    SceneObject slab; // a table top 1 above the ground, under a lamp of radius 0.3
    slab.name = "slab";
    slab.mesh = 1;
    slab.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.objects.push_back(slab);
    groundTruth->setScene(scene);
    LightInfo lamp;
    lamp.type = LightType::Point;
    lamp.position = glm::vec3(0.0f, 3.0f, 0.0f);
    lamp.size = 0.3f;
    const GBuffer g = groundGrid(-3.0f, 0.0f, 0.05f, 121, 1);
    ReferenceOptions options;
    options.mode = ReferenceOptions::Mode::Soft;
    const std::vector<glm::vec3> v = trace(*groundTruth, g, lamp, options);
    EXPECT_EQ(v[60], glm::vec3(0.0f)) << "under the slab";
    EXPECT_EQ(v[0], glm::vec3(1.0f)) << "far from it";
    bool partial = false;
    for (const glm::vec3& value : v) partial = partial || (value.x > 0.0f && value.x < 1.0f);
    EXPECT_TRUE(partial);
}

// Quads of alpha 0.5: one tinted red (transmission (1, 0, 0)) over x in [-1, 1], one tinted blue
// over x in [0, 2] above it, an opaque box, and an opaque box that casts no shadow; sun overhead.
TEST(GroundTruth, ColouredTransmissionMultiplies) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    Scene scene = planeScene();
    scene.materials.push_back({.name = "red", .alpha = 0.5f, .transmission = glm::vec3(1.0f, 0.0f, 0.0f)});
    scene.materials.push_back({.name = "blue", .alpha = 0.5f, .transmission = glm::vec3(0.0f, 0.0f, 1.0f)});
    scene.meshes.push_back(makePlane(2.0f, 2.0f, 1));
    scene.meshes.push_back(makeBox(glm::vec3(1.0f)));
    auto add = [&](const char* name, uint32_t mesh, uint32_t material, glm::vec3 at, bool castsShadow) {
        SceneObject object;
        object.name = name;
        object.mesh = mesh;
        object.material = material;
        object.transform = glm::translate(glm::mat4(1.0f), at);
        object.castsShadow = castsShadow;
        scene.objects.push_back(object);
    };
    add("red", 1, 1, {0.0f, 1.0f, 0.0f}, true);
    add("blue", 1, 2, {1.0f, 1.5f, 0.0f}, true);
    add("opaque", 2, 0, {-4.0f, 2.0f, 0.0f}, true);
    add("ghost", 2, 0, {4.0f, 2.0f, 0.0f}, false);
    groundTruth->setScene(scene);

    const LightInfo sun = directional({0.0f, -1.0f, 0.0f}, 0.02f);
    // Ground points: under red only, under both, open ground, under the opaque box, under the ghost,
    // and under the shared edge of the red quad's two triangles.
    const std::vector<glm::vec3> points = {{-0.5f, 0, 0.3f}, {0.5f, 0, -0.3f}, {0, 0, 3}, {-4, 0, 0}, {4, 0, 0}, {0.5f, 0, 0.5f}};
    GBuffer g;
    g.width = static_cast<int>(points.size());
    g.height = 1;
    for (glm::vec3 p : points) {
        g.positions.emplace_back(p, 1.0f);
        g.normals.emplace_back(0.0f, 1.0f, 0.0f, 0.0f);
    }
    const glm::vec3 red(1.0f, 0.5f, 0.5f), both(0.5f, 0.25f, 0.5f);

    // Soft twice: uniform and adaptive (a first batch of 8 of the 16 strata, all agreeing here).
    for (int variant = 0; variant < 3; ++variant) {
        const ReferenceOptions::Mode mode = variant == 0 ? ReferenceOptions::Mode::Hard : ReferenceOptions::Mode::Soft;
        ReferenceOptions options;
        options.mode = mode;
        options.samplesPerPixel = 16;
        options.adaptive = variant == 2;
        options.firstBatch = 8;
        options.model = TranslucencyModel::Physical;
        const std::vector<glm::vec3> v = trace(*groundTruth, g, sun, options);
        EXPECT_EQ(v[0], red);
        EXPECT_EQ(v[1], both);
        EXPECT_EQ(v[2], glm::vec3(1.0f));
        EXPECT_EQ(v[3], glm::vec3(0.0f));
        EXPECT_EQ(v[4], glm::vec3(1.0f)) << "castsShadow = false must not block";
        EXPECT_EQ(v[5], both) << "a ray through a shared edge crosses the surface once";

        // The opaque model: every caster blocks, translucent or not.
        options.model = TranslucencyModel::Opaque;
        const std::vector<glm::vec3> grey = trace(*groundTruth, g, sun, options);
        EXPECT_EQ(grey[0], glm::vec3(0.0f));
        EXPECT_EQ(grey[1], glm::vec3(0.0f));
        EXPECT_EQ(grey[2], glm::vec3(1.0f));
        EXPECT_EQ(grey[4], glm::vec3(1.0f));
    }
}

// The closed form of every translucency model: white light (a sun straight down) through one
// translucent quad of alpha a and transmission t onto a plane gives exactly the model's factor
// inside the quad's shadow and 1 outside; two stacked quads give its square.
TEST(GroundTruth, TranslucencyModelsMatchTheirClosedForm) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    const float a = 0.6f;
    const glm::vec3 t(0.25f, 0.5f, 1.0f);
    struct Expected {
        TranslucencyModel model;
        glm::vec3 factor;
    };
    const Expected expected[] = {
        {TranslucencyModel::Opaque, glm::vec3(0.0f)},
        {TranslucencyModel::Coverage, glm::vec3(1.0f - a)},
        {TranslucencyModel::Physical, (1.0f - a) + a * t},
        {TranslucencyModel::ModifiedTranslucent, (1.0f - a) * t},
        {TranslucencyModel::Ignore, glm::vec3(1.0f)},
    };
    for (int layers = 1; layers <= 2; ++layers) {
        Scene scene = planeScene();
        scene.materials.push_back({.name = "glass", .alpha = a, .transmission = t});
        scene.meshes.push_back(makePlane(2.0f, 2.0f, 1));
        for (int k = 0; k < layers; ++k) {
            SceneObject quad;
            quad.name = "quad";
            quad.mesh = 1;
            quad.material = 1;
            quad.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f + 0.5f * float(k), 0.0f));
            scene.objects.push_back(quad);
        }
        groundTruth->setScene(scene);
        // Inside the shadow (the quad spans x, z in [-1, 1]) and outside it.
        GBuffer g = groundGrid(-0.9f, -0.9f, 0.45f, 5, 5);
        for (glm::vec3 p : {glm::vec3(1.2f, 0, 0), glm::vec3(-3, 0, 2), glm::vec3(0, 0, -1.1f)}) {
            g.positions.emplace_back(p, 1.0f);
            g.normals.emplace_back(0.0f, 1.0f, 0.0f, 0.0f);
        }
        g.width = static_cast<int>(g.positions.size());
        g.height = 1;
        for (const Expected& e : expected)
            for (int soft = 0; soft < 2; ++soft) {
                ReferenceOptions options;
                options.model = e.model;
                options.mode = soft ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
                options.samplesPerPixel = 16;
                // Inside points lie 0.1 or more inside the quad's edge, further than the soft cone
                // (0.5 degrees) reaches from 1.5 up (0.013): wholly under it.
                const std::vector<glm::vec3> v = trace(*groundTruth, g, directional({0.0f, -1.0f, 0.0f}, 0.0087f), options);
                const glm::vec3 inside = layers == 1 ? e.factor : e.factor * e.factor;
                for (int i = 0; i < 25; ++i)
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(v[size_t(i)][c], inside[c], 1e-6f)
                            << translucencyModelName(e.model) << ", " << layers << " layer(s), point " << i << ", channel " << c;
                for (int i = 25; i < g.width; ++i)
                    EXPECT_EQ(v[size_t(i)], glm::vec3(1.0f)) << translucencyModelName(e.model) << ": outside the shadow";
            }
    }
}

// A quad textured with two texels (red glass of alpha 0.4, then blue glass of alpha 0.8) over
// x in [-1, 1]: the reference samples the texel the GPU samples, bilinearly with repeat wrapping.
// Under u = 0.25 and 0.75 (the texel centres) each texel's own factor, under u = 0.5 and at the
// wrapped edge u = 0 the factor of their mean, for every model.
TEST(GroundTruth, TransmissionTextureIsSampledBilinearly) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    Scene scene = planeScene();
    scene.textures.push_back({"two texels", 2, 1, {255, 0, 0, 102, 0, 0, 255, 204}});
    Material glass{.name = "glass", .alpha = 0.5f, .transmission = glm::vec3(0.5f)};
    glass.transmissionTexture = 0;
    scene.materials.push_back(glass);
    scene.meshes.push_back(makePlane(2.0f, 2.0f, 1));   // u = (x + 1) / 2
    SceneObject quad;
    quad.name = "quad";
    quad.mesh = 1;
    quad.material = 1;
    quad.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.objects.push_back(quad);
    groundTruth->setScene(scene);

    const float us[] = {0.25f, 0.75f, 0.5f, 0.001f, 0.125f};
    GBuffer g;
    g.width = 5;
    g.height = 1;
    for (float u : us) {
        g.positions.emplace_back(2.0f * u - 1.0f, 0.0f, 0.1f, 1.0f);
        g.normals.emplace_back(0.0f, 1.0f, 0.0f, 0.0f);
    }
    const glm::vec4 red(1.0f, 0.0f, 0.0f, 102.0f / 255.0f), blue(0.0f, 0.0f, 1.0f, 204.0f / 255.0f);
    auto texelAt = [&](float u) {   // the closed form of the bilinear filter on two texels with repeat
        const float w = u < 0.25f ? 0.25f - u : u <= 0.75f ? (u - 0.25f) * 2.0f : 1.0f - (u - 0.75f) * 2.0f;
        return u < 0.25f ? glm::mix(red, blue, 2.0f * w) : glm::mix(red, blue, w);
    };
    for (TranslucencyModel model : {TranslucencyModel::Coverage, TranslucencyModel::Physical, TranslucencyModel::ModifiedTranslucent}) {
        ReferenceOptions options;
        options.model = model;
        const std::vector<glm::vec3> v = trace(*groundTruth, g, directional({0.0f, -1.0f, 0.0f}), options);
        for (size_t i = 0; i < std::size(us); ++i) {
            const glm::vec4 texel = texelAt(us[i]);
            const glm::vec3 expected = crossingFactor(model, texel.a, glm::vec3(texel));
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(v[i][c], expected[c], 2e-3f) << translucencyModelName(model) << " at u = " << us[i] << ", channel " << c;
        }
        if (model == TranslucencyModel::Physical) {
            EXPECT_NEAR(v[0].r, 1.0f, 1e-5f) << "red glass lets red through";
            EXPECT_NEAR(v[0].b, 0.6f, 1e-5f);
            EXPECT_NEAR(v[1].b, 1.0f, 1e-5f);
            EXPECT_NEAR(v[1].r, 0.2f, 1e-5f);
        }
    }
}

TEST(GroundTruth, InstancedMeshesCastLikeFlattenedOnes) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    // Two objects share the box mesh (instanced), a third has its own (flattened).
    Scene scene = planeScene();
    scene.meshes.push_back(makeBox(glm::vec3(1.0f)));
    scene.meshes.push_back(makeBox(glm::vec3(1.0f)));
    for (int k = 0; k < 3; ++k) {
        SceneObject box;
        box.name = "box" + std::to_string(k);
        box.mesh = k < 2 ? 1 : 2;
        box.transform = glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f + 3.0f * static_cast<float>(k), 0.5f, 0.0f));
        scene.objects.push_back(box);
    }
    groundTruth->setScene(scene);
    const LightInfo sun = directional({0.0f, -1.0f, 0.0f});
    // Points under each box's top (y = 1) and beside it.
    GBuffer g = groundGrid(-3.0f, 0.0f, 1.5f, 5, 1);
    for (glm::vec4& p : g.positions) p.y = 0.0f;
    const std::vector<glm::vec3> v = trace(*groundTruth, g, sun);
    EXPECT_EQ(v[0], glm::vec3(0.0f));
    EXPECT_EQ(v[1], glm::vec3(1.0f));
    EXPECT_EQ(v[2], glm::vec3(0.0f));
    EXPECT_EQ(v[3], glm::vec3(1.0f));
    EXPECT_EQ(v[4], glm::vec3(0.0f));

    // Primary hits on instanced boxes report world-space points and normals.
    View view;
    view.eye = glm::vec3(-3.0f, 5.0f, 0.01f);
    view.target = glm::vec3(-3.0f, 0.0f, 0.0f);
    const GBuffer top = primary(*groundTruth, view);
    const size_t centre = static_cast<size_t>(view.height / 2) * static_cast<size_t>(view.width) + static_cast<size_t>(view.width / 2);
    EXPECT_NEAR(top.positions[centre].y, 1.0f, 1e-4f);
    EXPECT_NEAR(top.positions[centre].x, -3.0f, 0.05f);
    EXPECT_NEAR(top.normals[centre].y, 1.0f, 1e-5f);
}

// --- the soft reference's own error, and adaptive sampling -----------------------------------

namespace {

// A sphere of radius 0.5 centred 1.2 above the ground (no contact) under a sun of angular radius
// 4 degrees, seen top-down by a grid of ground points 0.015 apart around its shadow: the
// penumbra is about 12 samples wide.
constexpr float kSunRadius = 4.0f * std::numbers::pi_v<float> / 180.0f;
const glm::vec3 kSphereCentre(0.0f, 1.2f, 0.0f);
constexpr float kSphereRadius = 0.5f;

struct SphereSetup {
    Scene scene;
    LightInfo sun;
    GBuffer ground;
    std::vector<uint8_t> mask;
    std::vector<glm::vec3> exact; // closed form, per ground point
};

// Solid angle of the intersection of two spherical caps of angular radii a and b whose centres
// are g apart (on the unit sphere).
double capIntersection(double a, double b, double g) {
    if (g >= a + b) return 0.0;
    if (g <= std::abs(a - b)) return 2.0 * std::numbers::pi * (1.0 - std::cos(std::min(a, b)));
    auto arc = [](double x) { return std::acos(std::clamp(x, -1.0, 1.0)); };
    const double ca = std::cos(a), cb = std::cos(b), cg = std::cos(g);
    const double sa = std::sin(a), sb = std::sin(b), sg = std::sin(g);
    return 2.0 * (std::numbers::pi - arc((cg - ca * cb) / (sa * sb)) - arc((cb - cg * ca) / (sg * sa)) * ca -
                  arc((ca - cg * cb) / (sg * sb)) * cb);
}

// Closed-form visibility of a ground point p: the fraction of the sun's cap (uniform in solid
// angle, as the reference samples it) not covered by the cap the sphere subtends from p.
float exactSphereVisibility(glm::dvec3 p, glm::dvec3 toSun, double sunRadius) {
    const glm::dvec3 toCentre = glm::dvec3(kSphereCentre) - p;
    const double distance = glm::length(toCentre);
    const double sphere = std::asin(static_cast<double>(kSphereRadius) / distance);
    const double separation = std::acos(std::clamp(glm::dot(toCentre / distance, toSun), -1.0, 1.0));
    const double cap = 2.0 * std::numbers::pi * (1.0 - std::cos(sunRadius));
    return static_cast<float>(1.0 - capIntersection(sunRadius, sphere, separation) / cap);
}

// `rayOffset`: where the reference's rays start, above the ground point (IGroundTruth::rayOffset).
// The closed form is taken there too: 0.003 higher (this scene's offset) the shadow is 0.001
// to the side, a visibility difference of about 0.004 over this penumbra, larger than the
// sampling error the tests measure.
SphereSetup sphereUnderSun(float rayOffset) {
    SphereSetup s;
    s.scene = planeScene();
    s.scene.meshes.push_back(makeSphere(kSphereRadius, 256, 128)); // silhouette within 4e-5 of the sphere
    SceneObject sphere;
    sphere.name = "sphere";
    sphere.mesh = 1;
    sphere.transform = glm::translate(glm::mat4(1.0f), kSphereCentre);
    s.scene.objects.push_back(sphere);
    s.sun = directional({0.3f, -1.0f, 0.2f}, kSunRadius);
    // The shadow's centre on the ground, and a 160 x 96 grid around it.
    const glm::vec3 centre = kSphereCentre + s.sun.direction * (-kSphereCentre.y / s.sun.direction.y);
    const float step = 0.015f;
    s.ground = groundGrid(centre.x - 80.0f * step, centre.z - 48.0f * step, step, 160, 96);
    s.mask = compareMask(s.ground.view(), s.sun);
    for (const glm::vec4& p : s.ground.positions)
        s.exact.emplace_back(exactSphereVisibility(glm::dvec3(p) + glm::dvec3(0.0, rayOffset, 0.0),
                                                   -glm::dvec3(s.sun.direction), kSunRadius));
    return s;
}

ReferenceOptions softOptions(int samples, bool adaptive) {
    ReferenceOptions options;
    options.mode = ReferenceOptions::Mode::Soft;
    options.samplesPerPixel = samples;
    options.adaptive = adaptive;
    return options;
}

struct SoftRun {
    std::vector<glm::vec3> image;
    ReferenceStats stats;
    double floor = 0.0;             // estimated: penumbraMean of the per-pixel sampling error
    AccuracyMetrics againstExact;   // the closed form as the reference
};

SoftRun runSoft(IGroundTruth& groundTruth, const SphereSetup& s, const ReferenceOptions& options) {
    SoftRun run;
    groundTruth.trace(s.ground.view(), s.sun, options, run.image, &run.stats);
    run.floor = penumbraMean(run.stats.sampleError, run.image, s.mask, s.ground.width, s.ground.height);
    run.againstExact = compareVisibility(run.image, s.exact, s.mask, s.ground.width, s.ground.height);
    return run;
}

} // namespace

// The closed form itself: umbra under the sphere's centre, open ground far away, partial values
// on a ring, and the 1024-ray reference close to it.
TEST(GroundTruthSoftError, SphereClosedFormHasUmbraPenumbraAndLitGround) {
    const SphereSetup s = sphereUnderSun(0.0f);
    const size_t centre = 48u * 160u + 80u;
    EXPECT_EQ(s.exact[centre].x, 0.0f);
    EXPECT_EQ(s.exact[0].x, 1.0f);
    size_t partial = 0;
    for (const glm::vec3& v : s.exact) partial += v.x > 0.02f && v.x < 0.98f;
    EXPECT_GT(partial, 1500u);
    EXPECT_LT(partial, 6000u);
}

// (c) The floor: the per-pixel estimate averaged over the penumbra is about 0.014 at 64 uniform
// rays and 0.0025 at 1024, and within 1.5x of the error actually measured against the closed form.
TEST(GroundTruthSoftError, FloorEstimateMatchesTheMeasuredError) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(sphereUnderSun(0.0f).scene);
    const SphereSetup s = sphereUnderSun(groundTruth->rayOffset());
    const SoftRun low = runSoft(*groundTruth, s, softOptions(64, false));
    const SoftRun high = runSoft(*groundTruth, s, softOptions(1024, false));
    const double lowError = low.againstExact.maePenumbra, highError = high.againstExact.maePenumbra;
    std::printf("[ floor    ] 64 rays: measured %.5f, estimated %.5f; 1024 rays: measured %.5f, estimated %.5f\n",
                lowError, low.floor, highError, high.floor);
    EXPECT_EQ(low.stats.samplesPerPixel, 64);
    EXPECT_EQ(high.stats.samplesPerPixel, 1024);
    EXPECT_FALSE(high.stats.adaptive);
    EXPECT_EQ(high.stats.refinedPixels, high.stats.tracedPixels);
    EXPECT_GT(low.floor, 0.014 / 1.5);
    EXPECT_LT(low.floor, 0.014 * 1.5);
    EXPECT_GT(high.floor, 0.0025 / 1.5);
    EXPECT_LT(high.floor, 0.0025 * 1.5);
    EXPECT_GT(low.floor, lowError / 1.5);
    EXPECT_LT(low.floor, lowError * 1.5);
    EXPECT_GT(high.floor, highError / 1.5);
    EXPECT_LT(high.floor, highError * 1.5);
    EXPECT_LT(highError, lowError / 4.0) << "1024 stratified rays: at least 4x below 64";
}

// (a) and (b): adaptive 1024 rays equals uniform 1024 where it refined (bit for bit), keeps 0 or 1
// elsewhere, stays within the uniform estimate's own noise over the penumbra, and is as close to
// the closed-form shadow as the uniform reference.
TEST(GroundTruthSoftError, AdaptiveMatchesUniformAndTheClosedForm) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(sphereUnderSun(0.0f).scene);
    const SphereSetup s = sphereUnderSun(groundTruth->rayOffset());
    const SoftRun uniform = runSoft(*groundTruth, s, softOptions(1024, false));
    const SoftRun adaptive = runSoft(*groundTruth, s, softOptions(1024, true));
    EXPECT_TRUE(adaptive.stats.adaptive);
    EXPECT_EQ(adaptive.stats.firstBatch, 32);
    EXPECT_EQ(adaptive.stats.tracedPixels, uniform.stats.tracedPixels);
    EXPECT_LT(adaptive.stats.refinedPixels, adaptive.stats.tracedPixels);
    EXPECT_LT(adaptive.stats.shadowRays, uniform.stats.shadowRays / 2);

    size_t refined = 0, stopped = 0, stoppedDiffering = 0;
    double largestStoppedDifference = 0.0;
    for (size_t i = 0; i < s.mask.size(); ++i) {
        if (!s.mask[i]) continue;
        const glm::vec3 a = adaptive.image[i], u = uniform.image[i];
        if (adaptive.stats.sampleError[i] > 0.0f || (a.x > 0.0f && a.x < 1.0f)) {
            ++refined;
            EXPECT_EQ(a, u) << "a refined pixel is the uniform estimate, bit for bit (pixel " << i << ")";
            continue;
        }
        ++stopped;
        EXPECT_TRUE(a == glm::vec3(0.0f) || a == glm::vec3(1.0f)) << "a stopped pixel is unanimous";
        if (a != u) {
            ++stoppedDiffering;
            largestStoppedDifference = std::max(largestStoppedDifference, static_cast<double>(std::abs(a.x - u.x)));
        }
    }
    EXPECT_GT(refined, 1000u);
    EXPECT_GT(stopped, 5000u);
    const AccuracyMetrics againstUniform = compareVisibility(adaptive.image, uniform.image, s.mask, s.ground.width, s.ground.height);
    std::printf("[ adaptive ] refined %.1f%%, %.1f rays per pixel; vs uniform: penumbra MAE %.6f, %zu stopped pixels "
                "differ (largest %.4f); vs closed form: adaptive %.5f, uniform %.5f (floor %.5f)\n",
                100.0 * double(adaptive.stats.refinedPixels) / double(adaptive.stats.tracedPixels),
                double(adaptive.stats.shadowRays) / double(adaptive.stats.tracedPixels), againstUniform.maePenumbra,
                stoppedDiffering, largestStoppedDifference, adaptive.againstExact.maePenumbra,
                uniform.againstExact.maePenumbra, uniform.floor);
    EXPECT_LT(againstUniform.maePenumbra, uniform.floor) << "(a) within the uniform reference's own noise";
    EXPECT_LT(largestStoppedDifference, 0.02) << "a stopped pixel misses at most a sliver of the emitter";
    // (b) against the closed form: no worse than the 1024-ray floor plus 0.001.
    EXPECT_LT(adaptive.againstExact.maePenumbra, uniform.floor + 0.001);
    EXPECT_LT(adaptive.againstExact.maeOutsidePenumbra, 0.001);
    EXPECT_NEAR(adaptive.againstExact.maePenumbra, uniform.againstExact.maePenumbra, 0.0005);
}

// (d) Mostly lit or shadowed: the box under a 4 degree sun seen by the test camera. Few pixels
// are refined, the rays per pixel stay near the first batch, the image does not depend on the
// thread count, and a stopped pixel of the first batch is the uniform value where the uniform
// reference is 0 or 1.
TEST(GroundTruthSoftError, AdaptiveRefinesFewPixelsAndIsDeterministic) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(boxOnPlane());
    View view;
    view.width = 160;
    view.height = 120;
    const GBuffer g = primary(*groundTruth, view);
    const LightInfo sun = directional({0.5f, -1.0f, 0.35f}, kSunRadius);
    ReferenceOptions options = softOptions(1024, true);
    options.threads = 1;
    ReferenceStats stats;
    std::vector<glm::vec3> one;
    groundTruth->trace(g.view(), sun, options, one, &stats);
    const double refined = double(stats.refinedPixels) / double(stats.tracedPixels);
    const double raysPerPixel = double(stats.shadowRays) / double(stats.tracedPixels);
    std::printf("[ adaptive ] box: %.1f%% of %zu pixels refined, %.1f rays per pixel\n", 100.0 * refined,
                stats.tracedPixels, raysPerPixel);
    EXPECT_GT(stats.tracedPixels, 10000u);
    EXPECT_GT(refined, 0.01);
    EXPECT_LT(refined, 0.2);
    EXPECT_LT(raysPerPixel, 32.0 + 0.2 * 1056.0);
    options.threads = 3;
    EXPECT_TRUE(identical(one, trace(*groundTruth, g, sun, options)));
    options.threads = 0;
    EXPECT_TRUE(identical(one, trace(*groundTruth, g, sun, options)));

    // Turning adaptivity off, or a first batch as large as N, gives the uniform reference.
    const std::vector<glm::vec3> uniform = trace(*groundTruth, g, sun, softOptions(1024, false));
    ReferenceOptions whole = softOptions(1024, true);
    whole.firstBatch = 1024;
    ReferenceStats wholeStats;
    std::vector<glm::vec3> wholeImage;
    groundTruth->trace(g.view(), sun, whole, wholeImage, &wholeStats);
    EXPECT_FALSE(wholeStats.adaptive);
    EXPECT_TRUE(identical(uniform, wholeImage));
    size_t differing = 0;
    for (size_t i = 0; i < one.size(); ++i) differing += one[i] != uniform[i];
    EXPECT_LT(differing, stats.tracedPixels / 200) << "stopped pixels are nearly always exactly the uniform value";
}

TEST(GroundTruthSoftError, HardReferenceHasNoSamplingError) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(boxOnPlane());
    const GBuffer g = primary(*groundTruth, View{});
    ReferenceStats stats;
    std::vector<glm::vec3> v;
    groundTruth->trace(g.view(), directional({0.5f, -1.0f, 0.35f}, kSunRadius), ReferenceOptions{}, v, &stats);
    EXPECT_EQ(stats.samplesPerPixel, 1);
    EXPECT_TRUE(stats.sampleError.empty());
    EXPECT_EQ(stats.refinedPixels, stats.tracedPixels);
    EXPECT_GT(stats.tracedPixels, 0u);
}

// A G-buffer texel with a NaN normal or position (a texel no pass wrote, or NaN from a shader)
// faces no light and traces no ray: as a NaN shadow ray, Embree's robust traversal spun forever
// (seen on `point-light`, lispsm evaluated after csm). The other pixels keep their values.
TEST(GroundTruth, NonFiniteGBufferTexelsTraceNoRay) {
    auto groundTruth = loadOrFail();
    ASSERT_TRUE(groundTruth);
    groundTruth->setScene(boxOnPlane());
    GBuffer g = primary(*groundTruth, View{});
    const LightInfo sun = directional({0.5f, -1.0f, 0.35f}, 0.0f);
    std::vector<glm::vec3> clean;
    groundTruth->trace(g.view(), sun, ReferenceOptions{}, clean);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    size_t poisoned = 0;
    std::vector<size_t> lit;
    for (size_t i = 0; i < g.positions.size(); ++i)
        if (clean[i].x == 1.0f && g.positions[i].w != 0.0f) lit.push_back(i);
    ASSERT_GT(lit.size(), 100u);
    for (size_t k = 0; k < lit.size(); k += 7, ++poisoned) {
        if (k % 2) g.normals[lit[k]] = glm::vec4(nan, nan, nan, 0.0f);
        else g.positions[lit[k]].x = nan;
    }
    EXPECT_FALSE(facesLight(glm::vec4(0, 0, 0, 1), glm::vec4(nan, 1, 0, 0), sun));
    std::vector<glm::vec3> traced;
    groundTruth->trace(g.view(), sun, ReferenceOptions{}, traced);   // returns (it hung before)
    size_t changed = 0, dark = 0;
    for (size_t i = 0; i < clean.size(); ++i) changed += traced[i] != clean[i];
    for (size_t k = 0; k < lit.size(); k += 7) dark += traced[lit[k]] == glm::vec3(0.0f);
    EXPECT_EQ(changed, poisoned) << "only the poisoned texels change";
    EXPECT_EQ(dark, poisoned) << "and they trace no light";
}
