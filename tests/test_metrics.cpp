// Accuracy metrics against hand-built images whose answers are known exactly: error means,
// false shadow / false light rates, the penumbra class, the mask, the heatmap's colours, JSON.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "groundtruth/metrics.h"

using namespace shadowlab;

namespace {

std::vector<glm::vec3> grey(std::initializer_list<float> values) {
    std::vector<glm::vec3> image;
    for (float v : values) image.emplace_back(v);
    return image;
}

// 4 x 2, row 0 first. Pixel 7 is excluded; it is lit in the reference and badly wrong in the
// technique, so any use of it shows up.
//   reference  1 1 0 0      technique  1 0.2 0.6 0      mask  1 1 1 1
//              1 1 0 1                 1 1   0   0            1 1 1 0
struct SmallCase {
    int width = 4, height = 2;
    std::vector<glm::vec3> reference = grey({1, 1, 0, 0, 1, 1, 0, 1});
    std::vector<glm::vec3> technique = grey({1, 0.2f, 0.6f, 0, 1, 1, 0, 0});
    std::vector<uint8_t> mask = {1, 1, 1, 1, 1, 1, 1, 0};
};

std::array<uint8_t, 3> pixel(const std::vector<uint8_t>& rgb, size_t i) { return {rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]}; }

} // namespace

TEST(Metrics, ErrorsAndRatesOfAKnownImage) {
    const SmallCase c;
    const AccuracyMetrics m = compareVisibility(c.technique, c.reference, c.mask, c.width, c.height);
    EXPECT_EQ(m.comparedPixels, 7u);
    EXPECT_DOUBLE_EQ(m.comparedFraction, 7.0 / 8.0);
    EXPECT_NEAR(m.mae, (0.8 + 0.6) / 7.0, 1e-6);
    EXPECT_NEAR(m.rmse, std::sqrt((0.64 + 0.36) / 7.0), 1e-6);
    EXPECT_NEAR(m.maePerChannel.r, m.mae, 1e-6);
    EXPECT_NEAR(m.maePerChannel.g, m.mae, 1e-6);
    EXPECT_NEAR(m.maePerChannel.b, m.mae, 1e-6);
    EXPECT_DOUBLE_EQ(m.falseShadowRate, 1.0 / 7.0); // pixel 1: lit, technique 0.2
    EXPECT_DOUBLE_EQ(m.falseLightRate, 1.0 / 7.0);  // pixel 2: shadowed, technique 0.6
}

TEST(Metrics, HardReferenceHasABoundaryPenumbraClass) {
    const SmallCase c;
    const AccuracyMetrics m = compareVisibility(c.technique, c.reference, c.mask, c.width, c.height);
    // Pixels 1, 2, 5, 6 touch the other class; 0, 3, 4 do not (pixel 3's lit neighbour 7 is
    // excluded, so it is no edge).
    EXPECT_EQ(m.penumbraPixels, 4u);
    EXPECT_NEAR(m.maePenumbra, (0.8 + 0.6) / 4.0, 1e-6);
    EXPECT_DOUBLE_EQ(m.maeOutsidePenumbra, 0.0);
}

TEST(Metrics, PartialVisibilityIsPenumbra) {
    // 3 x 1, all lit but the middle at 0.5 (between 0.02 and 0.98): only the middle is penumbra,
    // its neighbours are lit like it (0.5 counts as lit).
    const auto reference = grey({1, 0.5f, 1});
    const auto technique = grey({1, 0.0f, 0.9f});
    const AccuracyMetrics m = compareVisibility(technique, reference, {1, 1, 1}, 3, 1);
    EXPECT_EQ(m.penumbraPixels, 1u);
    EXPECT_NEAR(m.maePenumbra, 0.5, 1e-6);
    EXPECT_NEAR(m.maeOutsidePenumbra, 0.05, 1e-6);
    EXPECT_NEAR(m.falseShadowRate, 1.0 / 3.0, 1e-12); // 0.5 is lit; technique 0 is shadowed
    EXPECT_DOUBLE_EQ(m.falseLightRate, 0.0);
}

