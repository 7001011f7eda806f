// The focus body B = ((V n S) + l) n S n L (seed 002 eq. 4.2, recipe of sec. 9.2.2) against bodies
// worked out by hand, seed 000's crop matrix (eq. 3.9-3.10) against its closed form, and texel
// snapping (seed 000 sec. 2.2.5) under sub-texel camera motion. kit/focus.h, no GL.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "shadowlab/kit/lispsm_warp.h"
#include "camera.h"
#include "test_cameras.h"
#include "render/light_space.h"
#include "shadowlab/kit/focus.h"

using namespace shadowlab;

namespace {

const Bounds kScene{{-50, 0, -50}, {50, 20, 50}};

// A camera at `eye` looking along -z (up +y), square, 60 degrees.
CameraInfo cameraLookingDownMinusZ(glm::vec3 eye, float nearPlane, float farPlane) {
    return test::lookAtCamera(eye, eye + glm::vec3(0, 0, -1), nearPlane, farPlane);
}

LightInfo directional(glm::vec3 direction) {
    LightInfo light{};
    light.type = LightType::Directional;
    light.direction = glm::normalize(direction);
    return light;
}

// Every expected corner is a corner of the body and the body has no others.
void expectCorners(const kit::ConvexBody& body, const std::vector<glm::vec3>& expected) {
    const std::vector<glm::vec3> corners = body.corners(1e-4f);
    EXPECT_EQ(corners.size(), expected.size());
    for (const glm::vec3& e : expected) {
        const bool found = std::any_of(corners.begin(), corners.end(), [&](const glm::vec3& c) {
            return glm::distance(c, e) < 2e-3f;
        });
        EXPECT_TRUE(found) << "missing corner (" << e.x << ", " << e.y << ", " << e.z << ")";
    }
    for (const glm::vec3& c : corners) {
        const bool expectedHere = std::any_of(expected.begin(), expected.end(), [&](const glm::vec3& e) {
            return glm::distance(c, e) < 2e-3f;
        });
        EXPECT_TRUE(expectedHere) << "unexpected corner (" << c.x << ", " << c.y << ", " << c.z << ")";
    }
}

// Every corner lies on or inside every face plane: the faces bound a convex body.
void expectConvexAndClosed(const kit::ConvexBody& body) {
    const auto planes = kit::inwardPlanes(body);
    for (const glm::vec3& c : body.vertices())
        for (const glm::vec4& p : planes) EXPECT_GE(glm::dot(glm::vec3(p), c) + p.w, -1e-3f);
    // Closed: the face area vectors of a closed surface sum to zero.
    glm::vec3 sum(0.0f);
    for (const auto& face : body.faces) sum += kit::focus_detail::areaNormal(face);
    EXPECT_LT(glm::length(sum), 1e-2f);
}

constexpr float kTan30 = 0.57735027f;

} // namespace

// A camera inside the scene looking horizontally, the sun straight above: V (near 1, far 8, inside
// S) swept up to the scene's top y = 20. Seen from above V's outline is the trapezoid of its near
// and far edges, so B is V's bottom face (4 corners) below that trapezoid lifted to y = 20.
TEST(FocusBody, CameraInsideSceneLightStraightDown) {
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 8.0f);
    const kit::ConvexBody body = kit::focusBody(camera, directional({0, -1, 0}), kScene, LightSpace{});
    const float n = kTan30, f = 8.0f * kTan30;
    expectCorners(body, {{-n, 5 - n, -1}, {n, 5 - n, -1}, {-f, 5 - f, -8}, {f, 5 - f, -8},
                         {-n, 20, -1}, {n, 20, -1}, {-f, 20, -8}, {f, 20, -8}});
    expectConvexAndClosed(body);
    for (const glm::vec3& corner : camera.frustumCorners) EXPECT_TRUE(kit::contains(body, corner));
    EXPECT_FALSE(kit::contains(body, {0, 2, -4})) << "below V: nothing there shadows the view";
    EXPECT_TRUE(kit::contains(body, {0, 19, -4})) << "above V: a caster there shadows it";
}

// The light travelling along the view direction (from behind the camera): V swept backwards
// towards the light. Along the view axis V's outline is its far rectangle, so B is the box from
// the far plane back to the scene's side z = 50 behind the camera.
TEST(FocusBody, LightParallelToTheViewDirection) {
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 8.0f);
    const kit::ConvexBody body = kit::focusBody(camera, directional({0, 0, -1}), kScene, LightSpace{});
    const float f = 8.0f * kTan30;
    expectCorners(body, {{-f, 5 - f, -8}, {f, 5 - f, -8}, {-f, 5 + f, -8}, {f, 5 + f, -8},
                         {-f, 5 - f, 50}, {f, 5 - f, 50}, {-f, 5 + f, 50}, {f, 5 + f, 50}});
    expectConvexAndClosed(body);
}

