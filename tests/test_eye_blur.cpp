// The host's eye-space depth-dependent blur of the shadow term and the lighting rules (seed 002
// sec. 6.2, 6.3, 9.4.2, Figs. 6.6-6.7; host_shared/eye_blur_shared.h, render/renderer.h eyeBlur*,
// plugin/host_params.h), on OSMesa (llvmpipe).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "bench/bench_spec.h"
#include "groundtruth/reference_technique.h"
#include "plugin/plugin_library.h"
#include "host_shared/eye_blur_shared.h"
#include "test_support.h"
#include "util/paths.h"

using namespace shadowlab;

namespace {

constexpr glm::ivec2 kSize{160, 160};

// Flat ground seen from straight above (tilted 0.57 degrees so the camera has an up vector: the
// ground's view depth varies by under 0.6% over the image), a 3 m post at x = -3 under a sun 45
// degrees up from -x: its shadow is the band x in [-2.5, 0.5], z in [-0.5, 0.5], whose long edges
// run along the image's rows at one view depth, `height`.
std::filesystem::path writeScene(float height) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / ("shadowlab-eye-blur-" + std::to_string(int(height)) + ".json");
    std::ofstream out(file);
    out << R"({"name": "eye-blur", "camera": {"position": [0, )" << height << R"(, 0], "target": [0, 0, -)"
        << 0.01f * height << R"(], "fovY": 60, "near": 1, "far": 50},
  "light": {"type": "directional", "elevation": 45, "azimuth": 180, "color": [1, 1, 1], "intensity": 1},
  "ambient": [0.1, 0.1, 0.1], "background": [0, 0, 0],
  "materials": {"ground": {"baseColor": [0.5, 0.5, 0.5], "specular": [0.5, 0.5, 0.5], "shininess": 8},
                "post": {"baseColor": [0.6, 0.3, 0.2]}},
  "objects": [{"name": "ground", "shape": "plane", "size": [20, 20], "material": "ground"},
              {"name": "post", "shape": "box", "size": [1, 3, 1], "translate": [-3, 1.5, 0], "material": "post"}]})";
    return file;
}

// The pixel column of world x = 0 (the image's middle); the term along it.
std::vector<float> middleColumn(const std::vector<glm::vec4>& visibility) {
    std::vector<float> column;
    for (int y = 0; y < kSize.y; ++y) column.push_back(visibility[size_t(y) * kSize.x + kSize.x / 2].r);
    return column;
}

// Pixels strictly between shadow and light (0.02 < s < 0.98) in each half of the column: the
// ramps of the band's two edges.
std::pair<int, int> rampWidths(const std::vector<float>& column) {
    int lower = 0, upper = 0;
    for (int y = 0; y < int(column.size()); ++y)
        if (column[size_t(y)] > 0.02f && column[size_t(y)] < 0.98f) (y < kSize.y / 2 ? lower : upper) += 1;
    return {lower, upper};
}

const std::vector<std::string> kHardMap = {"resolution=2048", "hardware_filter=0"};

} // namespace

// The width law and the kernel, C++ side of the header the GLSL uses: w(z) = W z_b / max(z, z_b),
// and the tap weights of a box w pixels wide sum to w (so a hard edge becomes a w-pixel ramp).
TEST(EyeBlur, WidthFallsWithDepthAndTheWeightsSumToIt) {
    EXPECT_FLOAT_EQ(eyeBlurWidth(16.0f, 5.0f, 2.0f), 16.0f) << "nearer than z_b: the full width";
    EXPECT_FLOAT_EQ(eyeBlurWidth(16.0f, 5.0f, 5.0f), 16.0f);
    EXPECT_FLOAT_EQ(eyeBlurWidth(16.0f, 5.0f, 10.0f), 8.0f);
    EXPECT_FLOAT_EQ(eyeBlurWidth(16.0f, 5.0f, 40.0f), 2.0f);
    for (const float w : {1.0f, 2.0f, 3.5f, 8.0f, 16.0f}) {
        float sum = 0.0f;
        for (int k = -SHADOWLAB_EYE_BLUR_MAX_RADIUS; k <= SHADOWLAB_EYE_BLUR_MAX_RADIUS; ++k) sum += eyeBlurTapWeight(w, k);
        EXPECT_NEAR(sum, w, 1e-5f) << w;
    }
    EXPECT_EQ(eyeBlurTapWeight(16.0f, SHADOWLAB_EYE_BLUR_MAX_RADIUS), 0.0f) << "the loop's reach covers w = 16";
    EXPECT_EQ(eyeBlurTapWeight(1.0f, 1), 0.0f) << "w = 1: the centre alone";
}

