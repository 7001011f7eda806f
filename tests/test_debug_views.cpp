// The classroom's debug views of issue 14 that show what a technique computes, not only its maps:
// the focus body B (seed 002 eq. 4.2) drawn in the camera view (`focus-body`), and the filter
// kernel's footprint around a probed pixel (`kernel`, render/kernel_probe.h): its numbers must be
// the technique's own (the probe's filtered value equals the shader's shadow term at that pixel),
// its sizes the technique's parameters, and what is drawn must lie where the geometry projects.
#include <algorithm>

#include <gtest/gtest.h>

#include <shadowlab/kit/focus.h>

#include "render/kernel_probe.h"
#include "render/light_space.h"
#include "render/shadow_map_views.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

// Pixels of `image` (bottom-up rows, RGBA8) whose colour is `colour` within `tolerance` levels.
std::vector<glm::ivec2> pixelsOfColour(const Image& image, glm::vec3 colour, int tolerance) {
    std::vector<glm::ivec2> found;
    const glm::ivec3 target = glm::ivec3(glm::round(colour * 255.0f));
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const uint8_t* p = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * 4];
            if (std::abs(p[0] - target.r) <= tolerance && std::abs(p[1] - target.g) <= tolerance &&
                std::abs(p[2] - target.b) <= tolerance)
                found.push_back({x, y});
        }
    return found;
}

// A world segment in GL window pixels (bottom-up), clipped to the camera's near plane (z >= -w).
bool projectSegment(const glm::mat4& viewProjection, glm::ivec2 size, glm::vec3 a, glm::vec3 b, glm::vec2& pa, glm::vec2& pb) {
    glm::vec4 ca = viewProjection * glm::vec4(a, 1.0f), cb = viewProjection * glm::vec4(b, 1.0f);
    const float da = ca.z + ca.w, db = cb.z + cb.w;
    if (da < 0.0f && db < 0.0f) return false;
    if (da < 0.0f) ca = glm::mix(ca, cb, da / (da - db));
    if (db < 0.0f) cb = glm::mix(cb, ca, db / (db - da));
    auto toPixel = [&](glm::vec4 c) { return (glm::vec2(c) / c.w * 0.5f + 0.5f) * glm::vec2(size); };
    pa = toPixel(ca);
    pb = toPixel(cb);
    return true;
}

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
    const glm::vec2 ab = b - a;
    const float t = glm::dot(ab, ab) > 0.0f ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0f, 1.0f) : 0.0f;
    return glm::distance(p, a + t * ab);
}

Image presentAndRead(App& app, const std::string& technique, const std::string& view) {
    std::string error;
    EXPECT_TRUE(app.presentView(technique, viewFromName(view), ~0u, {}, error)) << error;
    return app.readDisplay();
}

// GL pixel (bottom-up) -> the probe's top-left pixel.
glm::ivec2 topLeft(App& app, glm::ivec2 gl) { return {gl.x, app.renderer().size().y - 1 - gl.y}; }

// Probes `technique`'s kernel at GL pixel `gl` through the kernel view, as the window and --probe do.
KernelProbe probeAt(App& app, const std::string& technique, glm::ivec2 gl) {
    app.setProbePixel(topLeft(app, gl));
    presentAndRead(app, technique, "kernel");
    return app.lastProbe();
}

} // namespace

