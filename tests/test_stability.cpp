// Issue 12: camera and light paths, the temporal metrics and the failure suite.
//  - paths: keyframes read strictly, interpolated (linear, Catmull-Rom, orbit angles), built in per
//    scene (the dolly moves by the asked fraction of a texel), and named in scene files;
//  - temporal metrics on synthetic frames with known answers (reprojection through world positions);
//  - the failure suite's own claims, measured: the reference passes every case; `shadowmap` with the
//    map cropped to the frustum shimmers under the sub-texel dolly without snapping and not with it;
//    zero bias fails the grazing-light case; `vsm` without light-bleeding reduction fails `overlap`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>

#include <nlohmann/json.hpp>

#include "bench/path_run.h"
#include "bench/stress.h"
#include "plugin/plugin_library.h"
#include "scene/camera_path.h"
#include "test_support.h"
#include "util/paths.h"

using namespace shadowlab;

namespace {

CameraPath parsed(const std::string& text) {
    CameraPath path;
    std::string error;
    EXPECT_TRUE(parsePath(nlohmann::json::parse(text), "test.json", path, error)) << error;
    return path;
}

std::string parseError(const std::string& text) {
    CameraPath path;
    std::string error;
    EXPECT_FALSE(parsePath(nlohmann::json::parse(text), "test.json", path, error)) << text;
    return error;
}

} // namespace

TEST(CameraPath, LinearKeyframesInterpolate) {
    const CameraPath path = parsed(R"({"frames": 5, "keyframes": [
        {"time": 0, "camera": {"position": [0, 1, 4], "target": [0, 0, 0]}, "light": {"elevation": 90, "azimuth": 0, "size": 0.5}},
        {"time": 2, "camera": {"position": [4, 1, 4], "target": [2, 0, 0]}, "light": {"elevation": 10, "azimuth": 0, "size": 2.5}}]})");
    EXPECT_EQ(path.frames, 5);
    EXPECT_DOUBLE_EQ(path.frameTime(2), 1.0);
    const PathState mid = samplePath(path, 1.0);
    ASSERT_TRUE(mid.cameraPosition && mid.cameraTarget && mid.lightDirection && mid.lightSize);
    EXPECT_NEAR(mid.cameraPosition->x, 2.0f, 1e-6f);
    EXPECT_NEAR(mid.cameraTarget->x, 1.0f, 1e-6f);
    EXPECT_NEAR(*mid.lightSize, 1.5f, 1e-6f);
    // Angles are interpolated as angles: 50 degrees of elevation halfway, the light travelling down.
    EXPECT_NEAR(std::asin(-mid.lightDirection->y), 50.0 * M_PI / 180.0, 1e-5);
    // Before the first and after the last keyframe the ends hold.
    EXPECT_NEAR(samplePath(path, -1.0).cameraPosition->x, 0.0f, 1e-6f);
    EXPECT_NEAR(samplePath(path, 9.0).cameraPosition->x, 4.0f, 1e-6f);
}

TEST(CameraPath, OrbitKeepsItsDistanceAndSmoothPassesThroughKeys) {
    const CameraPath path = parsed(R"({"interpolation": "smooth", "keyframes": [
        {"time": 0, "camera": {"azimuth": 0, "elevation": 30, "distance": 5, "target": [1, 0, 0]}},
        {"time": 1, "camera": {"azimuth": 90, "elevation": 30, "distance": 5}},
        {"time": 2, "camera": {"azimuth": 180, "elevation": 30, "distance": 5}}]})");
    EXPECT_EQ(path.frames, 121);   // 60 a second, both ends
    for (double t : {0.0, 0.37, 1.0, 1.5}) {
        SceneCamera camera;
        LightInfo light;
        applyPathState(samplePath(path, t), camera, light);
        EXPECT_NEAR(glm::length(camera.position - glm::vec3(1, 0, 0)), 5.0f, 1e-4f) << t;
        EXPECT_NEAR(camera.position.y, 2.5f, 1e-4f) << t;
    }
    SceneCamera camera;
    LightInfo light;
    applyPathState(samplePath(path, 1.0), camera, light);   // azimuth 90: towards +z
    EXPECT_NEAR(camera.position.z, 5.0f * std::cos(float(M_PI) / 6.0f), 1e-4f);
}

