// The host depth pre-pass's auto mode (issue 32): the rule's thresholds and hysteresis, the
// depth complexity measured from the frame (forest chooses the pre-pass, cube does not), the
// image identical either way, the decision taken before a measurement's timed frames, and the
// bench columns that report it.
#include <gtest/gtest.h>

#include <algorithm>

#include "bench/bench.h"
#include "render/depth_prepass_rule.h"
#include "test_support.h"

using namespace shadowlab;

TEST(DepthPrepassRule, TheFirstMeasurementDecidesAtTheMidpoint) {
    const double mid = 0.5 * (DepthPrepassRule::kOnAbove + DepthPrepassRule::kOffBelow);
    DepthPrepassRule rule;
    EXPECT_FALSE(rule.measured());
    EXPECT_FALSE(rule.autoDecision()) << "off before anything is measured";
    EXPECT_TRUE(rule.update(mid + 0.01));
    EXPECT_TRUE(rule.autoDecision());
    rule.reset();
    EXPECT_FALSE(rule.measured());
    EXPECT_FALSE(rule.update(mid - 0.01));
    EXPECT_FALSE(rule.autoDecision());
    EXPECT_EQ(rule.measurements(), 1u);
}

TEST(DepthPrepassRule, HysteresisKeepsTheDecisionBetweenTheThresholds) {
    DepthPrepassRule rule;
    rule.update(1.0);
    ASSERT_FALSE(rule.autoDecision());
    // A camera moving about between the two thresholds (and briefly beyond) never flips it.
    for (int i = 0; i < 50; ++i) {
        rule.update(i % 2 ? DepthPrepassRule::kOffBelow + 0.05 : DepthPrepassRule::kOnAbove - 0.05);
        if (i % 7 == 0) rule.update(DepthPrepassRule::kOnAbove + 1.0);   // one frame of heavy overdraw
        EXPECT_FALSE(rule.autoDecision()) << "flipped at step " << i;
    }
    rule.update(1.0);   // ends any streak the loop left
    // Beyond the on threshold for kConfirmations measurements in a row: on.
    for (int i = 0; i < DepthPrepassRule::kConfirmations - 1; ++i) {
        rule.update(DepthPrepassRule::kOnAbove);
        EXPECT_FALSE(rule.autoDecision());
    }
    EXPECT_TRUE(rule.update(DepthPrepassRule::kOnAbove));
    EXPECT_TRUE(rule.autoDecision());
    // Between the thresholds it stays on; off only below the off threshold, again confirmed.
    for (int i = 0; i < 10; ++i) rule.update(0.5 * (DepthPrepassRule::kOnAbove + DepthPrepassRule::kOffBelow));
    EXPECT_TRUE(rule.autoDecision());
    for (int i = 0; i < DepthPrepassRule::kConfirmations; ++i) rule.update(DepthPrepassRule::kOffBelow);
    EXPECT_FALSE(rule.autoDecision());
    EXPECT_TRUE(rule.active(DepthPrepassMode::On)) << "on and off override the rule";
    EXPECT_FALSE(rule.active(DepthPrepassMode::Off));
    EXPECT_FALSE(rule.active(DepthPrepassMode::Auto));
}

namespace {

struct Decision {
    double complexity = 0.0;
    bool active = false;
    int prepassFrames = 0;
    bool timedPrepass = false;
};

// `measure` in auto mode with no warm-up: the decision must still be taken before the timed frames.
Decision decideAuto(App& app, const std::string& technique) {
    app.setDepthPrepassMode(DepthPrepassMode::Auto);
    Measurement m;
    std::string error;
    EXPECT_TRUE(app.measure(technique, 0, 3, m, error)) << error;
    Decision d;
    d.complexity = m.depthComplexity.value_or(-1.0);
    d.active = app.depthPrepassActive();
    d.prepassFrames = m.depthPrepassFrames;
    d.timedPrepass = m.gpuMs.count("depth pre-pass") > 0;
    return d;
}

} // namespace

