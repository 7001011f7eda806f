// Cascaded shadow maps' maths (kit/cascades.h, no GL): the practical split scheme against its
// closed form (Zhang et al. 2006; GPU Gems 3 eq. 10.1-10.3), stabilised cascades unchanged to the
// texel under sub-texel camera translation (and the tight fit, which is not, as the control), and
// every cascade's map covering its frustum slice; the kit's cube faces covering every direction.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "camera.h"
#include "shadowlab/kit/cascades.h"
#include "shadowlab/kit/cube_depth_map.h"

using namespace shadowlab;

namespace {

const Bounds kScene{{-105, -5, -105}, {105, 12, 105}};

CameraInfo cameraAt(glm::vec3 eye, glm::vec3 target, float fovDegrees, float aspect, float nearPlane, float farPlane) {
    CameraInfo c{};
    c.position = eye;
    c.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    c.projection = glm::perspective(glm::radians(fovDegrees), aspect, nearPlane, farPlane);
    c.viewProjection = c.projection * c.view;
    c.nearPlane = nearPlane;
    c.farPlane = farPlane;
    c.fovY = glm::radians(fovDegrees);
    c.aspect = aspect;
    completeCameraInfo(c);
    return c;
}

CameraInfo translated(const CameraInfo& camera, glm::vec3 offset) {
    CameraInfo c = camera;
    c.position += offset;
    c.view = camera.view * glm::translate(glm::mat4(1.0f), -offset);
    c.viewProjection = c.projection * c.view;
    completeCameraInfo(c);
    return c;
}

LightInfo sun(float elevationDegrees, float azimuthDegrees) {
    const float e = glm::radians(elevationDegrees), a = glm::radians(azimuthDegrees);
    LightInfo light{};
    light.type = LightType::Directional;
    light.direction = -glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
    return light;
}

// The map's texel coordinates of a world point (x and y, in texels from the map's corner).
glm::dvec2 texelOf(const LightSpace& light, glm::vec3 p, int resolution) {
    const glm::vec4 clip = light.viewProjection * glm::vec4(p, 1.0f);
    return (glm::dvec2(clip.x, clip.y) / double(clip.w) * 0.5 + 0.5) * double(resolution);
}

// A point inside the slice: trilinear in its corners (u, v, w in [0, 1]).
glm::vec3 insideSlice(const std::array<glm::vec3, 8>& c, float u, float v, float w) {
    auto lerp = [](glm::vec3 a, glm::vec3 b, float t) { return a + (b - a) * t; };
    const glm::vec3 nearPoint = lerp(lerp(c[0], c[1], u), lerp(c[2], c[3], u), v);
    const glm::vec3 farPoint = lerp(lerp(c[4], c[5], u), lerp(c[6], c[7], u), v);
    return lerp(nearPoint, farPoint, w);
}

} // namespace

// C_i = lambda n (f/n)^(i/N) + (1 - lambda)(n + (f - n) i/N), computed here independently in long
// double, for every count and the bench's lambdas; the logarithmic end gives every slice the same
// far/near ratio (seed 002 eq. 8.4: the same perspective error at both ends of each), the uniform
// end the same width.
TEST(PracticalSplits, MatchTheClosedForm) {
    for (const auto& [n, f] : {std::pair{0.1f, 400.0f}, std::pair{0.1f, 70.0f}, std::pair{1.0f, 30.0f}})
        for (int count = 1; count <= kit::kMaxCascades; ++count)
            for (const float lambda : {0.0f, 0.5f, 0.75f, 1.0f}) {
                SCOPED_TRACE(testing::Message() << "n " << n << " f " << f << " N " << count << " lambda " << lambda);
                const std::vector<float> splits = kit::practicalSplits(n, f, count, lambda);
                ASSERT_EQ(splits.size(), size_t(count) + 1);
                EXPECT_EQ(splits.front(), n);
                EXPECT_EQ(splits.back(), f);
                for (int i = 0; i <= count; ++i) {
                    const long double s = (long double)i / count;
                    const long double expected = lambda * n * std::pow((long double)f / n, s) +
                                                 (1.0L - lambda) * (n + ((long double)f - n) * s);
                    EXPECT_NEAR(splits[size_t(i)], double(expected), 2e-6 * double(expected));
                    if (i > 0) {
                        EXPECT_GT(splits[size_t(i)], splits[size_t(i) - 1]);
                    }
                }
                for (int i = 1; i < count; ++i) {
                    if (lambda == 1.0f) {
                        EXPECT_NEAR(splits[size_t(i) + 1] / splits[size_t(i)], splits[1] / splits[0],
                                    1e-4 * splits[1] / splits[0]);
                    }
                    if (lambda == 0.0f) {
                        EXPECT_NEAR(splits[size_t(i) + 1] - splits[size_t(i)], splits[1] - splits[0], 1e-4 * f);
                    }
                }
            }
    // The worked example of GPU Gems 3 ch. 10's set-up, by hand: n = 1, f = 1000, N = 3, lambda = 0.5:
    // C_1 = 0.5 * 10 + 0.5 * 334 = 172, C_2 = 0.5 * 100 + 0.5 * 667 = 383.5.
    const auto splits = kit::practicalSplits(1.0f, 1000.0f, 3, 0.5f);
    EXPECT_NEAR(splits[1], 172.0f, 1e-3f);
    EXPECT_NEAR(splits[2], 383.5f, 1e-3f);
}