// A point light 3 behind the camera on its axis: every face of V but the far one faces it, so the
// hull is the pyramid from the light to V's far rectangle. L (the light's frustum looking along
// -z, near 0.1) cuts its apex: B is the pyramid from z = 2.9 to the far plane, where its cross
// section is the far rectangle scaled by 0.1 / 11 about the axis.
TEST(FocusBody, PointLightBehindTheCamera) {
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 8.0f);
    LightInfo light{};
    light.type = LightType::Point;
    light.position = {0, 5, 3};
    LightSpace lightSpace{};
    lightSpace.view = glm::lookAt(light.position, light.position + glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
    lightSpace.projection = glm::perspective(glm::radians(120.0f), 1.0f, 0.1f, 100.0f);
    lightSpace.viewProjection = lightSpace.projection * lightSpace.view;
    lightSpace.perspective = true;
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, lightSpace);
    const float f = 8.0f * kTan30, a = f * 0.1f / 11.0f;
    expectCorners(body, {{-f, 5 - f, -8}, {f, 5 - f, -8}, {-f, 5 + f, -8}, {f, 5 + f, -8},
                         {-a, 5 - a, 2.9f}, {a, 5 - a, 2.9f}, {-a, 5 + a, 2.9f}, {a, 5 + a, 2.9f}});
    expectConvexAndClosed(body);
    for (const glm::vec3& corner : camera.frustumCorners) EXPECT_TRUE(kit::contains(body, corner));
}

// V reaching out of S (far 100 in a 100 m scene, below the ground too) is cut to S first (eq. 4.2's
// improvement over 4.1), and B stays inside S; every visible point of S swept towards the light
// until it leaves S lies in B.
TEST(FocusBody, ClippedToTheSceneAndHoldsEverySweptVisiblePoint) {
    const CameraInfo camera = cameraLookingDownMinusZ({3, 4, 10}, 0.5f, 100.0f);
    const LightInfo light = directional({-0.4f, -1.0f, 0.3f});
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    ASSERT_FALSE(body.empty());
    expectConvexAndClosed(body);
    float minZ = 1e30f;
    for (const glm::vec3& c : body.vertices()) {
        EXPECT_TRUE(glm::all(glm::greaterThanEqual(c, kScene.min - 1e-3f)) &&
                    glm::all(glm::lessThanEqual(c, kScene.max + 1e-3f)));
        minZ = std::min(minZ, c.z);
    }
    EXPECT_NEAR(minZ, -50.0f, 1e-3f) << "the far part of V outside S is gone";

    std::mt19937 rng(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int tested = 0;
    for (int i = 0; i < 4000; ++i) {
        // A random point of V (trilinear in its corners), kept if it is in S.
        const glm::vec3 t(unit(rng), unit(rng), unit(rng));
        const glm::vec3* c = camera.frustumCorners;
        auto lerp = [](glm::vec3 a, glm::vec3 b, float s) { return a + (b - a) * s; };
        const glm::vec3 p = lerp(lerp(lerp(c[0], c[1], t.x), lerp(c[2], c[3], t.x), t.y),
                                 lerp(lerp(c[4], c[5], t.x), lerp(c[6], c[7], t.x), t.y), t.z);
        if (glm::any(glm::lessThan(p, kScene.min)) || glm::any(glm::greaterThan(p, kScene.max))) continue;
        ++tested;
        EXPECT_TRUE(kit::contains(body, p, 1e-3f));
        const glm::vec3 towardsLight = p - light.direction * (unit(rng) * 200.0f);
        if (glm::all(glm::greaterThanEqual(towardsLight, kScene.min)) && glm::all(glm::lessThanEqual(towardsLight, kScene.max))) {
            EXPECT_TRUE(kit::contains(body, towardsLight, 1e-3f));
        }
    }
    EXPECT_GT(tested, 500);
    // Behind the camera and away from the light, nothing can shadow the view.
    EXPECT_FALSE(kit::contains(body, {3, 1, 30}));
}

TEST(FocusBody, EmptyWhenTheCameraSeesNothingOfTheScene) {
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, -80}, 0.5f, 20.0f);   // outside, looking away
    EXPECT_TRUE(kit::focusBody(camera, directional({0, -1, 0}), kScene, LightSpace{}).empty());
    const LightSpace sceneFit = fitLightSpace(directional({0, -1, 0}), kScene);
    const kit::FocusedLightSpace focused =
        kit::focusLightSpace(sceneFit, camera, directional({0, -1, 0}), kScene, {kit::Fit::FocusBody, true}, 2048);
    EXPECT_EQ(focused.light.viewProjection, sceneFit.viewProjection) << "falls back to the scene fit";
    EXPECT_TRUE(focused.cullPlanes.empty());
}