TEST(CameraPath, MalformedPathsNameTheField) {
    EXPECT_NE(parseError(R"({"keyframes": [{"time": 1}, {"time": 1}]})").find("test.json: keyframes[1].time: times must increase"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"keyframes": [{"time": 0, "camra": {}}]})").find("keyframes[0].camra: unknown field"), std::string::npos);
    EXPECT_NE(parseError(R"({"keyframes": []})").find("keyframes"), std::string::npos);
    EXPECT_NE(parseError(R"({"keyframes": [{"time": 0, "camera": {"position": [0, 1, 2]}},
                                           {"time": 1, "camera": {"azimuth": 0, "elevation": 0, "distance": 2}}]})")
                  .find("one way"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"keyframes": [{"time": 0, "light": {"elevation": -5, "azimuth": 0}}]})").find("light.elevation"),
              std::string::npos);
    EXPECT_NE(parseError(R"({"frames": 0, "keyframes": [{"time": 0}]})").find("frames"), std::string::npos);
    EXPECT_NE(parseError(R"({"keyframes": [{"time": 0, "camera": {"position": [0, "a", 2]}}]})").find("camera.position[1]"),
              std::string::npos);
}

TEST(CameraPath, ScenesCarryNamedPathsAndRefuseBadOnes) {
    const std::string scene = R"({"objects": [{"shape": "plane"}], "light": {"type": "directional", "elevation": 45},
        "paths": {"rise": {"keyframes": [{"time": 0, "light": {"elevation": 5, "azimuth": 0}},
                                         {"time": 1, "light": {"elevation": 60, "azimuth": 0}}]}}})";
    const Scene loaded = parseScene(scene, "paths.json", ".");
    ASSERT_EQ(loaded.paths.size(), 1u);
    EXPECT_EQ(loaded.paths[0].name, "rise");
    CameraPath path;
    std::string error;
    EXPECT_TRUE(resolvePath("rise", loaded, {}, path, error)) << error;
    EXPECT_FALSE(resolvePath("nonesuch", loaded, {}, path, error));
    EXPECT_NE(error.find("rise"), std::string::npos) << "the message lists the scene's paths: " << error;
    // A position for a directional light, and a malformed path, name the scene file and the path.
    const std::string positioned = R"({"objects": [{"shape": "plane"}],
        "paths": {"p": {"keyframes": [{"time": 0, "light": {"position": [0, 5, 0]}}]}}})";
    EXPECT_NE(test::sceneErrorOf([&] { parseScene(positioned, "paths.json", "."); }).find("paths.json: paths.p"), std::string::npos);
    const std::string broken = R"({"objects": [{"shape": "plane"}], "paths": {"q": {"keyframes": [{"time": "soon"}]}}})";
    EXPECT_NE(test::sceneErrorOf([&] { parseScene(broken, "paths.json", "."); }).find("paths.json: paths.q: keyframes[0].time"),
              std::string::npos);
}

