// Parameter parsing, range errors and the hand-over of values across a hot reload.
#include <gtest/gtest.h>

#include "plugin/params.h"

using namespace shadowlab;

namespace {

TechniqueInfo sampleTechnique() {
    TechniqueInfo info;
    info.id = "sample";
    info.shadowGlsl = "sample.glsl";
    info.params = {
        {"resolution", "resolution", ParamType::Int, 256, 8192, 2048, "texels", "", {}},
        {"bias", "bias", ParamType::Float, 0, 4, 0.5, "", "", {}},
        {"filter", "filter", ParamType::Bool, 0, 1, 0, "", "", {}},
        {"format", "format", ParamType::Enum, 0, 2, 2, "", "", {"16", "24", "32F"}},
    };
    return info;
}

} // namespace

TEST(Params, DefaultsComeFromTheDescriptor) {
    ParamStore store;
    const auto info = sampleTechnique();
    EXPECT_EQ(store.values(info), (std::vector<double>{2048, 0.5, 0, 2}));
}

TEST(Params, ParsesEveryType) {
    ParamStore store;
    const auto info = sampleTechnique();
    std::string error;
    EXPECT_TRUE(store.set(info, "resolution", "4096", error)) << error;
    EXPECT_TRUE(store.set(info, "bias", "1.25", error)) << error;
    EXPECT_TRUE(store.set(info, "filter", "on", error)) << error;
    EXPECT_TRUE(store.set(info, "format", "24", error)) << error;   // by label
    EXPECT_EQ(store.values(info), (std::vector<double>{4096, 1.25, 1, 1}));
    EXPECT_TRUE(store.set(info, "format", "0", error)) << error;    // not a label: an index
    EXPECT_TRUE(store.set(info, "filter", "false", error)) << error;
    EXPECT_EQ(store.values(info)[3], 0.0);
    EXPECT_EQ(store.values(info)[2], 0.0);
}

TEST(Params, RangeAndTypeErrorsNameTheParameterAndKeepTheValue) {
    ParamStore store;
    const auto info = sampleTechnique();
    std::string error;
    EXPECT_FALSE(store.set(info, "resolution", "100", error));
    EXPECT_NE(error.find("resolution"), std::string::npos) << error;
    EXPECT_NE(error.find("out of range [256, 8192]"), std::string::npos) << error;
    EXPECT_FALSE(store.set(info, "resolution", "1024.5", error));
    EXPECT_NE(error.find("not an integer"), std::string::npos) << error;
    EXPECT_FALSE(store.set(info, "bias", "lots", error));
    EXPECT_NE(error.find("not a number"), std::string::npos) << error;
    EXPECT_FALSE(store.set(info, "bias", "nan", error));
    EXPECT_FALSE(store.set(info, "filter", "maybe", error));
    EXPECT_NE(error.find("not a boolean"), std::string::npos) << error;
    EXPECT_FALSE(store.set(info, "format", "8", error));
    EXPECT_NE(error.find("16, 24, 32F"), std::string::npos) << error;
    EXPECT_FALSE(store.set(info, "kernel", "3", error));
    EXPECT_NE(error.find("has no parameter 'kernel'"), std::string::npos) << error;
    EXPECT_NE(error.find("resolution, bias, filter, format"), std::string::npos) << error;
    EXPECT_EQ(store.values(info), (std::vector<double>{2048, 0.5, 0, 2})) << "failed sets change nothing";
}

TEST(Params, AssignmentSyntax) {
    std::string error;
    auto a = parseAssignment("pcf.kernel=5", error);
    ASSERT_TRUE(a);
    EXPECT_EQ(a->technique, "pcf");
    EXPECT_EQ(a->param, "kernel");
    EXPECT_EQ(a->value, "5");
    a = parseAssignment("bias=0.1", error);
    ASSERT_TRUE(a);
    EXPECT_TRUE(a->technique.empty());
    EXPECT_FALSE(parseAssignment("bias", error));
    EXPECT_NE(error.find("expected key=value"), std::string::npos);
    EXPECT_FALSE(parseAssignment("=3", error));
    EXPECT_FALSE(parseAssignment("bias=", error));
}