// Clipping a box by a plane through it gives the hand-computed half box.
TEST(FocusBody, ClipByPlaneClosesTheHole) {
    kit::ConvexBody box = kit::boxBody({{0, 0, 0}, {2, 2, 2}});
    kit::clip(box, glm::vec4(-1, -1, 0, 2));   // keep x + y <= 2: a triangular prism
    expectCorners(box, {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}, {2, 0, 2}, {0, 2, 2}});
    expectConvexAndClosed(box);
    EXPECT_EQ(box.faces.size(), 5u);
    kit::clip(box, glm::vec4(0, 0, 1, 5));     // all inside: unchanged
    EXPECT_EQ(box.faces.size(), 5u);
    kit::clip(box, glm::vec4(0, 0, 1, -5));    // all outside: empty
    EXPECT_TRUE(box.empty());
}

// ---------------------------------------------------------------------------------------------

// F of eq. 3.9-3.10, entry by entry, and what it does: the window onto [-1, 1].
TEST(CropMatrix, MatchesEquations3_9And3_10) {
    const kit::CropWindow window{{-0.5f, -0.2f}, {0.3f, 0.6f}};
    const glm::mat4 f = kit::cropMatrix(window);
    // s = 2 / (max - min) = 2.5 on both axes; o_x = -2.5 * (-0.2) / 2 = 0.25, o_y = -2.5 * 0.4 / 2 = -0.5.
    const float expected[4][4] = {{2.5f, 0, 0, 0.25f}, {0, 2.5f, 0, -0.5f}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) EXPECT_FLOAT_EQ(f[col][row], expected[row][col]) << row << "," << col;
    const glm::vec4 lo = f * glm::vec4(-0.5f, -0.2f, 0.3f, 1.0f), hi = f * glm::vec4(0.3f, 0.6f, -0.7f, 1.0f);
    EXPECT_FLOAT_EQ(lo.x, -1.0f);
    EXPECT_FLOAT_EQ(lo.y, -1.0f);
    EXPECT_FLOAT_EQ(hi.x, 1.0f);
    EXPECT_FLOAT_EQ(hi.y, 1.0f);
    EXPECT_FLOAT_EQ(lo.z, 0.3f) << "depth untouched";
}

// The frustum fit of seed 000 sec. 3.2.3 with a hand-built light straight down over the scene:
// ortho(+-50) from y = 30 with up -z, so NDC x = x / 50 and NDC y = -z / 50.
TEST(CropMatrix, FrustumCornersInLightNdcClampedToTheMap) {
    LightSpace light{};
    light.view = glm::lookAt(glm::vec3(0, 30, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
    light.projection = glm::ortho(-50.0f, 50.0f, -50.0f, 50.0f, 1.0f, 40.0f);
    light.viewProjection = light.projection * light.view;
    light.worldSizeAtUnitDepth = {100, 100};
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 8.0f);
    const std::vector<glm::vec3> corners(camera.frustumCorners, camera.frustumCorners + 8);
    const kit::CropWindow window = kit::cropWindow(light.viewProjection, corners);
    const float f = 8.0f * kTan30;
    EXPECT_NEAR(window.min.x, -f / 50.0f, 1e-5f);
    EXPECT_NEAR(window.max.x, f / 50.0f, 1e-5f);
    EXPECT_NEAR(window.min.y, 1.0f / 50.0f, 1e-5f);   // near plane z = -1
    EXPECT_NEAR(window.max.y, 8.0f / 50.0f, 1e-5f);   // far plane z = -8
    // F P V: the frustum fills the map in x and y, depth as the uncropped map's.
    const LightSpace cropped = kit::cropLightSpace(light, window);
    EXPECT_NEAR(cropped.worldSizeAtUnitDepth.x, 2.0f * f, 1e-3f);
    EXPECT_NEAR(cropped.worldSizeAtUnitDepth.y, 7.0f, 1e-3f);
    const glm::vec4 farRight = cropped.viewProjection * glm::vec4(f, 5, -8, 1);
    EXPECT_NEAR(farRight.x, 1.0f, 1e-4f);
    EXPECT_NEAR(farRight.y, 1.0f, 1e-4f);
    EXPECT_NEAR(farRight.z, (light.viewProjection * glm::vec4(f, 5, -8, 1)).z, 1e-6f);

    // A far plane at 100 reaches out of the map: clamped to [-1, 1].
    const CameraInfo far = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 100.0f);
    const kit::CropWindow clamped =
        kit::cropWindow(light.viewProjection, std::vector<glm::vec3>(far.frustumCorners, far.frustumCorners + 8));
    EXPECT_FLOAT_EQ(clamped.min.x, -1.0f);
    EXPECT_FLOAT_EQ(clamped.max.x, 1.0f);
    EXPECT_NEAR(clamped.min.y, 0.02f, 1e-5f);
    EXPECT_FLOAT_EQ(clamped.max.y, 1.0f);
}