// Stabilised cascades (bounding sphere, texel snapping): under camera translations smaller than a
// texel, each cascade's texel size stays bit for bit the same and a fixed world point keeps its
// place inside its texel: its texel coordinates change by a whole number (0 or 1) to within 1e-3
// of a texel. The tight fit under the same motion moves the grid by fractions of a texel (the
// shimmer stabilisation removes), which shows the check can fail.
TEST(StabilisedCascades, UnchangedToTheTexelUnderSubTexelCameraTranslation) {
    const CameraInfo camera = cameraAt({3.0f, 9.0f, 80.0f}, {0.0f, 1.0f, 52.0f}, 60.0f, 16.0f / 9.0f, 0.1f, 70.0f);
    const LightInfo light = sun(40.0f, 10.0f);
    const glm::mat4 lightView = kit::stableLightView(light);
    const int res = 1024, count = 4;
    const kit::CascadeRanges ranges = kit::cascadeRanges(camera.nearPlane, camera.farPlane, count, 0.75f, 0.1f);
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<glm::vec3> probes;
    for (int i = 0; i < 64; ++i) probes.push_back({unit(random) * 30.0f, unit(random) * 3.0f + 2.0f, 60.0f + unit(random) * 25.0f});
    double tightFraction = 0.0;
    for (int c = 0; c < count; ++c) {
        SCOPED_TRACE(testing::Message() << "cascade " << c);
        auto fit = [&](const CameraInfo& cam, bool stabilise) {
            return kit::fitDirectionalCascade(cam, lightView, ranges.fitBegin[size_t(c)], ranges.splits[size_t(c) + 1],
                                              {.resolution = res, .stabilise = stabilise}, kScene, kScene);
        };
        const kit::Cascade before = fit(camera, true);
        const kit::Cascade tightBefore = fit(camera, false);
        ASSERT_GT(before.texelWorldSize, 0.0f);
        for (int step = 0; step < 20; ++step) {
            const glm::vec3 offset = glm::vec3(unit(random), unit(random), unit(random)) * 0.3f * before.texelWorldSize;
            const CameraInfo moved = translated(camera, offset);
            const kit::Cascade after = fit(moved, true);
            EXPECT_EQ(after.texelWorldSize, before.texelWorldSize);
            EXPECT_EQ(after.light.projection[0][0], before.light.projection[0][0]);
            EXPECT_EQ(after.light.projection[1][1], before.light.projection[1][1]);
            for (const glm::vec3& p : probes) {
                const glm::dvec2 shift = texelOf(after.light, p, res) - texelOf(before.light, p, res);
                for (int axis = 0; axis < 2; ++axis) {
                    EXPECT_NEAR(shift[axis], std::round(shift[axis]), 1e-3) << "a fraction of a texel";
                    EXPECT_LE(std::abs(std::round(shift[axis])), 1.0) << "more than a texel for a sub-texel move";
                }
            }
            const kit::Cascade tightAfter = fit(moved, false);
            const glm::dvec2 shift = texelOf(tightAfter.light, probes[0], res) - texelOf(tightBefore.light, probes[0], res);
            tightFraction = std::max(tightFraction, std::abs(shift.x - std::round(shift.x)));
        }
    }
    EXPECT_GT(tightFraction, 0.05) << "the tight fit's grid slides with the camera";
}

