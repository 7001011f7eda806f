// Cascaded shadow maps and point-light cube maps, rendered (llvmpipe): csm's cascades cover every
// visible pixel of their slices and beat one map of as many texels near the viewer on forest-002;
// stabilised cascades shimmer less along a slow dolly; the cube-map path of shadowmap, pcf and csm
// against the Embree reference on `point-light`; memory counting six faces and every array layer.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "../plugins/csm/csm_shared.h"
#include "shadowlab/kit/cascades.h"
#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/depth_map.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

size_t techniqueBytes(App& app, const std::string& id) {
    std::string error;
    LoadedTechnique* loaded = app.techniques().get(id, error);
    EXPECT_TRUE(loaded) << error;
    return loaded ? loaded->host().gpuBytes() : 0;
}

float viewDepth(const CameraInfo& camera, glm::vec3 p) { return -(camera.view * glm::vec4(p, 1.0f)).z; }

} // namespace

// Every visible pixel of forest-002 lies in the map of the cascade its view depth picks, for the
// fits csm uses (tight and stabilised, slices clipped to the scene or not), on the frame's real
// camera and the host's scene bounds: no pixel of a slice falls outside its cascade's map.
TEST(CsmRender, EveryCascadeCoversTheVisiblePixelsOfItsSlice) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("csm", error)) << error;
    const CameraInfo camera = app->lastFrame().camera;
    const LightInfo light = app->lastFrame().light;
    const Bounds scene = app->renderer().bounds(DrawSet::All);
    const Bounds casters = app->renderer().bounds(DrawSet::Casters);
    const auto positions = test::readTarget(*app, MainTarget::Position);
    for (const bool clipToScene : {false, true})
        for (const bool stabilise : {false, true}) {
            SCOPED_TRACE(testing::Message() << "clip " << clipToScene << " stabilise " << stabilise);
            const kit::DepthRange range = clipToScene ? kit::visibleDepthRange(camera, scene)
                                                      : kit::DepthRange{camera.nearPlane, camera.farPlane};
            const int count = 4;
            const kit::CascadeRanges ranges = kit::cascadeRanges(range.nearDistance, range.farDistance, count, 0.75f, 0.1f);
            std::vector<kit::Cascade> cascades;
            for (int i = 0; i < count; ++i)
                cascades.push_back(kit::fitDirectionalCascade(camera, kit::stableLightView(light), ranges.fitBegin[size_t(i)],
                                                              ranges.splits[size_t(i) + 1],
                                                              {.resolution = 1024, .stabilise = stabilise, .clipToScene = clipToScene},
                                                              scene, casters));
            size_t checked = 0, outside = 0;
            std::array<size_t, 4> perCascade{};
            for (const glm::vec4& p : positions) {
                if (p.w < 0.5f) continue;
                const float depth = viewDepth(camera, glm::vec3(p));
                int i = 0;
                while (i < count - 1 && depth > ranges.splits[size_t(i) + 1]) ++i;
                ++checked;
                ++perCascade[size_t(i)];
                const glm::vec4 clip = cascades[size_t(i)].light.viewProjection * glm::vec4(glm::vec3(p), 1.0f);
                const glm::vec3 ndc = glm::vec3(clip) / clip.w;
                outside += std::abs(ndc.x) > 1.0f || std::abs(ndc.y) > 1.0f || std::abs(ndc.z) > 1.0f;
            }
            EXPECT_GT(checked, 20000u);
            EXPECT_EQ(outside, 0u);
            // The nearest cascade (0.1 to about 5 m) sees no ground from 9 m up; the others do.
            for (int i = 1; i < count; ++i) EXPECT_GT(perCascade[size_t(i)], 100u) << "cascade " << i << " serves pixels";
        }
}

