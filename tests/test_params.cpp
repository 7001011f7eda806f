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