TEST(Metrics, PerChannelErrorOfColouredShadows) {
    const std::vector<glm::vec3> reference = {glm::vec3(1.0f), glm::vec3(1.0f, 0.5f, 0.5f)};
    const std::vector<glm::vec3> technique = {glm::vec3(1.0f, 0.5f, 0.5f), glm::vec3(1.0f, 0.5f, 0.5f)};
    const AccuracyMetrics m = compareVisibility(technique, reference, {1, 1}, 2, 1);
    EXPECT_NEAR(m.maePerChannel.r, 0.0, 1e-9);
    EXPECT_NEAR(m.maePerChannel.g, 0.25, 1e-9);
    EXPECT_NEAR(m.maePerChannel.b, 0.25, 1e-9);
    EXPECT_NEAR(m.mae, (1.0 / 3.0) / 2.0, 1e-6); // scalar = mean of rgb: 1 vs 2/3, then equal
}

TEST(Metrics, NothingComparedGivesZerosNotNaN) {
    const SmallCase c;
    const AccuracyMetrics m = compareVisibility(c.technique, c.reference, std::vector<uint8_t>(8, 0), 4, 2);
    EXPECT_EQ(m.comparedPixels, 0u);
    EXPECT_EQ(m.mae, 0.0);
    EXPECT_EQ(m.rmse, 0.0);
    EXPECT_EQ(m.comparedFraction, 0.0);
    EXPECT_EQ(nlohmann::json::parse(metricsToJson(m))["mae"], 0.0);
}

TEST(Metrics, RejectsMismatchedSizes) {
    const SmallCase c;
    EXPECT_THROW(compareVisibility(c.technique, c.reference, c.mask, 3, 2), std::invalid_argument);
    EXPECT_THROW(errorHeatmap(c.technique, grey({1}), c.mask, 4, 2), std::invalid_argument);
}

TEST(Metrics, CompareMaskExcludesBackgroundBackFacesAndOutsideTheCone) {
    // Ground points under a spot at (0, 4, 0) looking straight down with a 0.5 rad cone:
    // x = 0 inside, x = 3 outside (atan(3/4) = 0.64), background, a face turned away.
    const std::vector<glm::vec4> positions = {{0, 0, 0, 1}, {3, 0, 0, 1}, {0, 0, 0, 0}, {0.5f, 0, 0, 1}};
    const std::vector<glm::vec4> normals = {{0, 1, 0, 0}, {0, 1, 0, 0}, {0, 1, 0, 0}, {0, -1, 0, 0}};
    const GBufferView gbuffer{4, 1, positions.data(), normals.data()};
    LightInfo spot;
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0, 4, 0);
    spot.direction = glm::vec3(0, -1, 0);
    spot.spotOuterAngle = 0.5f;
    EXPECT_EQ(compareMask(gbuffer, spot), (std::vector<uint8_t>{1, 0, 0, 0}));

    LightInfo point = spot;
    point.type = LightType::Point; // no cone
    EXPECT_EQ(compareMask(gbuffer, point), (std::vector<uint8_t>{1, 1, 0, 0}));

    LightInfo sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(1, -1, 0));
    EXPECT_EQ(compareMask(gbuffer, sun), (std::vector<uint8_t>{1, 1, 0, 0}));
}

TEST(Metrics, HeatmapColoursAsDocumented) {
    // excluded, lit match, shadowed match, false shadow, false light, partial false shadow
    const auto reference = grey({1, 1, 0, 1, 0, 1});
    const auto technique = grey({0, 1, 0, 0, 1, 0.75f});
    const std::vector<uint8_t> mask = {0, 1, 1, 1, 1, 1};
    const std::vector<uint8_t> rgb = errorHeatmap(technique, reference, mask, 6, 1);
    ASSERT_EQ(rgb.size(), 18u);
    using Rgb = std::array<uint8_t, 3>;
    EXPECT_EQ(pixel(rgb, 0), (Rgb{24, 24, 24}));
    EXPECT_EQ(pixel(rgb, 1), (Rgb{128, 128, 128}));
    EXPECT_EQ(pixel(rgb, 2), (Rgb{56, 56, 56}));
    EXPECT_EQ(pixel(rgb, 3), (Rgb{255, 0, 255}));
    EXPECT_EQ(pixel(rgb, 4), (Rgb{0, 255, 0}));
    // e = -0.25, a = 0.5: halfway from grey 128 to magenta
    EXPECT_EQ(pixel(rgb, 5), (Rgb{192, 64, 192}));
}

