// The texel footprint m (seed 002 eq. 8.1, dp/ds: pixels one shadow-map texel covers along its
// worst direction) against its closed forms, and as eval measures it from the maps the
// techniques report (SHADOWLAB_EXT_SHADOW_MAPS).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "groundtruth/texel_footprint.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

constexpr float kFovY = glm::radians(60.0f);
constexpr int kPixels = 200;

CameraInfo cameraAt(glm::vec3 eye, glm::vec3 target, glm::vec3 up) {
    CameraInfo c;
    c.view = glm::lookAt(eye, target, up);
    c.projection = glm::perspective(kFovY, 1.0f, 0.1f, 1000.0f);
    c.viewProjection = c.projection * c.view;
    c.inverseViewProjection = glm::inverse(c.viewProjection);
    c.position = eye;
    c.nearPlane = 0.1f;
    c.farPlane = 1000.0f;
    c.fovY = kFovY;
    c.viewport = {kPixels, kPixels};
    return c;
}

// An orthographic map of `texels` over a square of `extent` world units, light travelling along
// `direction` towards the origin.
ShadowMapInfo orthographicMap(float extent, int texels, glm::vec3 direction) {
    ShadowMapInfo map;
    const glm::vec3 d = glm::normalize(direction);
    const glm::vec3 up = std::abs(d.z) > 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    map.worldToClip = glm::ortho(-extent / 2, extent / 2, -extent / 2, extent / 2, 0.1f, 100.0f) * glm::lookAt(-50.0f * d, glm::vec3(0), up);
    map.size = {texels, texels};
    return map;
}

// World size of one pixel at distance d, at the centre of the view.
float pixelSize(float distance) { return 2.0f * distance * std::tan(kFovY / 2) / float(kPixels); }

} // namespace

// Camera straight down 10 units over the ground, light straight down: one texel of a 1024 map
// over 20 units is 20/1024 units wide, one pixel 2*10*tan(30 deg)/200: m is their ratio.
TEST(TexelFootprint, PerpendicularViewIsTheTexelOverThePixel) {
    const CameraInfo camera = cameraAt({0, 10, 0}, {0, 0, 0}, {0, 0, -1});
    const ShadowMapInfo map = orthographicMap(20.0f, 1024, {0, -1, 0});
    const float m = texelFootprintAt(camera, map, {0, 0, 0}, {0, 1, 0});
    EXPECT_NEAR(m, (20.0f / 1024.0f) / pixelSize(10.0f), 1e-3 * m);
}

// Eq. 8.1's perspective term 1/z: twice as far, half the pixels per texel.
TEST(TexelFootprint, PerspectiveTermIsOneOverDistance) {
    const ShadowMapInfo map = orthographicMap(20.0f, 1024, {0, -1, 0});
    const float nearM = texelFootprintAt(cameraAt({0, 5, 0}, {0, 0, 0}, {0, 0, -1}), map, {0, 0, 0}, {0, 1, 0});
    const float farM = texelFootprintAt(cameraAt({0, 10, 0}, {0, 0, 0}, {0, 0, -1}), map, {0, 0, 0}, {0, 1, 0});
    EXPECT_NEAR(nearM / farM, 2.0f, 2e-3f);
}

// A camera tilted 60 degrees from the normal: pixels stretch along the tilt, so they hold more
// texels that way; the worst direction is across the tilt, where a pixel is as wide as seen
// head-on from the same distance.
TEST(TexelFootprint, WorstDirectionIsAcrossAnObliqueView) {
    const ShadowMapInfo map = orthographicMap(20.0f, 1024, {0, -1, 0});
    const float distance = 10.0f, tilt = glm::radians(60.0f);
    const CameraInfo camera = cameraAt({0, distance * std::cos(tilt), distance * std::sin(tilt)}, {0, 0, 0}, {0, 1, 0});
    const float m = texelFootprintAt(camera, map, {0, 0, 0}, {0, 1, 0});
    EXPECT_NEAR(m, (20.0f / 1024.0f) / pixelSize(distance), 2e-3 * m);
}