// Every cascade's map holds its whole fitted slice (its served range plus the blend band before
// it): the slice's corners and points inside it land within the map's x, y and depth range, for
// both fits, clipped to the scene or not, several cameras and lights, and spot lights' crops. The
// served ranges tile the depth range without gaps.
TEST(Cascades, EveryMapCoversItsFrustumSlice) {
    const std::vector<CameraInfo> cameras = {
        cameraAt({0.0f, 9.0f, 100.0f}, {0.0f, 1.0f, 72.0f}, 60.0f, 1.6f, 0.1f, 70.0f),
        cameraAt({-40.0f, 3.0f, 10.0f}, {10.0f, 0.0f, -20.0f}, 45.0f, 1.0f, 0.5f, 300.0f),
        cameraAt({5.0f, 60.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 75.0f, 2.0f, 0.1f, 150.0f),
    };
    const std::vector<LightInfo> lights = {sun(40.0f, 10.0f), sun(8.0f, 200.0f), sun(89.0f, 0.0f)};
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const int res = 512;
    for (const CameraInfo& camera : cameras)
        for (const LightInfo& light : lights)
            for (const int count : {1, 3, 8})
                for (const bool stabilise : {false, true}) {
                    SCOPED_TRACE(testing::Message() << "cascades " << count << " stabilise " << stabilise);
                    const kit::CascadeRanges ranges = kit::cascadeRanges(camera.nearPlane, camera.farPlane, count, 0.75f, 0.2f);
                    for (int i = 0; i < count; ++i) {
                        ASSERT_EQ(ranges.splits[size_t(i) + 1] > ranges.splits[size_t(i)], true);
                        EXPECT_LE(ranges.fitBegin[size_t(i)], ranges.splits[size_t(i)]);
                    }
                    const glm::mat4 lightView = kit::stableLightView(light);
                    for (int i = 0; i < count; ++i) {
                        const float begin = ranges.fitBegin[size_t(i)], end = ranges.splits[size_t(i) + 1];
                        const kit::Cascade cascade = kit::fitDirectionalCascade(
                            camera, lightView, begin, end, {.resolution = res, .stabilise = stabilise}, kScene, kScene);
                        const auto corners = kit::sliceCorners(camera, begin, end);
                        std::vector<glm::vec3> points(corners.begin(), corners.end());
                        for (int k = 0; k < 200; ++k) points.push_back(insideSlice(corners, unit(random), unit(random), unit(random)));
                        for (const glm::vec3& p : points) {
                            const glm::vec4 clip = cascade.light.viewProjection * glm::vec4(p, 1.0f);
                            const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                            EXPECT_LE(std::abs(ndc.x), 1.0f + 1e-5f);
                            EXPECT_LE(std::abs(ndc.y), 1.0f + 1e-5f);
                            EXPECT_LE(std::abs(ndc.z), 1.0f + 1e-5f);
                        }
                    }
                }
    // A spot light's cascades: crops of its frustum, holding the part of each slice inside it.
    LightInfo spot{};
    spot.type = LightType::Spot;
    spot.position = {0.0f, 30.0f, 60.0f};
    spot.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -0.4f));
    spot.spotOuterAngle = glm::radians(50.0f);
    const Bounds scene{{-60, -1, -20}, {60, 10, 120}};
    // A perspective fit around the scene, as the host makes one.
    LightSpace sceneFit;
    sceneFit.view = glm::lookAt(spot.position, spot.position + spot.direction, glm::vec3(0, 1, 0));
    sceneFit.nearPlane = 1.0f;
    sceneFit.farPlane = 200.0f;
    sceneFit.projection = glm::perspective(2.0f * spot.spotOuterAngle, 1.0f, 1.0f, 200.0f);
    sceneFit.viewProjection = sceneFit.projection * sceneFit.view;
    sceneFit.perspective = true;
    const CameraInfo& camera = cameras[0];
    const kit::CascadeRanges ranges = kit::cascadeRanges(camera.nearPlane, camera.farPlane, 4, 0.75f, 0.1f);
    const kit::ConvexBody lightFrustum = kit::frustumBody(glm::inverse(sceneFit.viewProjection));
    for (const bool stabilise : {false, true})
        for (int i = 0; i < 4; ++i) {
            const float begin = ranges.fitBegin[size_t(i)], end = ranges.splits[size_t(i) + 1];
            const kit::Cascade cascade =
                kit::fitPerspectiveCascade(camera, sceneFit, begin, end, {.resolution = res, .stabilise = stabilise}, scene);
            const auto corners = kit::sliceCorners(camera, begin, end);
            for (int k = 0; k < 300; ++k) {
                const glm::vec3 p = insideSlice(corners, unit(random), unit(random), unit(random));
                if (!kit::contains(lightFrustum, p, 0.0f)) continue;   // not lit by the spot: no map needed
                const glm::vec4 clip = cascade.light.viewProjection * glm::vec4(p, 1.0f);
                EXPECT_LE(std::abs(clip.x / clip.w), 1.0f + 1e-4f);
                EXPECT_LE(std::abs(clip.y / clip.w), 1.0f + 1e-4f);
            }
        }
}

// The kit's cube: every direction from the light falls inside the face GL's cube-map addressing
// picks for it (the major axis), at the depth range's distances.
TEST(CubeDepthMap, EveryDirectionLandsInTheFaceItsMajorAxisPicks) {
    const glm::vec3 light(1.0f, 2.0f, -3.0f);
    const auto faces = kit::cubeFaceViewProjections(light, 0.01f, 50.0f);
    std::mt19937 random(9);
    std::normal_distribution<float> normal;
    for (int k = 0; k < 2000; ++k) {
        const glm::vec3 dir = glm::normalize(glm::vec3(normal(random), normal(random), normal(random)));
        const glm::vec3 a = glm::abs(dir);
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : a.y >= a.z ? 1 : 2;
        const int face = 2 * axis + (dir[axis] < 0.0f ? 1 : 0);
        const glm::vec4 clip = faces[size_t(face)] * glm::vec4(light + dir * 10.0f, 1.0f);
        ASSERT_GT(clip.w, 0.0f);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0f + 1e-5f);
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0f + 1e-5f);
        EXPECT_LE(std::abs(clip.z / clip.w), 1.0f);
    }
}
