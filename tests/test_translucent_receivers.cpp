// Translucent receivers (seed 001 sec. 5.3.3, Fig. 5.3.3.A): the evaluation's translucent layers
// (peeled from the camera, traced and compared like the opaque image), and composited translucent
// shadows (sec. 4.2.3) shading every layer by the meshes nearer the light where translucent shadows
// tint every layer with all of them.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.h"

namespace shadowlab {
namespace {

using Mode = ReferenceOptions::Mode;

using test::SceneFile;

// A blue glass quad 1 above a red one 1 above the ground, the sun almost overhead, the camera above
// them: layer 0 is the blue quad, layer 1 the red one. Closed forms (alpha 0.5 both):
//   physical (1 - a) + a t:  red quad under blue (0.55, 0.65, 0.95); the blue quad 1;
//   modified (1 - a) t:      red quad under blue (0.05, 0.15, 0.45); the blue quad 1.
const char* kTwoPanes = R"({
  "name": "two-panes",
  "camera": {"position": [0.0, 7.0, 2.5], "target": [0.0, 1.0, 0.0], "fovY": 45, "near": 0.1, "far": 40},
  "light": {"type": "directional", "elevation": 88, "azimuth": 30, "color": [1, 1, 1], "intensity": 1},
  "ambient": [0.05, 0.05, 0.05],
  "materials": {
    "white": {"baseColor": [0.9, 0.9, 0.9]},
    "blue glass": {"baseColor": [0.1, 0.3, 0.9], "alpha": 0.5, "transmission": [0.1, 0.3, 0.9]},
    "red glass": {"baseColor": [0.9, 0.2, 0.1], "alpha": 0.5, "transmission": [0.9, 0.2, 0.1]}
  },
  "objects": [
    {"name": "ground", "shape": "plane", "size": [8, 8], "material": "white", "castsShadow": false},
    {"name": "red pane", "shape": "plane", "size": [2.4, 2.4], "translate": [0, 1.0, 0], "material": "red glass"},
    {"name": "blue pane", "shape": "plane", "size": [3, 3], "translate": [0, 2.0, 0], "material": "blue glass"}
  ]
})";

// Mean technique and reference colour, and MAE, over a layer's compared pixels at height `y`, well
// inside |x|, |z| < half.
struct LayerRegion {
    glm::dvec3 technique{0.0}, reference{0.0};
    double mae = 0.0;
    size_t pixels = 0;
};
LayerRegion layerRegion(const TranslucentLayerEvaluation& layer, float y, float half) {
    LayerRegion out;
    for (size_t i = 0; i < layer.mask.size(); ++i) {
        const glm::vec4 p = layer.positions[i];
        if (!layer.mask[i] || p.w < 0.5f || std::abs(p.y - y) > 1e-3f || std::abs(p.x) > half || std::abs(p.z) > half) continue;
        ++out.pixels;
        out.technique += glm::dvec3(layer.technique[i]);
        out.reference += glm::dvec3(layer.reference[i]);
        const glm::vec3 e = layer.technique[i] - layer.reference[i];
        out.mae += (std::abs(e.r) + std::abs(e.g) + std::abs(e.b)) / 3.0;
    }
    if (out.pixels) {
        out.technique /= double(out.pixels);
        out.reference /= double(out.pixels);
        out.mae /= double(out.pixels);
    }
    return out;
}

void expectNear(glm::dvec3 value, glm::dvec3 expected, double tolerance, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(value[c], expected[c], tolerance) << what << ", channel " << c;
}

} // namespace