TEST(CameraPath, BuiltinDollyMovesByTheAskedFractionOfATexel) {
    const Scene scene = loadScene("cube");
    BuiltinPathOptions options;
    options.texelWorldSize = 0.01;
    options.texelsPerFrame = 0.25;
    CameraPath path;
    std::string error;
    ASSERT_TRUE(builtinPath("dolly", scene, options, path, error)) << error;
    SceneCamera a = scene.camera, b = scene.camera;
    LightInfo light = scene.light;
    applyPathState(samplePath(path, path.frameTime(3)), a, light);
    applyPathState(samplePath(path, path.frameTime(4)), b, light);
    EXPECT_NEAR(glm::length(b.position - a.position), 0.0025f, 2e-5f);
    EXPECT_NEAR(glm::dot(b.position - a.position, scene.camera.target - scene.camera.position), 0.0f, 2e-5f) << "sideways";
    ASSERT_TRUE(builtinPath("sweep", scene, {}, path, error)) << error;
    LightInfo first = scene.light, last = scene.light;
    applyPathState(samplePath(path, path.frameTime(0)), a, first);
    applyPathState(samplePath(path, path.frameTime(path.frames - 1)), a, last);
    EXPECT_NEAR(first.direction.y, -1.0f, 1e-5f) << "from the zenith";
    EXPECT_NEAR(std::asin(-last.direction.y), 2.0 * M_PI / 180.0, 1e-5) << "to 2 degrees";
    for (const std::string& name : builtinPathNames()) EXPECT_TRUE(builtinPath(name, scene, {}, path, error)) << name << ": " << error;
}

namespace {

// A ground plane z = 0 seen from above through an orthographic camera covering [0, w) x [0, h)
// world units, one pixel per unit; `shift` moves the camera by that many pixels along x.
TemporalFrame planeFrame(int w, int h, float shift) {
    TemporalFrame f;
    f.width = w;
    f.height = h;
    f.viewProjection = glm::mat4(1.0f);
    // x_ndc = (x - shift) * 2 / w - 1 + 1 / w: pixel centres at whole world x.
    f.viewProjection[0][0] = 2.0f / float(w);
    f.viewProjection[3][0] = -1.0f + (1.0f - 2.0f * shift) / float(w);
    f.viewProjection[1][1] = 2.0f / float(h);
    f.viewProjection[3][1] = -1.0f + 1.0f / float(h);
    f.eye = glm::vec3(float(w) / 2, float(h) / 2, 100.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) f.positions.push_back(glm::vec4(float(x) + shift, float(y), 0.0f, 1.0f));
    f.mask.assign(size_t(w) * size_t(h), 1);
    return f;
}

} // namespace

TEST(TemporalMetrics, ATechniqueThatChangesAsTheTruthDoesHasNoFlicker) {
    // A shadow edge fixed in the world at x = 10.3 under a camera moving 0.4 pixels a frame.
    auto shade = [](TemporalFrame& f, float edge) {
        for (const glm::vec4& p : f.positions) {
            const float v = p.x < edge ? 0.0f : 1.0f;
            f.reference.push_back(glm::vec3(v));
            f.technique.push_back(glm::vec3(v));
        }
    };
    TemporalFrame a = planeFrame(32, 8, 0.0f), b = planeFrame(32, 8, 0.4f);
    shade(a, 10.3f);
    shade(b, 10.3f);
    const TemporalFrameMetrics same = compareConsecutiveFrames(a, b);
    EXPECT_EQ(same.flicker, 0.0);
    EXPECT_GT(same.pixels, 6u * 28u);   // the last row and column have no neighbour beyond them
    // The technique's edge crawls by a whole pixel while the truth stands still: one column of 8
    // rows changes by 1 (bilinear reprojection: about 1 - 0.4 of it at the neighbours).
    TemporalFrame c = planeFrame(32, 8, 0.4f);
    for (const glm::vec4& p : c.positions) {
        c.reference.push_back(glm::vec3(p.x < 10.3f ? 0.0f : 1.0f));
        c.technique.push_back(glm::vec3(p.x < 11.3f ? 0.0f : 1.0f));
    }
    const TemporalFrameMetrics crawl = compareConsecutiveFrames(a, c);
    EXPECT_GT(crawl.flicker, 0.5 * 8.0 / double(crawl.pixels));
    EXPECT_LT(crawl.flicker, 2.0 * 8.0 / double(crawl.pixels));
    // Off-screen and disoccluded pixels do not count: a previous frame showing another surface.
    TemporalFrame far = a;
    for (glm::vec4& p : far.positions) p.z = -50.0f;
    EXPECT_EQ(compareConsecutiveFrames(far, b).pixels, 0u);
}

