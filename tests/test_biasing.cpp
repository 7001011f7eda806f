// Biasing under LiSPSM (seed 002 ch. 5, Fig. 5.6) on forest-002, against the hard reference: the
// false-shadow rate (acne) and false-light rate (leaks) of each method, as the seed describes them.
#include <gtest/gtest.h>

#include "test_support.h"

using namespace shadowlab;

namespace {

AccuracyMetrics lispsm(App& app, std::vector<std::string> sets) {
    sets.push_back("resolution=2048");
    return test::measureAccuracy(app, "lispsm", sets, ReferenceOptions::Mode::Hard);
}

} // namespace

TEST(Biasing, Figure5_6UnderLispsm) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    const std::vector<std::string> none = {"constant_bias=0", "slope_bias=0"}, constant = {"constant_bias=20000", "slope_bias=0"},
                                   slope = {"constant_bias=4", "slope_bias=2"};
    auto with = [](std::vector<std::string> a, std::initializer_list<const char*> b) {
        a.insert(a.end(), b.begin(), b.end());
        return a;
    };
    const AccuracyMetrics noBias = lispsm(*app, with(none, {"depth=hyperbolic", "cull=none"}));
    const AccuracyMetrics constantHyperbolic = lispsm(*app, with(constant, {"depth=hyperbolic", "cull=none"}));
    const AccuracyMetrics constantLinear = lispsm(*app, with(constant, {"depth=linear", "cull=none"}));
    const AccuracyMetrics slopeHyperbolic = lispsm(*app, with(slope, {"depth=hyperbolic", "cull=none"}));
    const AccuracyMetrics slopeLinear = lispsm(*app, with(slope, {"depth=linear", "cull=none"}));
    const AccuracyMetrics backFaces = lispsm(*app, with(none, {"depth=hyperbolic", "cull=front"}));
    std::printf("false shadow %%: none %.2f, constant hyperbolic %.2f / linear %.2f, slope hyperbolic %.2f / linear %.2f, "
                "back faces %.2f\n",
                100 * noBias.falseShadowRate, 100 * constantHyperbolic.falseShadowRate, 100 * constantLinear.falseShadowRate,
                100 * slopeHyperbolic.falseShadowRate, 100 * slopeLinear.falseShadowRate, 100 * backFaces.falseShadowRate);
    EXPECT_GT(noBias.falseShadowRate, 0.2) << "no bias: acne over the lit ground and crowns";
    // Hyperbolic z spends its steps unevenly along the warp: one constant is too small at one end.
    EXPECT_LT(constantLinear.falseShadowRate, 0.7 * constantHyperbolic.falseShadowRate);
    // Slope-scaled bias does with a far smaller push what a constant cannot (sec. 5.3).
    EXPECT_LT(slopeHyperbolic.falseShadowRate, 0.05);
    EXPECT_LT(slopeLinear.falseShadowRate, 0.05);
    // Back faces in the map: the lit front faces never meet their own depth (sec. 5.1, Fig. 5.5).
    EXPECT_LT(backFaces.falseShadowRate, 0.01);
}

// Sec. 5.2: the second layer by depth peeling. Second-depth shadow mapping removes acne on closed
// casters without a bias; the midpoint (eq. 5.1) does not leak either, but at silhouettes,
// where the two surfaces meet, its bias shrinks to nothing and acne returns.
TEST(Biasing, TwoLayerMethods) {
    auto app = test::makeHeadlessApp("forest-002", {256, 160});
    ASSERT_TRUE(app);
    const AccuracyMetrics offset = lispsm(*app, {"bias_method=offset", "cull=none"});
    const AccuracyMetrics midpoint = lispsm(*app, {"bias_method=midpoint"});
    const AccuracyMetrics second = lispsm(*app, {"bias_method=second-depth"});
    std::printf("false shadow / false light %%: offset %.2f / %.2f, midpoint %.2f / %.2f, second depth %.2f / %.2f\n",
                100 * offset.falseShadowRate, 100 * offset.falseLightRate, 100 * midpoint.falseShadowRate,
                100 * midpoint.falseLightRate, 100 * second.falseShadowRate, 100 * second.falseLightRate);
    EXPECT_LT(second.falseShadowRate, 0.01);
    EXPECT_LT(second.falseLightRate, 0.01);
    EXPECT_LT(midpoint.falseLightRate, 0.01) << "z_offset bounds the bias: no leaks under the trees";
    EXPECT_GT(midpoint.falseShadowRate, second.falseShadowRate) << "silhouette acne";
}