TEST(TranslucentLayers, ArePeeledFrontToBackAndTracedAgainstTheClosedForm) {
    SceneFile scene("two-panes", kTwoPanes);
    auto app = test::makeHeadlessApp(scene.path(), {256, 192});
    ASSERT_TRUE(app);
    const Evaluation e = test::evaluateTechnique(*app, "cssm2", {"kernel=9"}, Mode::Hard, 1, TranslucencyModel::Physical);
    ASSERT_EQ(e.translucentLayers.size(), 2u) << "the blue pane, then the red one beneath it";
    const LayerRegion blue = layerRegion(e.translucentLayers[0], 2.0f, 1.0f);
    const LayerRegion red = layerRegion(e.translucentLayers[1], 1.0f, 0.8f);
    std::printf("layer 0 (blue pane) %zu px, reference %.4f %.4f %.4f; layer 1 (red pane) %zu px, reference %.4f %.4f %.4f, "
                "cssm2 9x9 %.4f %.4f %.4f\n",
                blue.pixels, blue.reference.r, blue.reference.g, blue.reference.b, red.pixels, red.reference.r,
                red.reference.g, red.reference.b, red.technique.r, red.technique.g, red.technique.b);
    ASSERT_GT(blue.pixels, 1000u);
    ASSERT_GT(red.pixels, 1000u);
    expectNear(blue.reference, {1.0, 1.0, 1.0}, 1e-6, "nothing above the blue pane");
    expectNear(red.reference, {0.55, 0.65, 0.95}, 1e-4, "(1 - a) + a t_blue on the red pane");
    // CSSM2 estimates the physical model on every layer (Fig. 5.3.3.A, top right): its mean is on
    // the closed form, each pixel off by its noise (9 x 9 taps of coin flips: 0.035 measured).
    expectNear(red.technique, red.reference, 0.01, "cssm2's expectation on the red pane");
    EXPECT_LT(red.mae, 0.05);
    EXPECT_GT(e.translucentMetrics.comparedPixels, blue.pixels + red.pixels - 1);
    EXPECT_LT(e.translucentMetrics.mae, 0.03);

    // One layer asked for: only the blue pane. None: the opaque image alone.
    app->setTranslucentLayers(1);
    EXPECT_EQ(test::evaluateTechnique(*app, "cssm2", {}, Mode::Hard, 1, TranslucencyModel::Physical).translucentLayers.size(), 1u);
    app->setTranslucentLayers(0);
    EXPECT_TRUE(test::evaluateTechnique(*app, "cssm2", {}, Mode::Hard, 1, TranslucencyModel::Physical).translucentLayers.empty());
}

TEST(TranslucentLayers, NoneWithoutTranslucentSurfaces) {
    auto app = test::makeHeadlessApp("cube", {160, 120});
    ASSERT_TRUE(app);
    const Evaluation e = test::evaluateTechnique(*app, "shadowmap", {}, Mode::Hard);
    EXPECT_TRUE(e.translucentLayers.empty());
    EXPECT_EQ(e.translucentMetrics.comparedPixels, 0u);
}