// Seed 002's forest at equal total texels (issue 16): four 256 cascades against one 512 map
// focused on the focus body, hard reference (small maps, so that the map's texels rather than the
// 256 x 160 image's pixels limit the error). Cascades put their texels near the viewer, so the
// near third's error is lower (tight cascades); the debug colours tint by cascade (at least three
// in view).
TEST(CsmRender, FourCascadesBeatOneFocusedMapOfAsManyTexelsNearTheViewer) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    using Mode = ReferenceOptions::Mode;
    const AccuracyMetrics single =
        test::measureAccuracy(*app, "shadowmap", {"fit=focus-body", "resolution=512", "cull=front"}, Mode::Hard);
    const AccuracyMetrics stable = test::measureAccuracy(*app, "csm", {"resolution=256", "cascades=4", "cull=front"}, Mode::Hard);
    const AccuracyMetrics tight =
        test::measureAccuracy(*app, "csm", {"resolution=256", "cascades=4", "cull=front", "snap=0"}, Mode::Hard);
    std::printf("forest-002 hard MAE near/mid/far third: shadowmap focus-body 512 %.4f/%.4f/%.4f, csm 4x256 stabilised "
                "%.4f/%.4f/%.4f, tight %.4f/%.4f/%.4f\n",
                single.maeByViewDepth[0], single.maeByViewDepth[1], single.maeByViewDepth[2], stable.maeByViewDepth[0],
                stable.maeByViewDepth[1], stable.maeByViewDepth[2], tight.maeByViewDepth[0], tight.maeByViewDepth[1],
                tight.maeByViewDepth[2]);
    EXPECT_LT(tight.maeByViewDepth[0], 0.8 * single.maeByViewDepth[0]);
    // Stabilised cascades pay for standing still: the square around each whole slice's sphere
    // (sky included) holds about a third of the tight rectangle's texel density here, and they lose
    // to the single focused map (measured 0.033 against 0.025 near); only bounded here.
    EXPECT_LT(stable.maeByViewDepth[0], 2.0 * single.maeByViewDepth[0]);

    // Cascade colours: the lit ground's hue per cascade; four distinct tints among the pixels.
    const auto visibility = test::renderVisibility(*app, "csm", {"resolution=256", "cascades=4", "debug_colours=1"});
    std::set<std::tuple<int, int, int>> tints;
    for (const glm::vec4& v : visibility)
        if (v.a > 0.5f && v.r + v.g + v.b > 1.5f) tints.insert({int(v.r * 4.0f), int(v.g * 4.0f), int(v.b * 4.0f)});
    EXPECT_GE(tints.size(), 3u);
}

// fit = sdsm: the depth range from the GPU reduction of the camera pre-pass, read back frames
// later. After a few frames the splits follow what the camera sees (forest-002: from about 0.3 m,
// not the near plane's 0.1 m, to the farthest visible tree); the near third is no worse than the
// focus-body fit's, and the reduction is a timed pass of its own.
TEST(CsmRender, SampleDistributionFitFromTheDepthReduction) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"fit=sdsm", "cull=front"}, "csm", error)) << error;
    for (int frame = 0; frame < 2; ++frame) ASSERT_TRUE(app->renderFrame("csm", error)) << error;
    const AccuracyMetrics sdsm = test::measureAccuracy(*app, "csm", {"fit=sdsm", "cull=front"}, ReferenceOptions::Mode::Hard);
    const AccuracyMetrics focus = test::measureAccuracy(*app, "csm", {"fit=focus-body", "cull=front"}, ReferenceOptions::Mode::Hard);
    std::printf("forest-002 csm hard MAE near third: sdsm %.4f, focus-body %.4f (all %.4f, %.4f)\n", sdsm.maeByViewDepth[0],
                focus.maeByViewDepth[0], sdsm.mae, focus.mae);
    EXPECT_LT(sdsm.mae, 0.05);
    EXPECT_LT(sdsm.falseLightRate, 0.02) << "no pixel left outside the cascades";
    EXPECT_LE(sdsm.maeByViewDepth[0], focus.maeByViewDepth[0] * 1.1);
}

// Shimmer: a slow dolly (2 cm a frame along the view, forest-002) and the mean per-pixel change of
// the shadow term between consecutive frames. The scene is static, so what changes is parallax
// (the same for both) and the texel grid sliding under unstabilised cascades.
TEST(CsmRender, StabilisedCascadesShimmerLessAlongASlowDolly) {
    auto temporalChange = [](bool snap) {
        auto app = test::makeHeadlessApp("forest-002", {256, 160});
        EXPECT_TRUE(app);
        app->camera().setMode(CameraController::Mode::Fly);
        std::string error;
        const std::vector<std::string> sets = {snap ? "snap=1" : "snap=0", "cull=front", "resolution=512"};
        std::vector<glm::vec4> previous = test::renderVisibility(*app, "csm", sets);
        double change = 0.0;
        size_t pixels = 0;
        for (int frame = 0; frame < 4; ++frame) {
            app->camera().fly({0.0f, 0.0f, 1.0f}, 0.02f / app->camera().flySpeed);
            const auto current = test::renderVisibility(*app, "csm", sets);
            for (size_t i = 0; i < current.size(); ++i)
                if (current[i].a > 0.5f && previous[i].a > 0.5f) {
                    change += std::abs(current[i].r - previous[i].r);
                    ++pixels;
                }
            previous = current;
        }
        return change / double(std::max<size_t>(pixels, 1));
    };
    const double stabilised = temporalChange(true), unstabilised = temporalChange(false);
    std::printf("forest-002 dolly, mean |shadow term change| per pixel and frame: stabilised %.5f, unstabilised %.5f\n",
                stabilised, unstabilised);
    EXPECT_LT(stabilised, unstabilised);
}