// Eq. 8.1's projection term cos(alpha) / cos(beta): a light 70 degrees off the normal spreads a
// texel over 1/cos(70 deg) as much ground along its direction, the camera still head-on.
TEST(TexelFootprint, ProjectionTermIsCosAlphaOverCosBeta) {
    const CameraInfo camera = cameraAt({0, 10, 0}, {0, 0, 0}, {0, 0, -1});
    const float beta = glm::radians(70.0f);
    const ShadowMapInfo slanted = orthographicMap(20.0f, 1024, {std::sin(beta), -std::cos(beta), 0});
    const float m = texelFootprintAt(camera, slanted, {0, 0, 0}, {0, 1, 0});
    EXPECT_NEAR(m, (20.0f / 1024.0f) / pixelSize(10.0f) / std::cos(beta), 2e-3 * m);
}

// Cascades: the first map whose view-distance range and clip volume hold the point serves it.
TEST(TexelFootprint, ServingMapFollowsTheSplitsAndTheCoverage) {
    std::vector<ShadowMapInfo> maps = {orthographicMap(10.0f, 512, {0, -1, 0}), orthographicMap(40.0f, 512, {0, -1, 0})};
    maps[0].viewDistanceEnd = 10.0f;
    maps[1].viewDistanceBegin = 10.0f;
    EXPECT_EQ(servingShadowMap(maps, {1, 0, 1}, 5.0f), 0);
    EXPECT_EQ(servingShadowMap(maps, {1, 0, 1}, 15.0f), 1);
    EXPECT_EQ(servingShadowMap(maps, {8, 0, 1}, 5.0f), -1) << "outside the near cascade's square, and too near for the far one";
    EXPECT_EQ(servingShadowMap(maps, {30, 0, 1}, 15.0f), -1) << "outside every map";
}

// Through eval: shadowmap reports its one map, and m scales as 1/resolution (same fit, same view).
TEST(TexelFootprint, EvalMeasuresTheReportedMap) {
    auto app = test::makeHeadlessApp("cube", {320, 240});
    ASSERT_TRUE(app);
    const Evaluation coarse = test::evaluateTechnique(*app, "shadowmap", {"resolution=1024"}, ReferenceOptions::Mode::Hard);
    const Evaluation fine = test::evaluateTechnique(*app, "shadowmap", {"resolution=2048"}, ReferenceOptions::Mode::Hard);
    ASSERT_EQ(coarse.footprint.maps, 1u);
    ASSERT_GT(coarse.footprint.measuredPixels, 10000u);
    EXPECT_EQ(coarse.footprint.uncoveredPixels, 0u) << "the scene fit covers every lit pixel";
    EXPECT_NEAR(coarse.footprint.median / fine.footprint.median, 2.0, 0.02);
    EXPECT_GE(coarse.footprint.p95, coarse.footprint.median);
    // `none` draws no map: nothing to measure.
    const Evaluation none = test::evaluateTechnique(*app, "none", {}, ReferenceOptions::Mode::Hard);
    EXPECT_EQ(none.footprint.maps, 0u);
    EXPECT_EQ(none.footprint.measuredPixels, 0u);
}

// Seed 002's claim in m itself (sec. 4.2, ch. 8): on forest-002 a scene-fitted 2048 map is
// undersampled near the viewer; the focus body and LiSPSM's warp give the near third smaller
// texels (lower m) from the same 2048 x 2048.
TEST(TexelFootprint, FocusingAndWarpingShrinkNearTexels) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    auto nearM = [&](const std::string& technique, std::vector<std::string> sets) {
        sets.push_back("resolution=2048");
        const Evaluation e = test::evaluateTechnique(*app, technique, sets, ReferenceOptions::Mode::Hard);
        EXPECT_GT(e.footprint.measuredPixels, 1000u) << technique;
        return e.footprint.medianByViewDepth[0];
    };
    const double scene = nearM("shadowmap", {"fit=scene"}), focus = nearM("shadowmap", {"fit=focus-body"}),
                 warped = nearM("lispsm", {});
    std::printf("forest-002 near-third median m: scene %.3f, focus-body %.3f, lispsm %.3f\n", scene, focus, warped);
    EXPECT_GT(scene, 1.0) << "a scene fit undersamples near the viewer";
    EXPECT_LT(focus, 0.5 * scene);
    EXPECT_LT(warped, focus);
}