// Fig. 5.3.3.A: translucent shadows shade the pane beneath with the whole colour buffer (its own
// filter included), composited shadows with the panes nearer the light only.
TEST(CompositedTranslucent, ShadesTheLowerPaneByThePaneAboveWhereTranslucentShadowsTintItWithItself) {
    SceneFile scene("two-panes", kTwoPanes);
    auto app = test::makeHeadlessApp(scene.path(), {256, 192});
    ASSERT_TRUE(app);
    const auto m3 = TranslucencyModel::ModifiedTranslucent;
    const Evaluation ts = test::evaluateTechnique(*app, "translucent-shadows", {"variant=modified"}, Mode::Hard, 1, m3);
    const Evaluation ct = test::evaluateTechnique(*app, "composited-translucent", {"variant=modified"}, Mode::Hard, 1, m3);
    ASSERT_EQ(ts.translucentLayers.size(), 2u);
    ASSERT_EQ(ct.translucentLayers.size(), 2u);
    const LayerRegion tsRed = layerRegion(ts.translucentLayers[1], 1.0f, 0.8f);
    const LayerRegion ctRed = layerRegion(ct.translucentLayers[1], 1.0f, 0.8f);
    const LayerRegion ctBlue = layerRegion(ct.translucentLayers[0], 2.0f, 1.0f);
    std::printf("red pane under blue, M3 %.4f %.4f %.4f: translucent-shadows %.4f %.4f %.4f, composited %.4f %.4f %.4f; "
                "translucent receivers MAE %.4f against %.4f\n",
                ctRed.reference.r, ctRed.reference.g, ctRed.reference.b, tsRed.technique.r, tsRed.technique.g,
                tsRed.technique.b, ctRed.technique.r, ctRed.technique.g, ctRed.technique.b, ts.translucentMetrics.mae,
                ct.translucentMetrics.mae);
    ASSERT_GT(ctRed.pixels, 1000u);
    expectNear(ctRed.reference, {0.05, 0.15, 0.45}, 1e-4, "(1 - a) t_blue");
    expectNear(ctRed.technique, {0.05, 0.15, 0.45}, 0.01, "composited: the blue pane's filter alone");
    expectNear(tsRed.technique, {0.05 * 0.45, 0.15 * 0.1, 0.45 * 0.05}, 0.01, "translucent shadows: blue times its own red");
    expectNear(ctBlue.technique, {1.0, 1.0, 1.0}, 0.01, "nothing nearer the light than the blue pane");
    EXPECT_LT(ct.translucentMetrics.mae, 0.005);
    EXPECT_GT(ts.translucentMetrics.mae, 5.0 * ct.translucentMetrics.mae + 0.02);
    // The opaque receivers get the same maps of every caster: the same image.
    ASSERT_EQ(ts.technique.size(), ct.technique.size());
    double largest = 0.0;
    for (size_t i = 0; i < ts.technique.size(); ++i)
        for (int c = 0; c < 3; ++c) largest = std::max(largest, double(std::abs(ts.technique[i][c] - ct.technique[i][c])));
    EXPECT_LT(largest, 1e-3) << "opaque receivers: composited shades them exactly as translucent shadows";
}

// On seed 001's layered-transparency scene every technique is measured on its translucent layers;
// composited shadows stay within their model where translucent shadows do not.
TEST(CompositedTranslucent, StaysWithinItsModelOnEveryLayerOfLayeredQuads) {
    auto app = test::makeHeadlessApp("layered-quads", {320, 240});
    ASSERT_TRUE(app);
    const auto m3 = TranslucencyModel::ModifiedTranslucent;
    const Evaluation ts = test::evaluateTechnique(*app, "translucent-shadows", {}, Mode::Hard, 1, m3);
    const Evaluation ct = test::evaluateTechnique(*app, "composited-translucent", {}, Mode::Hard, 1, m3);
    std::printf("layered-quads, translucent receivers against M3: translucent-shadows %.4f, composited %.4f (%zu layers, %zu px); "
                "opaque receivers %.4f and %.4f\n",
                ts.translucentMetrics.mae, ct.translucentMetrics.mae, ct.translucentLayers.size(),
                ct.translucentMetrics.comparedPixels, ts.metrics.mae, ct.metrics.mae);
    ASSERT_GE(ct.translucentLayers.size(), 2u);
    EXPECT_LT(ct.translucentMetrics.mae, 0.005);
    EXPECT_GT(ts.translucentMetrics.mae, 0.03);
    EXPECT_NEAR(ct.metrics.mae, ts.metrics.mae, 1e-4);
}

// Seed 001 sec. 5.3.1 times composited shadows with one scope around the translucent loop: here
// "translucent draws", inside "main", present only for a technique with the hook.
TEST(CompositedTranslucent, TimesItsTranslucentLoopAsOneScopeInsideTheMainPass) {
    auto app = test::makeHeadlessApp("layered-quads", {160, 120});
    ASSERT_TRUE(app);
    std::string error;
    Measurement composited, plain;
    ASSERT_TRUE(app->measure("composited-translucent", 2, 5, composited, error)) << error;
    ASSERT_TRUE(app->measure("translucent-shadows", 2, 5, plain, error)) << error;
    ASSERT_TRUE(composited.gpuMs.count("translucent draws"));
    EXPECT_FALSE(plain.gpuMs.count("translucent draws"));
    EXPECT_LE(composited.gpuMs["translucent draws"].median, composited.gpuMs["main"].median);
    EXPECT_GT(composited.gpuMs["translucent draws"].median, 0.0);
}

} // namespace shadowlab