// ---------------------------------------------------------------------------------------------

// Texel coordinates of fixed world points, in the map of `light` at `resolution`.
std::vector<glm::vec2> texelPositions(const LightSpace& light, int resolution) {
    std::vector<glm::vec2> out;
    for (const glm::vec3 p : {glm::vec3(1.3f, 0.2f, -3.1f), glm::vec3(-2.7f, 1.5f, -6.4f), glm::vec3(0.05f, 0.0f, -5.0f)}) {
        const glm::vec4 c = light.viewProjection * glm::vec4(p, 1.0f);
        out.push_back((glm::vec2(c) / c.w * 0.5f + 0.5f) * float(resolution));
    }
    return out;
}

float fractionalDifference(float a, float b) {
    const float d = std::abs(a - b);
    return std::abs(d - std::round(d));
}

// Moving the camera by fractions of a texel leaves every world point at the same place inside its
// texel in the snapped map (its texel index may change by whole texels), for both fits; without
// snapping the points slide within their texels.
TEST(TexelSnapping, SubTexelCameraTranslationKeepsTheTexelGrid) {
    const int resolution = 2048;
    const LightInfo light = directional({-0.3f, -1.0f, -0.2f});
    const LightSpace sceneFit = fitLightSpace(light, kScene);
    for (const kit::Fit fit : {kit::Fit::Frustum, kit::Fit::FocusBody}) {
        // V inside S, so B's outline in the map does not change under translation.
        const CameraInfo start = cameraLookingDownMinusZ({0, 5, 0}, 0.5f, 8.0f);
        const auto focusAt = [&](glm::vec3 eye, bool snap) {
            return kit::focusLightSpace(sceneFit, cameraLookingDownMinusZ(eye, 0.5f, 8.0f), light, kScene,
                                        {fit, snap}, resolution)
                .light;
        };
        const LightSpace snapped0 = focusAt(start.position, true);
        // The texel's size in world units (x of the map): the map's extent over the resolution.
        const float texelWorld = snapped0.worldSizeAtUnitDepth.x / float(resolution);
        ASSERT_LT(texelWorld, 0.01f) << "the crop is much tighter than the 100 m scene";
        const auto base = texelPositions(snapped0, resolution);
        float unsnappedSlide = 0.0f;
        const auto unsnapped0 = texelPositions(focusAt(start.position, false), resolution);
        for (const float step : {0.13f, 0.37f, 0.5f, 0.81f, 2.29f, 40.6f}) {
            const glm::vec3 eye = start.position + glm::vec3(step, 0.3f * step, -0.6f * step) * texelWorld;
            const LightSpace snapped = focusAt(eye, true);
            EXPECT_NEAR(snapped.worldSizeAtUnitDepth.x, snapped0.worldSizeAtUnitDepth.x, 1e-4f) << "size quantised";
            const auto moved = texelPositions(snapped, resolution);
            for (size_t i = 0; i < base.size(); ++i) {
                EXPECT_LT(fractionalDifference(moved[i].x, base[i].x), 2e-3f) << int(fit) << " step " << step;
                EXPECT_LT(fractionalDifference(moved[i].y, base[i].y), 2e-3f) << int(fit) << " step " << step;
            }
            const auto unsnapped = texelPositions(focusAt(eye, false), resolution);
            for (size_t i = 0; i < base.size(); ++i)
                unsnappedSlide = std::max(unsnappedSlide, fractionalDifference(unsnapped[i].x, unsnapped0[i].x));
        }
        EXPECT_GT(unsnappedSlide, 0.1f) << "without snapping the grid slides (the test can fail)";
    }
}