TEST(TemporalMetrics, NoiseEstimatesTheTemporalVariance) {
    // A constant truth and a technique of 0.5 plus independent +-0.1 each frame: variance 0.01.
    TemporalFrame a = planeFrame(64, 64, 0.0f), b = planeFrame(64, 64, 0.0f);
    uint32_t state = 12345u;
    auto coin = [&] {
        state = state * 1664525u + 1013904223u;
        return (state >> 16) & 1u ? 0.1f : -0.1f;
    };
    for (size_t i = 0; i < a.positions.size(); ++i) {
        a.reference.push_back(glm::vec3(0.5f));
        b.reference.push_back(glm::vec3(0.5f));
        a.technique.push_back(glm::vec3(0.5f + coin()));
        b.technique.push_back(glm::vec3(0.5f + coin()));
    }
    const TemporalFrameMetrics m = compareConsecutiveFrames(a, b);
    EXPECT_NEAR(m.noiseVariance, 0.01, 0.001);
    EXPECT_EQ(m.constantPixels, m.pixels);
    const TemporalSummary s = summarizeTemporal({{0.01, 0, 10, 10}, {0.05, 0, 10, 10}, {0.02, 0, 10, 10}});
    EXPECT_NEAR(s.popping, 0.04, 1e-12);
    EXPECT_EQ(s.poppingFrame, 2);
    EXPECT_EQ(s.worstFrame, 2);
    EXPECT_NEAR(s.meanFlicker, 0.08 / 3.0, 1e-12);
}

// --- the failure suite, measured (OSMesa, the cases' own small size) -------------------------

namespace {

StressSuite suite() {
    StressSuite s;
    std::string error;
    EXPECT_TRUE(loadStressSuite(defaultStressCases(), s, error)) << error;
    return s;
}

const StressCase& stressCase(const StressSuite& s, const std::string& id) {
    for (const StressCase& c : s.cases)
        if (c.id == id) return c;
    ADD_FAILURE() << "no case " << id;
    return s.cases.front();
}

StressCell run(App& app, const StressSuite& s, const std::string& id, const std::string& technique,
               const std::vector<std::string>& sets = {}) {
    StressOptions options;
    options.sets = sets;
    StressCell cell;
    std::string error;
    EXPECT_TRUE(runStressCell(app, s, stressCase(s, id), technique, options, cell, error)) << error;
    std::printf("stress %-24s %-10s %s: %s %.5f (threshold %.4f) %s\n", id.c_str(), technique.c_str(), cell.settings.c_str(),
                stressMetricName(stressCase(s, id).metric), cell.value, stressCase(s, id).threshold, cell.pass ? "pass" : "FAIL");
    return cell;
}

} // namespace

TEST(StressSuite, TheReferencePassesEveryCase) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    for (const StressCase& c : s.cases) {
        SCOPED_TRACE(c.id);
        const StressCell cell = run(*app, s, c.id, "reference");
        if (cell.skipped) continue;
        EXPECT_TRUE(cell.pass) << c.id << ": " << cell.value << " > " << c.threshold;
        EXPECT_LT(cell.falseShadow, 1e-3);
        EXPECT_LT(cell.falseLight, 1e-3);
        EXPECT_LT(cell.flicker, 1e-3) << "temporal error near zero";
        EXPECT_GT(cell.pixels, 50u) << "the case's view shows what it measures";
    }
}

TEST(StressSuite, UnsnappedFrustumMapsShimmerUnderTheSubTexelDolly) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell unsnapped = run(*app, s, "shimmer-dolly", "shadowmap", {"snap=0"});
    const StressCell snapped = run(*app, s, "shimmer-dolly", "shadowmap", {"snap=1"});
    EXPECT_FALSE(unsnapped.pass);
    EXPECT_TRUE(snapped.pass);
    EXPECT_LT(snapped.flicker, 0.5 * unsnapped.flicker);
}