// Seed 002 Figs. 8.7 and 9.3 measured: the error against view depth (TexelFootprint::byViewDepth,
// depthError: pixels per texel along the direction the ground recedes, eq. 6.1's projection term
// divided out) on `aliasing-plane`, the seed's optimal case of sec. 8.2.1 (ground under a light
// straight down, the camera level at h = 0.5, near 1, far 100), 64x2048 so that the ground has
// pixel rows out to z = 100. Against the analytic curves of eq. 8.1 in pixels:
//   dp/ds = F / (R z ds/dz) * sqrt(1 + h^2 / z^2),  F = (H / 2) / tan(30 deg) pixels, R the map,
// the last factor being the ground's own: a ground step seen at elevation e = atan(h / z) spans
// 1 / cos e more screen than eq. 8.1's edge perpendicular to the view ray (seed Fig. 8.5 idealises
// it to 1; it is 1.118 at z = 1 and under 1.005 beyond z = 5).
//   LiSPSM, eq. 8.9: ds/dz = n f / ((z - z_n + n)^2 (f - n)), f = n + d, d = z_f - z_n, n from
//     eq. 8.10 with z_f (100, or the virtual far plane of sec. 9.2.5);
//   uniform, eq. 8.2: ds/dz constant, so dp/ds z / sqrt(1 + h^2 / z^2) is the same at every depth.
// Tolerance: 4% per bin (the bin's median depth stands for its pixels, 10% wide; rasterised
// G-buffer positions), over bins of at least 64 pixels.
TEST(TexelFootprint, ErrorAgainstViewDepthMatchesEquations8_2And8_9) {
    const glm::ivec2 size{64, 2048};
    auto app = test::makeHeadlessApp("aliasing-plane", size);
    ASSERT_TRUE(app);
    const double zn = 1.0, zf = 100.0, h = 0.5, R = 2048.0;
    const double F = 0.5 * size.y / std::tan(glm::radians(30.0));
    auto groundFactor = [&](double z) { return std::sqrt(1.0 + h * h / (z * z)); };
    for (const double farForN : {100.0, 25.0}) {
        SCOPED_TRACE(farForN);
        const Evaluation e = test::evaluateTechnique(
            *app, "lispsm", {"resolution=2048", "virtual_far=" + std::to_string(farForN)}, ReferenceOptions::Mode::Hard);
        ASSERT_EQ(e.footprint.byViewDepth.size(), size_t(kFootprintDepthBins));
        const double n = zn + std::sqrt(zn * farForN), f = n + (zf - zn);
        int checked = 0;
        double worst = 0.0;
        for (const TexelFootprint::DepthBin& bin : e.footprint.byViewDepth) {
            if (bin.pixels < 64) continue;
            const double z = bin.depth, t = z - zn + n;
            const double analytic = F * t * t * (f - n) / (R * n * f * z) * groundFactor(z);   // eq. 8.9 in pixels
            EXPECT_NEAR(bin.depthError / analytic, 1.0, 0.04) << "z " << z;
            worst = std::max(worst, std::abs(bin.depthError / analytic - 1.0));
            ++checked;
        }
        std::printf("aliasing-plane lispsm (z_f for n %.0f): %d bins within %.2f%% of eq. 8.9\n", farForN, checked, 100.0 * worst);
        EXPECT_GE(checked, 30) << "bins from z = 1 well past z = 50";
    }
    // Uniform (focused map, no warp): eq. 8.2's 1/z.
    const Evaluation uniform = test::evaluateTechnique(*app, "shadowmap", {"resolution=2048", "fit=focus-body"},
                                                       ReferenceOptions::Mode::Hard);
    std::vector<double> scaled;
    for (const TexelFootprint::DepthBin& bin : uniform.footprint.byViewDepth)
        if (bin.pixels >= 64) scaled.push_back(bin.depthError * bin.depth / groundFactor(bin.depth));
    ASSERT_GE(scaled.size(), 30u);
    const double mid = scaled[scaled.size() / 2];
    for (const double v : scaled) EXPECT_NEAR(v / mid, 1.0, 0.04);
    // The figures' ordering at the ends (Fig. 8.7): uniform worst at the near plane, LiSPSM's error
    // far below it there.
    const Evaluation warped = test::evaluateTechnique(*app, "lispsm", {"resolution=2048"}, ReferenceOptions::Mode::Hard);
    const auto firstFull = [](const TexelFootprint& f) {
        for (const auto& bin : f.byViewDepth)
            if (bin.pixels >= 64) return bin.depthError;
        return 0.0;
    };
    EXPECT_LT(firstFull(warped.footprint), 0.2 * firstFull(uniform.footprint));
}