// The snapped window holds the raw one, stays in the map, and its size is a whole number of
// texels of a grid that divides [-1, 1] into a whole number of texels.
TEST(TexelSnapping, SnappedWindowHoldsTheRawOne) {
    const int resolution = 1024;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        // Windows of 2% of the map or more: in float, a window's edges hold about 1e-7 of the
        // map, so for a window of 1024 texels of a grid of 100,000 (1%) that is 0.01 texel.
        std::uniform_real_distribution<float> size(0.02f, 1.6f);
        const glm::vec2 lo(coord(rng), coord(rng));
        const kit::CropWindow raw{lo, lo + glm::vec2(size(rng), size(rng))};
        const kit::CropWindow snapped = kit::snapToTexels(raw, resolution);
        for (int axis = 0; axis < 2; ++axis) {
            EXPECT_LE(snapped.min[axis], raw.min[axis] + 1e-6f);
            EXPECT_GE(snapped.max[axis], std::min(raw.max[axis], 1.0f) - 1e-6f);
            EXPECT_GE(snapped.min[axis], -1.0f - 1e-6f);
            EXPECT_LE(snapped.max[axis], 1.0f + 1e-6f);
            const double texel = double(snapped.max[axis] - snapped.min[axis]) / resolution;
            const double across = 2.0 / texel;   // texels across the whole map
            EXPECT_NEAR(across, std::round(across), 1e-2 * across / resolution);
            const double offset = (double(snapped.min[axis]) + 1.0) / texel;
            EXPECT_NEAR(offset, std::round(offset), 1e-2);
        }
    }
}

// The cull planes bound what the map covers: a caster box under the visible ground is kept, one
// behind the camera out of the light's way is culled.
TEST(FocusBody, CullPlanesKeepCastersOfTheViewOnly) {
    const LightInfo light = directional({0, -1, 0});
    const LightSpace sceneFit = fitLightSpace(light, kScene);
    const CameraInfo camera = cameraLookingDownMinusZ({0, 1.5f, 0}, 1.0f, 8.0f);   // V reaches the ground
    for (const kit::Fit fit : {kit::Fit::Frustum, kit::Fit::FocusBody}) {
        const auto focused = kit::focusLightSpace(sceneFit, camera, light, kScene, {fit, false}, 2048);
        ASSERT_FALSE(focused.cullPlanes.empty());
        auto kept = [&](const Bounds& box) {
            for (const glm::vec4& p : focused.cullPlanes) {
                const glm::vec3 n(p);
                const glm::vec3 far{n.x >= 0 ? box.max.x : box.min.x, n.y >= 0 ? box.max.y : box.min.y,
                                    n.z >= 0 ? box.max.z : box.min.z};
                if (glm::dot(n, far) + p.w < 0.0f) return false;
            }
            return true;
        };
        EXPECT_TRUE(kept({{-0.5f, 0, -5}, {0.5f, 1, -4}})) << "tree in view";
        EXPECT_TRUE(kept({{-0.5f, 15, -5}, {0.5f, 18, -4}})) << "cloud above the view casts into it";
        EXPECT_FALSE(kept({{-0.5f, 0, 20}, {0.5f, 1, 21}})) << "tree behind the camera";
        EXPECT_FALSE(kept({{30, 0, -5}, {31, 1, -4}})) << "tree far to the side";
        EXPECT_TRUE(kept({{-50, 0, -50}, {50, 0, 50}})) << "the ground under the view (on S's bottom face)";
    }
}