TEST(StressSuite, ZeroBiasFailsTheGrazingLight) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell zero = run(*app, s, "acne-5", "shadowmap", {"constant_bias=0", "slope_bias=0"});
    EXPECT_FALSE(zero.pass);
    EXPECT_GT(zero.falseShadow, 0.05) << "acne: lit ground drawn shadowed";
}

TEST(StressSuite, VsmWithoutBleedingReductionFailsOverlap) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell bleeding = run(*app, s, "overlap", "vsm", {"light_bleeding=0"});
    EXPECT_FALSE(bleeding.pass);
}

// --- the tuned cases: each separates a technique the literature says fails from one it does not.
// Thresholds and the figures behind them: docs/stability.md ("Tuning the thresholds").

TEST(StressSuite, ASceneFitMapFailsPerspectiveNearWhereWarpsAndCascadesPass) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell uniform = run(*app, s, "perspective-near", "shadowmap");
    const StressCell lispsm = run(*app, s, "perspective-near", "lispsm");
    const StressCell csm = run(*app, s, "perspective-near", "csm");
    // psm scored 0.81 (no shadow at all near the camera) while psm::nearestReceiverDepth skipped
    // plane receivers and pushed the near plane from the ground (0.12 m) to the wall (2.05 m);
    // measured since: 0.0141, m 1.48 in the nearest third.
    const StressCell psm = run(*app, s, "perspective-near", "psm");
    EXPECT_FALSE(uniform.pass);
    EXPECT_TRUE(lispsm.pass);
    EXPECT_TRUE(csm.pass);
    EXPECT_TRUE(psm.pass);
    ASSERT_GT(psm.footprintPixels, 0u);
    EXPECT_GT(uniform.footprintNear, 10.0 * psm.footprintNear);
    // The texel footprint m says why: one texel of the scene-fit map spreads over tens of pixels
    // in the nearest third, the warped map's over a few.
    ASSERT_GT(uniform.footprintPixels, 0u);
    ASSERT_GT(lispsm.footprintPixels, 0u);
    EXPECT_GT(uniform.footprintNear, 20.0);
    EXPECT_GT(uniform.footprintNear, 10.0 * lispsm.footprintNear);
    EXPECT_GT(uniform.footprintNear, csm.footprintNear);
    // A technique without maps reports no m.
    EXPECT_EQ(run(*app, s, "perspective-near", "reference").footprintPixels, 0u);
}

// The literature names psm as failing here (casters behind the camera plane are lost unless the
// virtual camera moves back over them, seed 002 sec. 7.2.2). The case runs psm with move_back=0,
// which shows that failure; with the move-back (psm's default) it keeps the tower. psm failed this
// case with the move-back too (MAE 0.103, false light 0.089) only while the ground was skipped for
// its near plane (psm::nearestReceiverDepth), leaving the ground at the camera's feet outside the
// map (docs/stability.md).
TEST(StressSuite, LightBehindLosesTheTowerWithoutPsmsMoveBack) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell psm = run(*app, s, "light-behind", "psm");
    const StressCell movedBack = run(*app, s, "light-behind", "psm", {"move_back=1"});
    const StressCell lispsm = run(*app, s, "light-behind", "lispsm");
    const StressCell uniform = run(*app, s, "light-behind", "shadowmap");   // fit=focus-body: the same B
    const StressCell none = run(*app, s, "light-behind", "none");
    EXPECT_FALSE(psm.pass) << "without the move-back the tower behind the camera is clipped";
    EXPECT_GT(psm.falseLight, 0.05) << "its shadow in front of the viewer is lost";
    EXPECT_TRUE(movedBack.pass);
    EXPECT_LT(movedBack.falseLight, 0.01) << "the tower's shadow near the camera is kept";
    EXPECT_FALSE(none.pass) << "the case has shadow to lose";
    EXPECT_TRUE(lispsm.pass);
    EXPECT_TRUE(uniform.pass);
}