TEST(DepthPrepassAuto, ForestChoosesThePrepassAndCubeDoesNot) {
    auto forest = test::makeHeadlessApp("forest", {320, 180});
    ASSERT_TRUE(forest);
    const Decision f = decideAuto(*forest, "pcss");
    EXPECT_GE(f.complexity, DepthPrepassRule::kOnAbove) << "forest's overdraw";
    EXPECT_TRUE(f.active);
    EXPECT_EQ(f.prepassFrames, 3) << "every timed frame ran it";
    EXPECT_TRUE(f.timedPrepass);
    forest.reset();

    auto cube = test::makeHeadlessApp("cube", {320, 180});
    ASSERT_TRUE(cube);
    const Decision c = decideAuto(*cube, "pcss");
    EXPECT_GT(c.complexity, 0.3) << "the ground and the cube cover most of the view";
    EXPECT_LE(c.complexity, DepthPrepassRule::kOffBelow);
    EXPECT_FALSE(c.active);
    EXPECT_EQ(c.prepassFrames, 0);
    EXPECT_FALSE(c.timedPrepass);
}

TEST(DepthPrepassAuto, TheCountIsTheSameWithAndWithoutThePrepass) {
    // With the pre-pass the count comes from the pre-pass, without it from the main pass: the
    // same opaque fragments through the same LESS test, so the hysteresis compares like with like.
    auto app = test::makeHeadlessApp("forest", {200, 120});
    ASSERT_TRUE(app);
    std::string error;
    double complexity[2] = {0.0, 0.0};
    for (int on = 0; on < 2; ++on) {
        app->setDepthPrepassMode(on ? DepthPrepassMode::On : DepthPrepassMode::Off);
        Measurement m;
        ASSERT_TRUE(app->measure("shadowmap", 2, 2, m, error)) << error;
        EXPECT_EQ(m.depthPrepassFrames, on ? 2 : 0);
        complexity[on] = m.depthComplexity.value_or(-1.0);
    }
    EXPECT_GT(complexity[0], 1.0);
    EXPECT_NEAR(complexity[0], complexity[1], 1e-9);
}

TEST(DepthPrepassAuto, TheImageIsTheSameEitherWay) {
    auto app = test::makeHeadlessApp("forest", {240, 136});
    ASSERT_TRUE(app);
    std::string error;
    for (const char* technique : {"shadowmap", "pcss"}) {
        app->setDepthPrepassMode(DepthPrepassMode::Off);
        Measurement m;
        ASSERT_TRUE(app->measure(technique, 1, 1, m, error)) << error;
        ASSERT_FALSE(app->depthPrepassActive());
        const auto without = test::readTarget(*app, MainTarget::Color);
        const Decision d = decideAuto(*app, technique);
        ASSERT_TRUE(d.active) << technique << ": auto should have chosen the pre-pass on forest";
        const auto with = test::readTarget(*app, MainTarget::Color);
        ASSERT_EQ(without.size(), with.size());
        size_t different = 0;
        float largest = 0.0f;
        for (size_t i = 0; i < with.size(); ++i) {
            const glm::vec4 d = glm::abs(with[i] - without[i]);
            const float difference = std::max(std::max(d.x, d.y), std::max(d.z, d.w));
            largest = std::max(largest, difference);
            different += difference > 1e-5f;
        }
        // main.vert's invariant gl_Position: depth EQUAL keeps exactly the nearest fragment, and
        // the stencil count the first of tied ones, as LESS does.
        EXPECT_EQ(different, 0u) << technique << ": largest difference " << largest;
    }
}