// B's white edges lie on B's projected edges, and B's visible edges are drawn: B computed here
// from the frame's camera, light and scene bounds (kit::focusBody), projected with the frame's
// camera. With fit = scene there is no B and nothing white.
TEST(FocusBodyView, TheWhiteOutlineIsWhereBsEdgesProject) {
    auto app = test::makeHeadlessApp("pillars", {480, 270});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"fit=focus-body", "snap=0"}, "shadowmap", error)) << error;
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    const Image image = presentAndRead(*app, "shadowmap", "focus-body");
    const glm::ivec2 size = app->renderer().size();

    const FrameContext& frame = app->lastFrame();
    const Bounds scene = app->renderer().bounds(DrawSet::All), casters = app->renderer().bounds(DrawSet::Casters);
    const kit::ConvexBody body = kit::focusBody(frame.camera, frame.light, scene, fitLightSpace(frame.light, scene, &casters));
    ASSERT_FALSE(body.empty());
    const std::vector<glm::vec3> edges = kit::bodyEdges(body);
    ASSERT_GE(edges.size(), 24u) << "B has at least a box's 12 edges";
    std::vector<std::pair<glm::vec2, glm::vec2>> projected;
    std::vector<bool> onNearPlane;   // edges of B's face on the camera's near plane: clipping may drop them
    for (size_t i = 0; i + 1 < edges.size(); i += 2) {
        glm::vec2 a, b;
        if (!projectSegment(frame.camera.viewProjection, size, edges[i], edges[i + 1], a, b)) continue;
        projected.push_back({a, b});
        const glm::vec4 ca = frame.camera.viewProjection * glm::vec4(edges[i], 1.0f);
        const glm::vec4 cb = frame.camera.viewProjection * glm::vec4(edges[i + 1], 1.0f);
        onNearPlane.push_back(ca.z / ca.w < -0.999f && cb.z / cb.w < -0.999f);
    }
    ASSERT_FALSE(projected.empty());

    const std::vector<glm::ivec2> white = pixelsOfColour(image, overlay_colour::kFocusBody, 6);
    ASSERT_GT(white.size(), 200u) << "B's outline is drawn";
    size_t onEdge = 0;
    for (const glm::ivec2& p : white) {
        float nearest = 1e30f;
        for (const auto& [a, b] : projected) nearest = std::min(nearest, distanceToSegment(glm::vec2(p) + 0.5f, a, b));
        if (nearest <= 1.5f) ++onEdge;
    }
    EXPECT_GE(double(onEdge), 0.98 * double(white.size())) << "white pixels lie on B's projected edges";

    // Every projected edge inside the image (2 px in from its border) has its pixels drawn.
    size_t samples = 0, drawn = 0;
    std::vector<uint8_t> isWhite(size_t(size.x) * size_t(size.y), 0);
    for (const glm::ivec2& p : white) isWhite[size_t(p.y) * size_t(size.x) + size_t(p.x)] = 1;
    for (size_t e = 0; e < projected.size(); ++e) {
        if (onNearPlane[e]) continue;
        const auto& [a, b] = projected[e];
        const int steps = int(glm::distance(a, b) / 3.0f);
        for (int k = 1; k < steps; ++k) {
            const glm::vec2 p = glm::mix(a, b, float(k) / float(steps));
            if (p.x < 3 || p.y < 3 || p.x > float(size.x - 4) || p.y > float(size.y - 4)) continue;
            ++samples;
            bool hit = false;
            for (int dy = -1; dy <= 1 && !hit; ++dy)
                for (int dx = -1; dx <= 1 && !hit; ++dx)
                    hit = isWhite[size_t(int(p.y) + dy) * size_t(size.x) + size_t(int(p.x) + dx)] != 0;
            drawn += hit ? 1 : 0;
        }
    }
    ASSERT_GT(samples, 50u) << "some of B's edges cross the view";
    EXPECT_GE(double(drawn), 0.97 * double(samples)) << "B's edges in the view are drawn";

    // The scene fit has no B: no white, but the map's volume is still drawn.
    ASSERT_TRUE(app->applyAssignments({"fit=scene"}, "shadowmap", error)) << error;
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    const Image sceneFit = presentAndRead(*app, "shadowmap", "focus-body");
    EXPECT_LT(pixelsOfColour(sceneFit, overlay_colour::kFocusBody, 6).size(), 5u);
    EXPECT_NE(app->debugViewsOf("shadowmap").find("coverage"), std::string::npos);
    EXPECT_EQ(app->debugViewsOf("shadowmap").find("focus-body"), std::string::npos);
}