// Point lights: the cube-map path against the hard Embree reference on `point-light` (a lamp
// 2.8 m up among pillars: shadows all round it, on the floor and the walls).
TEST(PointLight, CubeMapShadowsAgainstTheReference) {
    auto app = test::makeHeadlessApp("point-light", {320, 240});
    ASSERT_TRUE(app);
    ASSERT_EQ(app->light().type, LightType::Point);
    struct Case {
        const char* id;
        std::vector<std::string> sets;
        double mae, falseShadow, falseLight;
    };
    const std::vector<Case> cases = {
        // Measured on llvmpipe (MAE, false shadow, false light): shadowmap (2048 faces) 0.0006,
        // 0.0004, 0.0002; pcf (5 x 5, a ramp against the hard reference) 0.0055, 0.0003, 0.0003;
        // csm (its default 1024 faces: acne at grazing angles) 0.0045, 0.0041, 0.0004.
        {"shadowmap", {}, 0.003, 0.002, 0.002},
        {"pcf", {}, 0.012, 0.002, 0.002},
        {"csm", {}, 0.007, 0.007, 0.002},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.id);
        const AccuracyMetrics m = test::measureAccuracy(*app, c.id, c.sets, ReferenceOptions::Mode::Hard);
        std::printf("point-light %s: hard MAE %.4f, false shadow %.4f, false light %.4f, compared %.2f\n", c.id, m.mae,
                    m.falseShadowRate, m.falseLightRate, m.comparedFraction);
        EXPECT_LT(m.mae, c.mae);
        EXPECT_LT(m.falseShadowRate, c.falseShadow);
        EXPECT_LT(m.falseLightRate, c.falseLight);
        EXPECT_GT(m.comparedFraction, 0.5);
    }
    // For comparison, a technique still on one perspective frustum (lispsm's uniform fallback;
    // measured 0.0037, 0.0011, 0.0027: the lamp is high enough for one 80-degree frustum to see
    // the room, with stretched texels towards its edge).
    const AccuracyMetrics single = test::measureAccuracy(*app, "lispsm", {}, ReferenceOptions::Mode::Hard);
    std::printf("point-light lispsm (one frustum): hard MAE %.4f, false shadow %.4f, false light %.4f\n", single.mae,
                single.falseShadowRate, single.falseLightRate);
}

// The host counts what the techniques allocate exactly: the cube's six faces, every layer of the
// cascades' array (and nothing else but the techniques' small buffers; the cube path's block only
// once a point light needed it).
TEST(CsmRender, MemoryCountsSixFacesAndEveryArrayLayer) {
    using kit::CubeDepthMapUniforms;
    using kit::DepthMapUniforms;
    const size_t res = 512, texel = 4;   // GL_DEPTH_COMPONENT32F
    {
        auto app = test::makeHeadlessApp("point-light", {160, 120});
        ASSERT_TRUE(app);
        test::renderVisibility(*app, "shadowmap", {"resolution=512"});
        EXPECT_EQ(techniqueBytes(*app, "shadowmap"),
                  6 * res * res * texel + sizeof(DepthMapUniforms) + sizeof(CubeDepthMapUniforms));
        test::renderVisibility(*app, "csm", {"resolution=512"});
        EXPECT_EQ(techniqueBytes(*app, "csm"), 6 * res * res * texel + sizeof(shared::csm::CsmUniforms) +
                                                   3 * 2 * sizeof(uint32_t) + sizeof(CubeDepthMapUniforms));
    }
    auto app = test::makeHeadlessApp("cube", {160, 120});
    ASSERT_TRUE(app);
    for (const int cascades : {3, 8, 2}) {
        SCOPED_TRACE(cascades);
        test::renderVisibility(*app, "csm", {"resolution=512", "cascades=" + std::to_string(cascades)});
        EXPECT_EQ(techniqueBytes(*app, "csm"),
                  size_t(cascades) * res * res * texel + sizeof(shared::csm::CsmUniforms) + 3 * 2 * sizeof(uint32_t));
    }
}