TEST(Params, RemapKeepsValuesByIdAndClampsToNewRanges) {
    ParamStore store;
    auto before = sampleTechnique();
    std::string error;
    ASSERT_TRUE(store.set(before, "resolution", "8192", error));
    ASSERT_TRUE(store.set(before, "bias", "3", error));
    auto after = before;
    after.params.erase(after.params.begin() + 2);                       // "filter" removed
    after.params[0].maxValue = 4096;                                    // range shrank
    after.params.push_back({"kernel", "kernel", ParamType::Int, 1, 15, 3, "", "", {}});
    store.remap(before, after);
    EXPECT_EQ(store.values(after), (std::vector<double>{4096, 3, 2, 3}));
}

// kit/params.h: one X-macro list gives the table, the indices and typed values, groups splice
// in keeping their order, and kit::depthMapConfig reads whichever groups a list has.
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/params.h>

namespace {
using namespace shadowlab;
enum class Mode : int { A = 0, B = 1 };
constexpr ParamDesc kModeParam = kit::enumParam("mode", "mode", 1, "a|b", "");
// An enum's range is its options' indices: stated once, by the options.
static_assert(kModeParam.type == ParamType::Enum && kModeParam.minValue == 0 && kModeParam.maxValue == 1);
static_assert(kit::enumParam("m", "m", 0, "one", "").maxValue == 0);
static_assert(kit::enumParam("m", "m", 0, "16|24|32F", "").maxValue == 2);
#define KIT_PARAMS_TEST_LIST(X)                      \
    SHADOWLAB_DEPTH_MAP_PARAMS(X, 1024, 100, 2)      \
    X(Mode, mode, kModeParam)                        \
    SHADOWLAB_FIT_PARAMS(X)
SHADOWLAB_PARAMS(KitParams, KIT_PARAMS_TEST_LIST);
static_assert(KitParams::Id::count == 8 && std::size(KitParams::table) == 8);
static_assert(KitParams::Id::resolution == 0 && KitParams::Id::mode == 5 && KitParams::Id::snap == 7);
static_assert(kit::paramIndex(KitParams::table, "cull") == KitParams::Id::cull);
} // namespace

TEST(ParamsKit, OneListGivesTableIndicesAndTypedValues) {
    EXPECT_STREQ(KitParams::table[KitParams::Id::constant_bias].id, "constant_bias");
    EXPECT_EQ(KitParams::table[KitParams::Id::resolution].defaultValue, 1024);
    EXPECT_EQ(KitParams::table[KitParams::Id::constant_bias].maxValue, 100);
    EXPECT_EQ(KitParams::table[KitParams::Id::cull].defaultValue, 2);
    const double raw[] = {512, 1, 3.5, 1.25, 2, 0, 1, 1};
    const KitParams p = KitParams::read(ParamValues(raw, 8));
    EXPECT_EQ(p.resolution, 512);
    EXPECT_EQ(p.depth_format, 1);
    EXPECT_FLOAT_EQ(p.constant_bias, 3.5f);
    EXPECT_FLOAT_EQ(p.slope_bias, 1.25f);
    EXPECT_EQ(p.mode, Mode::A);
    EXPECT_EQ(p.fit, 1);
    EXPECT_TRUE(p.snap);
    const kit::DepthMapConfig config = kit::depthMapConfig(p);
    EXPECT_EQ(config.resolution, 512);
    EXPECT_EQ(config.format, kit::depthFormat(1));
    EXPECT_FLOAT_EQ(config.constantBias, 3.5f);
    EXPECT_EQ(config.cull, kit::Cull::Front);
    EXPECT_EQ(config.fit.fit, kit::Fit::Frustum);
    EXPECT_TRUE(config.fit.snap);
}