// The moment maps report B too (kit::MomentMap), and every single-map technique's descriptor
// names the views (TechniqueDesc::debugViews; the explanations no longer repeat them).
TEST(FocusBodyView, MomentMapsReportBAndExplanationsNameTheViews) {
    auto app = test::makeHeadlessApp("pillars", {320, 180});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"fit=focus-body"}, "vsm", error)) << error;
    ASSERT_TRUE(app->renderFrame("vsm", error)) << error;
    EXPECT_NE(app->debugViewsOf("vsm").find("focus-body"), std::string::npos) << app->debugViewsOf("vsm");
    EXPECT_GT(pixelsOfColour(presentAndRead(*app, "vsm", "focus-body"), overlay_colour::kFocusBody, 6).size(), 100u);
    for (const char* id : {"shadowmap", "pcf", "adaptive-pcf", "pcss", "vsm", "esm", "evsm", "msm", "csm"}) {
        const TechniqueInfo* info = app->techniques().find(id);
        ASSERT_TRUE(info) << id;
        EXPECT_TRUE(info->debugViewsDeclared) << id;
        EXPECT_EQ(info->explanation.find("Debug views:"), std::string::npos) << id;
        const auto& views = info->debugViews;
        for (const char* view : {"footprint", "texel-grid", "coverage"})
            EXPECT_NE(std::find(views.begin(), views.end(), view), views.end()) << id << " " << view;
        const bool focusBody = std::find(views.begin(), views.end(), "focus-body") != views.end();
        EXPECT_TRUE(std::string(id) == "csm" || focusBody) << id;
    }
    for (const char* id : {"pcf", "adaptive-pcf", "pcss"}) {
        const auto& views = app->techniques().find(id)->debugViews;
        EXPECT_NE(std::find(views.begin(), views.end(), "kernel"), views.end()) << id;
    }
}

namespace {

// Pixels of the cube scene's ground, in GL coordinates, whose shadow term is in (lo, hi).
std::vector<glm::ivec2> groundPixelsWithTerm(App& app, float lo, float hi, size_t stride) {
    const auto positions = test::readTarget(app, MainTarget::Position);
    const auto normals = test::readTarget(app, MainTarget::Normal);
    const auto visibility = test::readTarget(app, MainTarget::Visibility);
    const glm::ivec2 size = app.renderer().size();
    std::vector<glm::ivec2> found;
    for (int y = 2; y < size.y - 2; ++y)
        for (int x = 2; x < size.x - 2; ++x) {
            const size_t i = size_t(y) * size_t(size.x) + size_t(x);
            if (positions[i].w < 0.5f || normals[i].y < 0.99f || std::abs(positions[i].y) > 1e-3f) continue;
            if (visibility[i].r > lo && visibility[i].r < hi) found.push_back({x, y});
        }
    std::vector<glm::ivec2> picked;
    for (size_t k = 0; k < found.size(); k += std::max<size_t>(stride, 1)) picked.push_back(found[k]);
    return picked;
}

float shadowTermAt(App& app, glm::ivec2 gl) {
    const auto visibility = test::readTarget(app, MainTarget::Visibility);
    return visibility[size_t(gl.y) * size_t(app.renderer().size().x) + size_t(gl.x)].r;
}

// The probe's filtered value against the shader's at pixels of the penumbra: the host re-evaluates
// the same taps, so they agree.
void expectProbeMatchesTheShader(App& app, const std::string& technique, FilterKernel kernel, float tolerance) {
    const std::vector<glm::ivec2> penumbra = groundPixelsWithTerm(app, 0.02f, 0.98f, 7);
    ASSERT_GT(penumbra.size(), 10u) << technique << " has a penumbra on the ground";
    size_t agree = 0, checked = 0;
    for (const glm::ivec2& p : penumbra) {
        if (checked == 40) break;
        const float term = shadowTermAt(app, p);
        const KernelProbe probe = probeAt(app, technique, p);
        ASSERT_TRUE(probe.valid) << probe.problem;
        EXPECT_EQ(probe.kernel, kernel);
        ++checked;
        if (std::abs(probe.lit - term) <= tolerance) ++agree;
    }
    std::printf("%s: the probe equals the shader's shadow term (within %.4f) at %zu of %zu penumbra pixels\n",
                technique.c_str(), double(tolerance), agree, checked);
    EXPECT_GE(double(agree), 0.9 * double(checked)) << technique << ": " << agree << " of " << checked
                                                    << " probes equal the shader's shadow term";
}

} // namespace