TEST(StressSuite, SingleMapsLoseTheFarThirdOfAHugeDepthRangeWhereCascadesDoNot) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell psm = run(*app, s, "depth-far", "psm");
    const StressCell uniform = run(*app, s, "depth-far", "shadowmap");
    const StressCell csm = run(*app, s, "depth-far", "csm");
    const StressCell none = run(*app, s, "depth-far", "none");
    EXPECT_FALSE(psm.pass);
    EXPECT_FALSE(uniform.pass);
    EXPECT_TRUE(csm.pass);
    EXPECT_LT(csm.maeFar, 0.6 * none.maeFar) << "the far cascade keeps shadows in the far third";
    EXPECT_GT(psm.maeFar, 0.9 * none.maeFar) << "psm keeps (almost) none there";
}

TEST(StressSuite, MapsRefittedToTheViewPopUnderTheOrbitAndASceneFitMapDoesNot) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell focused = run(*app, s, "popping-orbit", "shadowmap");   // fit=focus-body snap=1
    const StressCell scene = run(*app, s, "popping-orbit", "shadowmap", {"fit=scene"});
    const StressCell lispsm = run(*app, s, "popping-orbit", "lispsm");
    EXPECT_FALSE(focused.pass);
    EXPECT_FALSE(lispsm.pass);
    EXPECT_TRUE(scene.pass);
    EXPECT_LT(scene.popping, 1e-4) << "the same map every frame: nothing jumps";
}

// --- the six cases whose claims now name techniques (docs/stability.md, "Which technique fails
// which case"): a technique each claim names as failing fails, one it names as doing better passes.

// The claim names psm as failing (seed 002 sec. 8.3: no reparameterisation helps with view and
// light parallel, and PSM's warp makes it worse). Measured, psm passes: it failed (0.0700) only
// while its near plane skipped the ground (psm::nearestReceiverDepth); with the near plane on the
// nearest receiver its map here is as good as the focused uniform map or better (0.0016 against
// 0.0040 on llvmpipe and on the H200). The page marks the cell "(claim: fails)".
TEST(StressSuite, DuellingFrustaLispsmDegeneratesToTheUniformMapAndPsmDoesNotFail) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell psm = run(*app, s, "duelling-frusta", "psm");
    const StressCell lispsm = run(*app, s, "duelling-frusta", "lispsm");
    const StressCell uniform = run(*app, s, "duelling-frusta", "shadowmap");
    EXPECT_TRUE(psm.pass) << "measured: the claim's failure does not show here (see above)";
    EXPECT_TRUE(lispsm.pass);
    EXPECT_TRUE(uniform.pass);
    // Seed 002 sec. 8.3: with view and light parallel LiSPSM is (nearly) the uniform map.
    EXPECT_LT(std::abs(lispsm.mae - uniform.mae), 0.25 * stressCase(s, "duelling-frusta").threshold);
}

TEST(StressSuite, MomentMapsAndAdaptivePcfLoseTheThinPolesContactShadow) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell none = run(*app, s, "contact-pole", "none");
    const StressCell vsm = run(*app, s, "contact-pole", "vsm");
    const StressCell adaptive = run(*app, s, "contact-pole", "adaptive-pcf");
    const StressCell uniform = run(*app, s, "contact-pole", "shadowmap");
    const StressCell pcf = run(*app, s, "contact-pole", "pcf");
    EXPECT_FALSE(vsm.pass);
    EXPECT_FALSE(adaptive.pass);
    EXPECT_TRUE(uniform.pass);
    EXPECT_TRUE(pcf.pass);
    EXPECT_GT(vsm.falseLight, 0.8 * none.falseLight) << "VSM leaks (nearly) all of the shadow at the pole's foot";
}