TEST(DepthPrepassAuto, TiedDepthsKeepTheFirstSurfaceAsWithoutThePrepass) {
    // Two coplanar planes of different colours: every pixel's depths tie. LESS keeps the first
    // drawn; after the pre-pass both pass EQUAL, and without the renderer's stencil count the
    // second would be drawn over it (the stress case depth-far's far third changed so).
    const test::SceneFile scene("coplanar", R"({"camera": {"position": [0, 3, 6], "target": [0, 0, 0]},
        "light": {"type": "directional", "elevation": 50, "azimuth": 30},
        "materials": {"red": {"baseColor": [0.8, 0.1, 0.1]}, "blue": {"baseColor": [0.1, 0.1, 0.8]}},
        "objects": [{"shape": "plane", "size": [20, 20], "material": "red"},
                    {"shape": "plane", "size": [20, 20], "material": "blue"},
                    {"shape": "box", "size": [1, 1, 1], "translate": [0, 0.5, 0], "material": "red"}]})");
    auto app = test::makeHeadlessApp(scene.path(), {96, 64});
    ASSERT_TRUE(app);
    std::string error;
    std::vector<glm::vec4> images[2];
    for (int on = 0; on < 2; ++on) {
        app->setDepthPrepassMode(on ? DepthPrepassMode::On : DepthPrepassMode::Off);
        ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
        ASSERT_EQ(app->depthPrepassActive(), on == 1);
        images[on] = test::readTarget(*app, MainTarget::Color);
    }
    size_t different = 0, red = 0;
    for (size_t i = 0; i < images[0].size(); ++i) {
        different += images[0][i] != images[1][i];
        red += images[0][i].r > 2.0f * images[0][i].b;
    }
    EXPECT_GT(red, images[0].size() / 2) << "the first plane drawn (red) is the one seen";
    EXPECT_EQ(different, 0u);
}

TEST(DepthPrepassAuto, ANewSceneIsMeasuredAgain) {
    auto app = test::makeHeadlessApp("forest", {160, 90});
    ASSERT_TRUE(app);
    ASSERT_TRUE(decideAuto(*app, "shadowmap").active);
    std::string error;
    ASSERT_TRUE(app->loadScene("cube", {}, error)) << error;
    EXPECT_FALSE(app->depthPrepassRule().measured()) << "forest's count is not cube's";
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    EXPECT_FALSE(app->depthPrepassActive()) << "off until cube is measured";
    EXPECT_FALSE(decideAuto(*app, "shadowmap").active);
}

TEST(DepthPrepassAuto, BenchRowsReportTheModeAndTheDecisionTaken) {
    auto app = test::makeHeadlessApp("cube", {160, 90});
    ASSERT_TRUE(app);
    BenchSpec spec;
    spec.techniques = {"shadowmap"};
    spec.scenes = {"cube", "forest"};
    spec.sizes = {{160, 90}};
    spec.frames = 2;
    spec.warmupFrames = 1;
    std::string error;
    ASSERT_TRUE(addSweep(spec, "host.depth_prepass=auto,on,off", error)) << error;
    std::vector<nlohmann::json> rows;
    testing::internal::CaptureStderr();
    ASSERT_TRUE(runBench(*app, spec, rows, error)) << error;
    testing::internal::GetCapturedStderr();
    ASSERT_EQ(rows.size(), 6u);
    for (const auto& row : rows) {
        const std::string mode = row["depth_prepass_mode"];
        const bool forest = row["scene"] == "forest";
        const int expected = mode == "on" || (mode == "auto" && forest) ? 1 : 0;
        EXPECT_EQ(row["depth_prepass"].get<int>(), expected) << row.dump();
        EXPECT_EQ(row.contains("depth_prepass_ms"), expected == 1) << row.dump();
        EXPECT_FALSE(row.contains("depth_prepass_frames")) << "a still view never switches: " << row.dump();
        EXPECT_EQ(row["depth_complexity"].get<double>() >= DepthPrepassRule::kOnAbove, forest) << row.dump();
        EXPECT_FALSE(row.contains("host.depth_prepass")) << "reported as depth_prepass_mode";
    }
}