// A spot light over part of the view: B is cut to its cone L, and the crop of its perspective map
// (an off-axis part of the cone's frustum) holds B in [-1, 1] while being smaller than the cone.
TEST(FocusBody, SpotLightBodyIsCutToItsConeAndCropped) {
    LightInfo spot{};
    spot.type = LightType::Spot;
    spot.position = {0, 15, -4};
    spot.direction = {0, -1, 0};
    spot.spotOuterAngle = glm::radians(30.0f);
    const LightSpace sceneFit = fitLightSpace(spot, kScene);
    ASSERT_TRUE(sceneFit.perspective);
    const CameraInfo camera = cameraLookingDownMinusZ({5, 2, -2}, 0.5f, 6.0f);   // sees the cone's +x part
    for (const kit::Fit fit : {kit::Fit::Frustum, kit::Fit::FocusBody}) {
        const kit::FocusedLightSpace focused = kit::focusLightSpace(sceneFit, camera, spot, kScene, {fit, false}, 1024);
        EXPECT_LT(focused.light.worldSizeAtUnitDepth.x * focused.light.worldSizeAtUnitDepth.y,
                  0.8f * sceneFit.worldSizeAtUnitDepth.x * sceneFit.worldSizeAtUnitDepth.y)
            << int(fit) << ": the view covers part of the cone only";
        if (fit != kit::Fit::FocusBody) continue;
        ASSERT_FALSE(focused.body.empty());
        expectConvexAndClosed(focused.body);
        for (const glm::vec3& c : focused.body.vertices()) {
            for (const LightSpace* ls : {&sceneFit, &focused.light}) {
                const glm::vec4 clipPos = ls->viewProjection * glm::vec4(c, 1.0f);
                ASSERT_GT(clipPos.w, 0.0f) << "B is in front of the light";
                EXPECT_LE(std::abs(clipPos.x / clipPos.w), 1.0f + 1e-3f);
                EXPECT_LE(std::abs(clipPos.y / clipPos.w), 1.0f + 1e-3f);
            }
        }
        // A visible ground point under the cone, and a point between it and the light, are in B.
        EXPECT_TRUE(kit::contains(focused.body, {5, 0.5f, -5}, 1e-3f));
        EXPECT_TRUE(kit::contains(focused.body, {2, 9.2f, -4.4f}, 1e-3f));   // 0.6 of the way
    }
}

// ---------------------------------------------------------------------------------------------
// LiSPSM (plugins/lispsm/lispsm_warp.h)

// Eq. 8.13 as re-derived, d / (sqrt(z1 / z0) - 1), is eq. 8.11 for z0 = -z_n, z1 = -(z_n + d sin g)
// and eq. 8.10 for g = 90 degrees.
TEST(Lispsm, NOptGeneralFormulaReducesToEquations8_11And8_10) {
    for (const double zn : {0.1, 0.5, 2.0})
        for (const double d : {5.0, 70.0, 300.0})
            for (const double sinGamma : {0.2, 0.7, 1.0}) {
                const double general = lispsm::nOpt(d, -zn, -(zn + d * sinGamma));
                EXPECT_NEAR(general, lispsm::nOptDirectional(zn, d, sinGamma), 1e-9 * general);
                EXPECT_NEAR(general, (zn + std::sqrt(zn * (zn + d * sinGamma))) / sinGamma, 1e-9 * general);
            }
    const double zn = 0.1, zf = 70.0;
    EXPECT_NEAR(lispsm::nOpt(zf - zn, -zn, -zf), zn + std::sqrt(zn * zf), 1e-9);   // eq. 8.10
}

// The seed's optimal case (sec. 8.2.1): view perpendicular to a directional light, the frustum in
// the scene. B spans z_n..z_f along the view, so n = z_n + sqrt(z_n z_f) (eq. 8.10); every corner
// of B lands in the map; light rays stay rays of the map (same texel, growing depth); and the
// perspective error dp/ds of eq. 8.1 (re-derived eq. 8.9: 1 / (z ds/dz)) is the same at the near
// and the far plane, which is what n_opt is chosen for, while the uniform map's is z_f / z_n
// times larger at the near plane.
TEST(Lispsm, OptimalCaseWarpMatchesEquation8_10AndEqualisesTheError) {
    const float zn = 1.0f, zf = 8.0f;
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, zn, zf);
    const LightInfo light = directional({0, -1, 0});
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    const auto warp = lispsm::directionalWarp(body.vertices(), light.direction, camera, zn, 1.0);
    ASSERT_TRUE(warp);
    EXPECT_NEAR(warp->sinGamma, 1.0, 1e-6);
    EXPECT_NEAR(warp->d, zf - zn, 1e-3);
    EXPECT_NEAR(warp->n, zn + std::sqrt(zn * zf), 1e-3);
    auto ndc = [&](glm::vec3 p) {
        const glm::vec4 c = warp->viewProjection * glm::vec4(p, 1.0f);
        EXPECT_GT(c.w, 0.0f);
        return glm::vec3(c) / c.w;
    };
    for (const glm::vec3& corner : body.vertices()) {
        const glm::vec3 q = ndc(corner);
        EXPECT_LE(glm::max(std::abs(q.x), std::max(std::abs(q.y), std::abs(q.z))), 1.0f + 1e-4f);
    }
    const glm::vec3 top = ndc({1.0f, 12.0f, -4.0f}), bottom = ndc({1.0f, 2.0f, -4.0f});
    EXPECT_NEAR(top.x, bottom.x, 1e-5f);
    EXPECT_NEAR(top.y, bottom.y, 1e-5f);
    EXPECT_LT(top.z, bottom.z) << "nearer the light, smaller depth";
    // ds/dz along the view axis on the ground under it (s: the map coordinate along the warp).
    auto dsdz = [&](float z) {
        const float h = 1e-3f * z;
        return (ndc({0, 0, -(z + h)}).y - ndc({0, 0, -(z - h)}).y) / (2.0f * h);
    };
    const double nearError = 1.0 / (zn * dsdz(zn)), farError = 1.0 / (zf * dsdz(zf));
    EXPECT_NEAR(nearError / farError, 1.0, 1e-2) << "n_opt equalises the error at z_n and z_f";
    EXPECT_LT(nearError, 0.5 * (zf / zn) * farError) << "far below the uniform map's near/far ratio of z_f / z_n";
    // A smaller n warps harder: the near plane gets more of the map.
    const auto harder = lispsm::directionalWarp(body.vertices(), light.direction, camera, zn, 0.3);
    ASSERT_TRUE(harder);
    EXPECT_NEAR(harder->n, 0.3 * warp->n, 1e-3);
}