TEST(StressSuite, PlanarShadowsCannotSelfShadowTheDragonWhereAPlainMapCan) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell planar = run(*app, s, "self-shadow-dragon-like", "planar");
    const StressCell vsm = run(*app, s, "self-shadow-dragon-like", "vsm");
    const StressCell uniform = run(*app, s, "self-shadow-dragon-like", "shadowmap");
    EXPECT_FALSE(planar.pass);
    EXPECT_FALSE(vsm.pass);
    EXPECT_TRUE(uniform.pass);
    EXPECT_GT(planar.falseLight, 0.05) << "the creature's shadows on itself are missing: false light";
}

TEST(StressSuite, FilteredMapsShimmerUnderTheLightSweepWhereAHardMapFollowsIt) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell pcf = run(*app, s, "shimmer-sweep", "pcf");
    const StressCell uniform = run(*app, s, "shimmer-sweep", "shadowmap");
    EXPECT_FALSE(pcf.pass);
    EXPECT_TRUE(uniform.pass);
    EXPECT_GT(pcf.flicker, 2.0 * uniform.flicker);
}

TEST(StressSuite, UniformMapsLoseTheNearThirdOfAHugeDepthRangeWhereWarpsDoNot) {
    const StressSuite s = suite();
    auto app = test::makeHeadlessApp("cube", s.size);
    ASSERT_TRUE(app);
    const StressCell uniform = run(*app, s, "depth-near", "shadowmap");
    const StressCell psm = run(*app, s, "depth-near", "psm");
    const StressCell lispsm = run(*app, s, "depth-near", "lispsm");
    EXPECT_FALSE(uniform.pass);
    EXPECT_TRUE(psm.pass);
    EXPECT_TRUE(lispsm.pass);
}

// Every case names the techniques its claim is about (issue 12: "each case states which technique
// the literature says fails there and why"), by ids of techniques that exist, and cites its seed.
TEST(StressSuite, EveryCaseNamesTheTechniquesItsClaimIsAbout) {
    const StressSuite s = suite();
    std::set<std::string> ids = {"reference"};
    for (const TechniqueInfo& t : scanPlugins(pluginDir()).techniques) ids.insert(t.id);
    ASSERT_GT(ids.size(), 10u);
    for (const StressCase& c : s.cases) {
        SCOPED_TRACE(c.id);
        EXPECT_FALSE(c.expectedToFail.empty() && c.expectedToPass.empty()) << "the claim names no technique";
        for (const auto* list : {&c.expectedToFail, &c.expectedToPass})
            for (const std::string& id : *list) EXPECT_TRUE(ids.count(id)) << "'" << id << "' is not a technique";
        EXPECT_TRUE(c.source.find("seed 00") != std::string::npos || c.claim.find("seed 00") != std::string::npos)
            << "the claim cites no seed";
    }
    // The six that named none before name a failing technique now.
    for (const char* id : {"depth-near", "duelling-frusta", "shimmer-sweep", "contact-pole", "self-shadow-dragon-like",
                           "self-shadow-stanford"})
        EXPECT_FALSE(stressCase(s, id).expectedToFail.empty()) << id;
}

TEST(StressSuite, ACaseCannotClaimATechniqueBothFailsAndPasses) {
    StressSuite s;
    std::string error;
    const auto node = nlohmann::json::parse(R"({"cases": [{"id": "x", "title": "t", "scene": "cube", "metric": "mae",
        "threshold": 0.1, "expectedToFail": ["psm"], "expectedToPass": ["psm"], "claim": "c", "source": "s"}]})");
    EXPECT_FALSE(parseStressSuite(node, "cases.json", s, error));
    EXPECT_NE(error.find("cases[0].expectedToPass"), std::string::npos) << error;
    const auto footprint = nlohmann::json::parse(R"({"cases": [{"id": "x", "title": "t", "scene": "cube", "metric": "mae",
        "threshold": 0.1, "footprint": 1, "claim": "c", "source": "s"}]})");
    EXPECT_FALSE(parseStressSuite(footprint, "cases.json", s, error));
    EXPECT_NE(error.find("cases[0].footprint"), std::string::npos) << error;
}