TEST(Metrics, JsonCarriesEveryField) {
    const SmallCase c;
    const AccuracyMetrics m = compareVisibility(c.technique, c.reference, c.mask, c.width, c.height);
    const nlohmann::json json = nlohmann::json::parse(metricsToJson(m));
    EXPECT_DOUBLE_EQ(json["mae"].get<double>(), m.mae);
    EXPECT_DOUBLE_EQ(json["rmse"].get<double>(), m.rmse);
    EXPECT_DOUBLE_EQ(json["falseShadowRate"].get<double>(), m.falseShadowRate);
    EXPECT_DOUBLE_EQ(json["falseLightRate"].get<double>(), m.falseLightRate);
    EXPECT_DOUBLE_EQ(json["maePenumbra"].get<double>(), m.maePenumbra);
    EXPECT_DOUBLE_EQ(json["maeOutsidePenumbra"].get<double>(), m.maeOutsidePenumbra);
    EXPECT_EQ(json["maePerChannel"].size(), 3u);
    EXPECT_DOUBLE_EQ(json["maePerChannel"][1].get<double>(), m.maePerChannel.g);
    EXPECT_DOUBLE_EQ(json["comparedFraction"].get<double>(), m.comparedFraction);
    EXPECT_EQ(json["comparedPixels"].get<size_t>(), 7u);
    EXPECT_EQ(json["penumbraPixels"].get<size_t>(), 4u);
}

TEST(Metrics, NoiseEnergySeparatesNoiseFromSmoothError) {
    const int w = 16, h = 16;
    const std::vector<glm::vec3> reference(size_t(w * h), glm::vec3(0.5f));
    const std::vector<uint8_t> mask(size_t(w * h), 1);
    // A constant offset (a smooth bias) has no high-frequency part.
    const std::vector<glm::vec3> offset(size_t(w * h), glm::vec3(0.6f));
    EXPECT_NEAR(compareVisibility(offset, reference, mask, w, h).noiseEnergy, 0.0, 1e-9);
    // A checkerboard of +-0.1 is all high frequency: |e - mean(neighbours)| = 0.2 everywhere.
    std::vector<glm::vec3> checker(size_t(w * h));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) checker[size_t(y * w + x)] = glm::vec3((x + y) % 2 ? 0.6f : 0.4f);
    const AccuracyMetrics m = compareVisibility(checker, reference, mask, w, h);
    EXPECT_NEAR(m.noiseEnergy, 0.2, 1e-6);
    EXPECT_NEAR(m.techniquePenumbraFraction, 1.0, 1e-12) << "every technique value is between 0.02 and 0.98";
}

// View-depth thirds of [near, far] = [1, 10]: thirds end at 4 and 7. With the camera at the origin
// looking down -z (view = identity), pixel i of the small case sits at depth 1.5, 3, 4.5, 6, 7.5, 9,
// 9.9 and 12 (the last excluded by the mask): pixels 0-1 near, 2-3 mid, 4-6 far.
TEST(Metrics, ErrorByViewDepthThird) {
    const SmallCase c;
    const float depths[8] = {1.5f, 3, 4.5f, 6, 7.5f, 9, 9.9f, 12};
    std::vector<glm::vec4> positions;
    for (float d : depths) positions.emplace_back(0.3f, -0.2f, -d, 1.0f);
    AccuracyMetrics m = compareVisibility(c.technique, c.reference, c.mask, c.width, c.height);
    addViewDepthThirds(m, c.technique, c.reference, c.mask, positions.data(), c.width, c.height, glm::mat4(1.0f), 1.0f, 10.0f);
    // Errors: 0, 0.8 | 0.6, 0 | 0, 0, 0 (pixel 7's 1.0 is masked out).
    EXPECT_EQ(m.pixelsByViewDepth[0], 2u);
    EXPECT_EQ(m.pixelsByViewDepth[1], 2u);
    EXPECT_EQ(m.pixelsByViewDepth[2], 3u);
    EXPECT_NEAR(m.maeByViewDepth[0], 0.4, 1e-6);
    EXPECT_NEAR(m.maeByViewDepth[1], 0.3, 1e-6);
    EXPECT_NEAR(m.maeByViewDepth[2], 0.0, 1e-6);
    const nlohmann::json json = nlohmann::json::parse(metricsToJson(m));
    EXPECT_NEAR(json["maeByViewDepth"][0].get<double>(), 0.4, 1e-6);
    EXPECT_EQ(json["comparedPixelsByViewDepth"][2].get<size_t>(), 3u);
    EXPECT_THROW(addViewDepthThirds(m, c.technique, c.reference, c.mask, positions.data(), c.width, c.height,
                                    glm::mat4(1.0f), 5.0f, 5.0f),
                 std::invalid_argument);
}