// PCF: the box is n texels wide (n + 1 with bilinear taps, the texels they blend), n^2 samples, and
// the probe's average is the shader's; the yellow box is drawn around the probed point.
TEST(KernelProbe, PcfBoxIsTheKernelsTexelsAndItsAverageIsTheShaders) {
    auto app = test::makeHeadlessApp("cube", {320, 240});
    ASSERT_TRUE(app);
    std::string error;
    for (int n : {3, 5, 7}) {
        SCOPED_TRACE(n);
        ASSERT_TRUE(app->applyAssignments({"kernel=" + std::to_string(n), "offset_scale=1", "hardware_filter=0",
                                           "sampling=taps", "cone_bias=1", "fit=scene", "resolution=256"},
                                          "pcf", error))
            << error;
        ASSERT_TRUE(app->renderFrame("pcf", error)) << error;
        const std::vector<glm::ivec2> penumbra = groundPixelsWithTerm(*app, 0.02f, 0.98f, 1);
        ASSERT_FALSE(penumbra.empty());
        const glm::ivec2 pixel = penumbra[penumbra.size() / 2];
        const KernelProbe probe = probeAt(*app, "pcf", pixel);
        ASSERT_TRUE(probe.valid) << probe.problem;
        EXPECT_EQ(probe.kernel, FilterKernel::Box);
        EXPECT_EQ(probe.n, n);
        EXPECT_FLOAT_EQ(probe.kernelTexels, float(n));
        EXPECT_EQ(probe.samplesTaken, n * n);
        EXPECT_EQ(probe.taps.size(), size_t(n * n));
        EXPECT_NEAR((probe.boxMax.x - probe.boxMin.x) * 256.0f, float(n), 1e-3f);
        EXPECT_LE(probe.boxMin.x, probe.coord.x);
        EXPECT_GE(probe.boxMax.x, probe.coord.x);
        // With nearest taps the average has n^2 + 1 values: the shader's is one of them, the same.
        EXPECT_NEAR(probe.lit, shadowTermAt(*app, pixel), 0.5f / float(n * n));

        // The drawn box: its yellow pixels inside the projected corners' bounding rectangle.
        const Image image = app->readDisplay();
        const std::vector<glm::ivec2> yellow = pixelsOfColour(image, overlay_colour::kBox, 8);
        ASSERT_GT(yellow.size(), 8u);
        glm::vec2 lo(1e30f), hi(-1e30f);
        const ShadowMapInfo& map = app->techniques().get("pcf", error)->host().shadowMaps().front();
        for (glm::vec2 corner : {probe.boxMin, probe.boxMax, glm::vec2(probe.boxMin.x, probe.boxMax.y),
                                 glm::vec2(probe.boxMax.x, probe.boxMin.y)}) {
            glm::vec2 a, b;
            const glm::vec3 w = onReceiverPlane(map, probe, corner);
            ASSERT_TRUE(projectSegment(app->lastFrame().camera.viewProjection, app->renderer().size(), w, w, a, b));
            lo = glm::min(lo, a);
            hi = glm::max(hi, a);
        }
        for (const glm::ivec2& p : yellow) {
            EXPECT_GE(float(p.x) + 0.5f, lo.x - 1.5f);
            EXPECT_LE(float(p.x) + 0.5f, hi.x + 1.5f);
            EXPECT_GE(float(p.y) + 0.5f, lo.y - 1.5f);
            EXPECT_LE(float(p.y) + 0.5f, hi.y + 1.5f);
        }
    }
    // Bilinear taps read one texel more across.
    ASSERT_TRUE(app->applyAssignments({"kernel=5", "hardware_filter=1"}, "pcf", error)) << error;
    ASSERT_TRUE(app->renderFrame("pcf", error)) << error;
    const std::vector<glm::ivec2> penumbra = groundPixelsWithTerm(*app, 0.02f, 0.98f, 1);
    ASSERT_FALSE(penumbra.empty());
    const KernelProbe bilinear = probeAt(*app, "pcf", penumbra.front());
    ASSERT_TRUE(bilinear.valid) << bilinear.problem;
    EXPECT_FLOAT_EQ(bilinear.kernelTexels, 6.0f);
    ASSERT_NO_FATAL_FAILURE(expectProbeMatchesTheShader(*app, "pcf", FilterKernel::Box, 0.01f));
}