// PSM on the same scene (seed 002 eq. 8.3): in post-perspective space the ground's depth z maps
// to z_pp = (f + n) / (f - n) - 2 f n / ((f - n) z) (eq. 7.1 for a point in front), and with the
// light straight down PP holds it as a directional light across the view (sec. 7.2.3), so the map
// is an orthographic projection of PP with one axis along z_pp over B's image [-1, 1]: s = R (z_pp
// + 1) / 2, ds/dz = R n f / ((f - n) z^2), and eq. 8.1 gives
//   dp/ds = F z (1 / z_n - 1 / z_f) / R * sqrt(1 + h^2 / z^2),
// linear in z: eq. 8.3's s ~ 1/z. z_n is psm's near plane, pushed to the nearest receiver (the
// ground meets the frustum's lower edge at 0.87, inside the near plane 1: it stays 1), z_f the far
// plane (B reaches it). Tolerance 1% per bin (measured on llvmpipe: within 0.01% at every bin
// from z = 1 to 93, 48 bins: PSM's s is exactly affine in 1/z, so the bin's median depth does not
// blur it as it does eq. 8.9's curve). Before the fix in psm::nearestReceiverDepth (flat bounds of the ground
// plane were dropped, the near plane went to the far plane) no pixel was inside psm's map.
TEST(TexelFootprint, PsmErrorAgainstViewDepthMatchesEquation8_3) {
    const glm::ivec2 size{64, 2048};
    auto app = test::makeHeadlessApp("aliasing-plane", size);
    ASSERT_TRUE(app);
    const double zn = 1.0, zf = 100.0, h = 0.5, R = 2048.0;
    const double F = 0.5 * size.y / std::tan(glm::radians(30.0));
    const Evaluation e = test::evaluateTechnique(*app, "psm", {"resolution=2048"}, ReferenceOptions::Mode::Hard);
    EXPECT_LT(e.footprint.uncoveredPixels, e.footprint.measuredPixels / 100 + 1) << "psm's map holds the visible ground";
    ASSERT_EQ(e.footprint.byViewDepth.size(), size_t(kFootprintDepthBins));
    int checked = 0;
    double worst = 0.0;
    for (const TexelFootprint::DepthBin& bin : e.footprint.byViewDepth) {
        if (bin.pixels < 64) continue;
        const double z = bin.depth;
        const double analytic = F * z * (1.0 / zn - 1.0 / zf) / R * std::sqrt(1.0 + h * h / (z * z));   // eq. 8.3 in pixels
        EXPECT_NEAR(bin.depthError / analytic, 1.0, 0.01) << "z " << z;
        worst = std::max(worst, std::abs(bin.depthError / analytic - 1.0));
        ++checked;
    }
    std::printf("aliasing-plane psm: %d bins within %.2f%% of eq. 8.3\n", checked, 100.0 * worst);
    EXPECT_GE(checked, 30) << "bins from z = 1 well past z = 50";
}