// host.shadow_blur = 1 runs every pass of the blur (term pass, two blur passes, the main pass
// reading the texture), but a kernel one pixel wide leaves each term as it was: the image and
// the measured term must be bit-identical to the single main pass (host.shadow_blur = 0), with a
// filtered technique (fractional terms, kept exactly by the RGBA32F texture); and back at 0 the
// first image again. A 4-pixel blur (full width up to z_b = 5, the cube about 6 away) changes it.
TEST(EyeBlur, WidthOneAndZeroLeaveTheImageBitIdentical) {
    auto app = test::makeHeadlessApp("cube", {200, 150});
    ASSERT_TRUE(app);
    std::string error;
    auto frame = [&](const std::string& blur) {
        EXPECT_TRUE(app->applyAssignments({"host.shadow_blur=" + blur, "host.shadow_blur_depth=5", "host.lighting=phong",
                                           "resolution=1024", "hardware_filter=1"},
                                          "pcf", error))
            << error;
        EXPECT_TRUE(app->renderFrame("pcf", error)) << error;
        return std::make_pair(test::readTarget(*app, MainTarget::Color), test::readTarget(*app, MainTarget::Visibility));
    };
    const auto [colour0, term0] = frame("0");
    const auto [colour1, term1] = frame("1");
    const auto [colour4, term4] = frame("4");
    const auto [colourBack, termBack] = frame("0");
    ASSERT_EQ(colour0.size(), colour1.size());
    int fractional = 0;
    for (const glm::vec4& t : term0) fractional += t.r > 0.01f && t.r < 0.99f ? 1 : 0;
    EXPECT_GT(fractional, 20) << "pcf's filtered edge: terms between 0 and 1";
    EXPECT_EQ(std::memcmp(colour0.data(), colour1.data(), colour0.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(term0.data(), term1.data(), term0.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(colour0.data(), colourBack.data(), colour0.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(term0.data(), termBack.data(), term0.size() * sizeof(glm::vec4)), 0);
    EXPECT_NE(std::memcmp(colour0.data(), colour4.data(), colour0.size() * sizeof(glm::vec4)), 0) << "a real blur changes it";
}

// Fig. 6.6's blur and sec. 6.3's depth dependence: a hard shadow edge (nearest depth test) is
// one step; blurred with W = 16 pixels at z_b = 5 it becomes a ramp of w(z) pixels: 16 with the
// ground at depth 5, 8 with it at depth 10 (w = 16 x 5 / 10). The box's weights give an even w
// exactly w pixels strictly between 0 and 1; the edge's own texel steps may add one.
TEST(EyeBlur, EdgeRampIsTheKernelWidthAndNarrowsWithDepth) {
    for (const float height : {5.0f, 10.0f}) {
        SCOPED_TRACE(height);
        auto app = test::makeHeadlessApp(writeScene(height).string(), kSize);
        ASSERT_TRUE(app);
        std::vector<std::string> sets = kHardMap;
        sets.push_back("host.shadow_blur=0");
        const auto sharp = middleColumn(test::renderVisibility(*app, "shadowmap", sets));
        const auto [sharpLower, sharpUpper] = rampWidths(sharp);
        EXPECT_EQ(sharpLower + sharpUpper, 0) << "the unblurred hard edge is one step";
        EXPECT_LT(sharp[size_t(kSize.y / 2)], 0.02f) << "the band's middle is in shadow";
        sets.back() = "host.shadow_blur=16";
        sets.push_back("host.shadow_blur_depth=5");
        const auto blurred = middleColumn(test::renderVisibility(*app, "shadowmap", sets));
        const auto [lower, upper] = rampWidths(blurred);
        const int expected = int(std::lround(eyeBlurWidth(16.0f, 5.0f, height)));
        std::printf("eye blur, ground at depth %.0f: ramps %d and %d pixels (w(z) = %d)\n", height, lower, upper, expected);
        EXPECT_GE(lower, expected - 1);
        EXPECT_LE(lower, expected + 1);
        EXPECT_GE(upper, expected - 1);
        EXPECT_LE(upper, expected + 1);
        EXPECT_LT(blurred[size_t(kSize.y / 2)], 0.02f) << "the middle of the band stays in shadow";
    }
}

// Sec. 6.2's rules (Fig. 6.7), on a pixel in the post's shadow and one in the light, read from
// the linear colour target: ambient is never shadowed, diffuse and specular vanish in shadow;
// lighting = none puts the term on the unlit surface, albedo (ambient + light s). With the blur on,
// a pixel on the ramp gets ambient + (diffuse + specular) s with s the blurred term.
TEST(EyeBlur, LightingRulesOnALitAndAShadowedPixel) {
    auto app = test::makeHeadlessApp(writeScene(5.0f).string(), kSize);
    ASSERT_TRUE(app);
    const glm::vec3 albedo(0.5f), ambient(0.1f), specular(0.5f);
    const float shininess = 8.0f;
    const glm::vec3 toLight = -glm::normalize(app->light().direction);
    auto render = [&](const std::vector<std::string>& host) {
        std::vector<std::string> sets = kHardMap;
        sets.insert(sets.end(), host.begin(), host.end());
        const auto visibility = test::renderVisibility(*app, "shadowmap", sets);
        return std::make_pair(test::readTarget(*app, MainTarget::Color), visibility);
    };
    const size_t shadowed = size_t(kSize.y / 2) * kSize.x + kSize.x / 2;   // world (0, 0, 0)
    const size_t lit = size_t(kSize.y / 2) * kSize.x + kSize.x - 20;        // world (2.5, 0, 0)
    auto phongAt = [&](size_t pixel, const std::vector<glm::vec4>& positions, float s) {
        const glm::vec3 p(positions[pixel]), N(0, 1, 0);
        const glm::vec3 V = glm::normalize(app->lastFrame().camera.position - p), H = glm::normalize(toLight + V);
        const float NdotL = glm::dot(N, toLight);
        return ambient * albedo + (albedo * NdotL + specular * std::pow(glm::dot(N, H), shininess)) * s;
    };
    const auto [phong, phongTerm] = render({"host.shadow_blur=0", "host.lighting=phong"});
    const auto positions = test::readTarget(*app, MainTarget::Position);
    ASSERT_LT(phongTerm[shadowed].r, 0.01f);
    ASSERT_GT(phongTerm[lit].r, 0.99f);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(phong[shadowed][c], ambient[c] * albedo[c], 1e-3f) << "in shadow: ambient alone";
        EXPECT_NEAR(phong[lit][c], phongAt(lit, positions, 1.0f)[c], 2e-3f) << "lit: ambient + diffuse + specular";
    }
    const auto [unlit, unlitTerm] = render({"host.shadow_blur=0", "host.lighting=none"});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(unlit[shadowed][c], ambient[c] * albedo[c], 1e-3f);
        EXPECT_NEAR(unlit[lit][c], albedo[c] * (ambient[c] + 1.0f), 2e-3f) << "unlit: no N.L, no specular";
    }
    // Blurred: on the lower edge's ramp the colour follows the blurred term.
    const auto [blurred, blurredTerm] = render({"host.shadow_blur=16", "host.shadow_blur_depth=5", "host.lighting=phong"});
    int checked = 0;
    for (int y = 0; y < kSize.y / 2; ++y) {
        const size_t pixel = size_t(y) * kSize.x + kSize.x / 2;
        const float s = blurredTerm[pixel].r;
        if (!(s > 0.05f && s < 0.95f)) continue;
        ++checked;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(blurred[pixel][c], phongAt(pixel, positions, s)[c], 2e-3f) << "row " << y;
    }
    EXPECT_GE(checked, 10) << "the ramp is about 16 pixels";
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(blurred[shadowed][c], ambient[c] * albedo[c], 1e-3f) << "deep in shadow: ambient";
    std::string error;
    EXPECT_TRUE(app->applyAssignments({"host.shadow_blur=0", "host.lighting=phong"}, "shadowmap", error)) << error;
}

// The host's parameters are checked like a technique's: out of range or an unknown one is refused
// with the parameter named.
TEST(EyeBlur, HostParametersAreChecked) {
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    std::string error;
    EXPECT_FALSE(app->applyAssignments({"host.shadow_blur=17"}, "shadowmap", error));
    EXPECT_NE(error.find("shadow_blur"), std::string::npos) << error;
    EXPECT_FALSE(app->applyAssignments({"host.lighting=flat"}, "shadowmap", error));
    EXPECT_NE(error.find("phong"), std::string::npos) << error;
    EXPECT_FALSE(app->applyAssignments({"host.blur=2"}, "shadowmap", error));
    EXPECT_DOUBLE_EQ(app->hostValues()[kHostShadowBlur], 0.0) << "off by default";
    EXPECT_DOUBLE_EQ(app->hostValues()[kHostShadowBlurDepth], 10.0);
    EXPECT_TRUE(app->applyAssignments({"host.shadow_blur=8"}, "shadowmap", error)) << error;
    EXPECT_DOUBLE_EQ(app->hostValues()[kHostShadowBlur], 8.0);
}

// Sweeps take the host's parameters like a technique's (Fig. 6.6's widths as one sweep), checked
// before the run.
TEST(EyeBlur, BenchSweepsTakeTheHostParameters) {
    PluginScan scan = scanPlugins(pluginDir());
    scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));
    auto check = [&](const std::string& sweep, std::string& error) {
        BenchSpec spec;
        spec.fromCommandLine = true;
        EXPECT_TRUE(addSweep(spec, sweep, error)) << error;
        return checkBenchSpec(spec, scan.techniques, error);
    };
    std::string error;
    EXPECT_TRUE(check("host.shadow_blur=0,1,2,4,8,16", error)) << error;
    EXPECT_TRUE(check("host.lighting=phong,none", error)) << error;
    EXPECT_FALSE(check("host.shadow_blur=0,32", error));
    EXPECT_NE(error.find("out of range"), std::string::npos) << error;
    EXPECT_FALSE(check("host.lighting=flat", error));
    EXPECT_NE(error.find("phong"), std::string::npos) << error;
    EXPECT_TRUE(isHostKey("host.shadow_blur_depth"));
    EXPECT_FALSE(isHostKey("host.blur"));
}