// Adaptive PCF: a pixel far from any shadow stops after the outer ring (n samples, rounded up to
// whole texels), a penumbra pixel takes all n^2, and the result is the shader's.
TEST(KernelProbe, AdaptiveDiscStopsAfterTheRingOutsideThePenumbra) {
    auto app = test::makeHeadlessApp("cube", {320, 240});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"grid=8", "sets=16", "radius=4", "hardware_filter=0", "coherent=0", "classify=ring",
                                       "cone_bias=1", "fit=scene", "resolution=1024"},
                                      "adaptive-pcf", error))
        << error;
    ASSERT_TRUE(app->renderFrame("adaptive-pcf", error)) << error;
    const std::vector<glm::ivec2> lit = groundPixelsWithTerm(*app, 0.999f, 2.0f, 97);
    ASSERT_FALSE(lit.empty());
    const KernelProbe outside = probeAt(*app, "adaptive-pcf", lit.front());
    ASSERT_TRUE(outside.valid) << outside.problem;
    EXPECT_EQ(outside.kernel, FilterKernel::Disc);
    EXPECT_TRUE(outside.earlyOut);
    EXPECT_EQ(outside.samplesTaken, 8) << "the outer ring of an 8 x 8 set";
    EXPECT_FLOAT_EQ(outside.filterRadiusTexels, 4.0f);
    EXPECT_FLOAT_EQ(outside.lit, 1.0f);
    EXPECT_EQ(std::count_if(outside.taps.begin(), outside.taps.end(), [](const KernelTap& t) { return !t.taken; }), 56);

    const std::vector<glm::ivec2> penumbra = groundPixelsWithTerm(*app, 0.1f, 0.9f, 1);
    ASSERT_FALSE(penumbra.empty());
    const KernelProbe inside = probeAt(*app, "adaptive-pcf", penumbra[penumbra.size() / 2]);
    ASSERT_TRUE(inside.valid) << inside.problem;
    EXPECT_FALSE(inside.earlyOut);
    EXPECT_EQ(inside.samplesTaken, 64);
    // Every sample within the disc of 4 texels around the point (the disc's rim: |offset| <= 1).
    for (const KernelTap& tap : inside.taps)
        EXPECT_LE(glm::distance(tap.uv, glm::vec2(inside.coord)) * 1024.0f, 4.0f + 1e-2f);
    ASSERT_NO_FATAL_FAILURE(expectProbeMatchesTheShader(*app, "adaptive-pcf", FilterKernel::Disc, 1.0f / 128.0f));
    // The quad-coherent early out too (the quad's four rings decide).
    ASSERT_TRUE(app->applyAssignments({"coherent=1"}, "adaptive-pcf", error)) << error;
    ASSERT_TRUE(app->renderFrame("adaptive-pcf", error)) << error;
    ASSERT_NO_FATAL_FAILURE(expectProbeMatchesTheShader(*app, "adaptive-pcf", FilterKernel::Disc, 1.0f / 128.0f));
}