// Duelling frusta (Fig. 8.11): looking along the light there is nothing to warp.
TEST(Lispsm, NoWarpWhenViewAndLightAreParallel) {
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, 1.0f, 8.0f);
    const LightInfo light = directional({0.01f, 0.0f, -1.0f});
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    EXPECT_FALSE(lispsm::directionalWarp(body.vertices(), light.direction, camera, 1.0f, 1.0));
    EXPECT_FALSE(lispsm::directionalWarp({}, glm::vec3(0, -1, 0), camera, 1.0f, 1.0)) << "no body";
}

// Sec. 9.2.5's virtual far plane in the optimal case above: n from the body of the frustum cut at
// z_f' = 4 (the real far plane stays 8) is eq. 8.10 with z_f', z_n + sqrt(z_n z_f') = 3 instead of
// 1 + sqrt(8); the error of eq. 8.9 is then equal at z_n and z_f' (it equalises up to the virtual
// plane) and larger at the real far plane, while the map still holds the whole of B.
TEST(Lispsm, VirtualFarPlaneTunesNOnly) {
    const float zn = 1.0f, zf = 8.0f, zv = 4.0f;
    const CameraInfo camera = cameraLookingDownMinusZ({0, 5, 0}, zn, zf);
    const LightInfo light = directional({0, -1, 0});
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    const kit::ConvexBody virtualBody = kit::focusBody(lispsm::virtualViewBody(camera, zv), light, kScene, LightSpace{});
    lispsm::WarpOptions options;
    options.bodyForN = virtualBody.vertices();
    const auto warp = lispsm::directionalWarp(body.vertices(), light.direction, camera, zn, options);
    ASSERT_TRUE(warp);
    EXPECT_NEAR(warp->dForN, zv - zn, 1e-3);
    EXPECT_NEAR(warp->d, zf - zn, 1e-3) << "P still spans B";
    EXPECT_NEAR(warp->n, zn + std::sqrt(zn * zv), 1e-3);
    EXPECT_NEAR(warp->n, lispsm::nOpt(zv - zn, -zn, -zv), 1e-3);
    auto ndc = [&](glm::vec3 p) {
        const glm::vec4 c = warp->viewProjection * glm::vec4(p, 1.0f);
        return glm::vec3(c) / c.w;
    };
    for (const glm::vec3& corner : body.vertices()) {
        const glm::vec3 q = ndc(corner);
        EXPECT_LE(glm::max(std::abs(q.x), std::max(std::abs(q.y), std::abs(q.z))), 1.0f + 1e-4f);
    }
    auto error = [&](float z) {   // 1 / (z ds/dz), eq. 8.1 with cos a / cos b = 1
        const float h = 1e-3f * z;
        return 1.0 / (z * (ndc({0, 0, -(z + h)}).y - ndc({0, 0, -(z - h)}).y) / (2.0f * h));
    };
    EXPECT_NEAR(error(zn) / error(zv), 1.0, 1e-2) << "equalised between z_n and the virtual far plane";
    EXPECT_GT(error(zf), 1.2 * error(zn)) << "beyond it the error grows";
    // At or beyond the camera's far plane the virtual frustum is the frustum: the recipe unchanged.
    const kit::ConvexBody same = kit::focusBody(lispsm::virtualViewBody(camera, 0.0f), light, kScene, LightSpace{});
    lispsm::WarpOptions sameOptions;
    sameOptions.bodyForN = same.vertices();
    const auto plain = lispsm::directionalWarp(body.vertices(), light.direction, camera, zn, sameOptions);
    ASSERT_TRUE(plain);
    EXPECT_NEAR(plain->n, zn + std::sqrt(zn * zf), 1e-3);
}