// PCSS: a lit pixel far from the cube finds no blocker, a penumbra pixel finds some of the n_s^2
// samples blocked, at a depth between the light and the receiver, and its penumbra estimate is the
// similar-triangles width (eq. 3.19-3.20) of that depth; an umbra pixel is fully blocked.
TEST(KernelProbe, PcssBlockerSearchAndPenumbraEstimate) {
    auto app = test::makeHeadlessApp("cube", {320, 240});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"search_grid=6", "filter_grid=8", "sets=16", "bilinear=1", "search_bound=depth-range",
                                       "cone_bias=1", "fit=scene", "resolution=1024"},
                                      "pcss", error))
        << error;
    ASSERT_TRUE(app->renderFrame("pcss", error)) << error;
    const FilterFootprint& reported = app->techniques().get("pcss", error)->host().filterFootprint();
    ASSERT_EQ(reported.kernel, FilterKernel::Pcss);
    EXPECT_EQ(reported.searchTaps, 6);
    EXPECT_EQ(reported.taps, 8);

    const std::vector<glm::ivec2> lit = groundPixelsWithTerm(*app, 0.999f, 2.0f, 131);
    ASSERT_FALSE(lit.empty());
    const KernelProbe outside = probeAt(*app, "pcss", lit.front());
    ASSERT_TRUE(outside.valid) << outside.problem;
    EXPECT_EQ(outside.blockers, 0);
    EXPECT_FLOAT_EQ(outside.lit, 1.0f);

    const std::vector<glm::ivec2> penumbra = groundPixelsWithTerm(*app, 0.2f, 0.8f, 3);
    ASSERT_GT(penumbra.size(), 3u);
    int withBlockers = 0;
    for (size_t k = 0; k < std::min<size_t>(penumbra.size(), 20); ++k) {
        const KernelProbe probe = probeAt(*app, "pcss", penumbra[k]);
        ASSERT_TRUE(probe.valid) << probe.problem;
        if (probe.decision != "searched") continue;
        ++withBlockers;
        EXPECT_GT(probe.blockers, 0);
        EXPECT_LE(probe.blockers, 36);
        EXPECT_EQ(probe.searchSamples, 36);
        EXPECT_GT(probe.averageBlockerDepth, 0.0f);
        EXPECT_LT(probe.averageBlockerDepth, probe.receiverDepth) << "blockers lie between the light and the receiver";
        // eq. 3.19-3.20 for the directional light: radius (z_r - z_b) tan(alpha) / W of the map, in texels.
        const float expected = std::max((probe.receiverDepth - probe.averageBlockerDepth) * reported.lightSize /
                                            std::min(reported.lightWorldSize.x, reported.lightWorldSize.y) * 1024.0f,
                                        1.0f);
        EXPECT_NEAR(probe.filterRadiusTexels, expected, 1e-3f * expected + 1e-4f);
        EXPECT_EQ(probe.samplesTaken, 36 + (probe.earlyOut ? 8 : 64));
    }
    EXPECT_GT(withBlockers, 3) << "penumbra pixels find blockers";
    ASSERT_NO_FATAL_FAILURE(expectProbeMatchesTheShader(*app, "pcss", FilterKernel::Pcss, 0.01f));

    const std::vector<glm::ivec2> umbra = groundPixelsWithTerm(*app, -1.0f, 1e-4f, 11);
    ASSERT_FALSE(umbra.empty());
    const KernelProbe dark = probeAt(*app, "pcss", umbra[umbra.size() / 2]);
    ASSERT_TRUE(dark.valid) << dark.problem;
    EXPECT_FLOAT_EQ(dark.lit, 0.0f);
    EXPECT_TRUE(dark.decision == "fully blocked" || dark.blockers == 36) << dark.decision << " " << dark.blockers;
}

// Techniques without a kernel say so instead of drawing one; no probe, no footprint.
TEST(KernelProbe, TechniquesWithoutAKernelAndNoPixelSaySo) {
    auto app = test::makeHeadlessApp("cube", {160, 120});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    app->setProbePixel(glm::ivec2(80, 100));
    presentAndRead(*app, "shadowmap", "kernel");
    EXPECT_FALSE(app->lastProbe().valid);
    EXPECT_NE(app->lastProbe().problem.find("no filter kernel"), std::string::npos) << app->lastProbe().problem;
    ASSERT_TRUE(app->renderFrame("pcf", error)) << error;
    app->setProbePixel(std::nullopt);
    presentAndRead(*app, "pcf", "kernel");
    EXPECT_FALSE(app->lastProbe().valid);
    EXPECT_NE(app->lastProbe().problem.find("--probe"), std::string::npos) << app->lastProbe().problem;
}