// Sec. 9.2.6's body vector on a body worked out by hand: the camera on the scene's x = 0 face,
// looking along -z, 60 degrees square, near 1, far 8, at half the height of a 1 m thin scene; the
// light straight down. V n S is the half frustum x in [0, d tan 30], y in [0, 1], eye depth d in
// [1, 8], and sweeping it up to S's top changes nothing, so B has the 8 corners (0, {0,1}, -1),
// (tan 30, {0,1}, -1), (0, {0,1}, -8), (8 tan 30, {0,1}, -8). From the eye (0, 0.5, 0) their sum is
// (2 (1 + 8) tan 30, 0, -4 (1 + 8)) = (6 sqrt 3, 0, -36): the axis turns 16.1 degrees off the view
// direction towards the half of the frustum that is in the scene.
TEST(Lispsm, BodyVectorPointsIntoTheMiddleOfB) {
    const Bounds thin{{0, 0, -50}, {50, 1, 50}};
    const CameraInfo camera = cameraLookingDownMinusZ({0, 0.5f, 0}, 1.0f, 8.0f);
    const LightInfo light = directional({0, -1, 0});
    const kit::ConvexBody body = kit::focusBody(camera, light, thin, LightSpace{});
    const float t = std::tan(glm::radians(30.0f));
    std::vector<glm::vec3> expected;
    for (const float y : {0.0f, 1.0f})
        for (const glm::vec3& c : {glm::vec3(0, y, -1), glm::vec3(t, y, -1), glm::vec3(0, y, -8), glm::vec3(8 * t, y, -8)})
            expected.push_back(c);
    ASSERT_NO_FATAL_FAILURE(expectCorners(body, expected));
    const glm::vec3 byHand = glm::normalize(glm::vec3(6.0f * std::sqrt(3.0f), 0.0f, -36.0f));
    const glm::vec3 vector = lispsm::bodyVector(body.corners(1e-4f), camera.position);
    EXPECT_NEAR(glm::distance(vector, byHand), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::degrees(std::acos(glm::dot(vector, glm::vec3(0, 0, -1)))), 16.10, 0.01);

    lispsm::WarpOptions options;
    options.axisSource = vector;
    const auto warp = lispsm::directionalWarp(body.vertices(), light.direction, camera, 1.0f, options);
    ASSERT_TRUE(warp);
    EXPECT_NEAR(glm::distance(warp->up, byHand), 0.0f, 1e-4f) << "u: the body vector (already across the light)";
    EXPECT_NEAR(warp->viewAlongUp, byHand.z * -1.0f, 1e-5);
    // d along u over the hand-computed corners, and eq. 8.13 with z1 = z0 - d (v . u) (sec. 9.2.5).
    double lo = 1e9, hi = -1e9;
    for (const glm::vec3& c : expected) {
        lo = std::min(lo, double(glm::dot(byHand, c - camera.position)));
        hi = std::max(hi, double(glm::dot(byHand, c - camera.position)));
    }
    EXPECT_NEAR(warp->d, hi - lo, 1e-3);
    EXPECT_NEAR(warp->n, lispsm::nOpt(hi - lo, -1.0, -1.0 - (hi - lo) * warp->viewAlongUp), 1e-3);
    for (const glm::vec3& c : expected) {
        const glm::vec4 q = warp->viewProjection * glm::vec4(c, 1.0f);
        EXPECT_LE(std::max(std::abs(q.x / q.w), std::abs(q.y / q.w)), 1.0f + 1e-4f) << "B fills the map";
    }
    // Without the body vector the axis is the view direction, to one side of B.
    const auto plain = lispsm::directionalWarp(body.vertices(), light.direction, camera, 1.0f, 1.0);
    ASSERT_TRUE(plain);
    EXPECT_NEAR(glm::distance(plain->up, glm::vec3(0, 0, -1)), 0.0f, 1e-5f);
}
