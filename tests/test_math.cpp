// Closed-form checks: the planar projection matrix (seed 000 eq. 3.1-3.3 and its generalisation),
// light-space fitting, and timing percentiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "shadowlab/kit/planar_projection.h"
#include "render/light_space.h"
#include "util/stats.h"

using namespace shadowlab;

TEST(PlanarProjection, MatchesSeedEquation3_3ForGroundPlane) {
    const glm::vec4 light(1.5f, 6.0f, -2.0f, 1.0f);
    const glm::mat4 m = planar::projectionMatrix({0, 1, 0, 0}, light);
    // eq. 3.3, row by row (glm is column-major: m[column][row]).
    const float expected[4][4] = {{6.0f, -1.5f, 0, 0}, {0, 0, 0, 0}, {0, 2.0f, 6.0f, 0}, {0, -1, 0, 6.0f}};
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) EXPECT_FLOAT_EQ(m[col][row], expected[row][col]) << row << "," << col;
}

TEST(PlanarProjection, PointLightProjectionMatchesEquations3_1And3_2) {
    const glm::vec3 l(0.7f, 5.0f, -1.2f);
    const glm::mat4 m = planar::projectionMatrix({0, 1, 0, 0}, glm::vec4(l, 1.0f));
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-3.0f, 3.0f), height(0.0f, 4.5f);
    for (int i = 0; i < 100; ++i) {
        const glm::vec3 v(coord(rng), height(rng), coord(rng));
        const glm::vec4 p = m * glm::vec4(v, 1.0f);
        // eq. 3.1 and 3.2: p_x = (l_y v_x - l_x v_y) / (l_y - v_y), likewise z; p_y = 0.
        EXPECT_NEAR(p.x / p.w, (l.y * v.x - l.x * v.y) / (l.y - v.y), 1e-4f);
        EXPECT_NEAR(p.z / p.w, (l.y * v.z - l.z * v.y) / (l.y - v.y), 1e-4f);
        EXPECT_NEAR(p.y / p.w, 0.0f, 1e-5f);
    }
}

TEST(PlanarProjection, AnyPlaneAndDirectionalLightLandOnThePlaneAlongTheRay) {
    // Tilted plane through (0, 1, 0) with normal n; directional light towards d.
    const glm::vec3 n = glm::normalize(glm::vec3(0.3f, 1.0f, -0.2f));
    const glm::vec4 plane(n, -glm::dot(n, glm::vec3(0, 1, 0)));
    const glm::vec3 toLight = glm::normalize(glm::vec3(-0.4f, 1.0f, 0.5f));
    const glm::mat4 m = planar::projectionMatrix(plane, glm::vec4(toLight, 0.0f));
    for (const glm::vec3 v : {glm::vec3(0.5f, 2.0f, 0.1f), glm::vec3(-1.0f, 3.0f, 2.0f), glm::vec3(2.0f, 1.5f, -1.0f)}) {
        const glm::vec4 h = m * glm::vec4(v, 1.0f);
        const glm::vec3 p = glm::vec3(h) / h.w;
        EXPECT_NEAR(glm::dot(plane, glm::vec4(p, 1.0f)), 0.0f, 1e-4f) << "projected point is on the plane";
        // p - v is parallel to the light direction.
        EXPECT_NEAR(glm::length(glm::cross(p - v, toLight)), 0.0f, 1e-4f);
    }
}

TEST(LightSpace, DirectionalFitContainsBoundsAndLooksAlongTheLight) {
    LightInfo light{};
    light.type = LightType::Directional;
    light.direction = glm::normalize(glm::vec3(-0.5f, -1.0f, -0.3f));
    const Bounds bounds{{-10, 0, -10}, {10, 2, 10}};
    const LightSpace ls = fitLightSpace(light, bounds);
    EXPECT_FALSE(ls.perspective);
    glm::vec3 corners[8];
    boxCorners(bounds, corners);
    float minX = 1, maxX = -1;
    for (const auto& c : corners) {
        const glm::vec4 ndc = ls.viewProjection * glm::vec4(c, 1.0f);
        EXPECT_LE(std::abs(ndc.x / ndc.w), 1.0001f);
        EXPECT_LE(std::abs(ndc.y / ndc.w), 1.0001f);
        EXPECT_LE(std::abs(ndc.z / ndc.w), 1.0001f);
        minX = std::min(minX, ndc.x);
        maxX = std::max(maxX, ndc.x);
    }
    EXPECT_LT(minX, -0.99f) << "fit is tight";
    EXPECT_GT(maxX, 0.99f);
    // Moving a point along the light direction increases its depth and keeps x, y.
    const glm::vec4 a = ls.viewProjection * glm::vec4(0, 1, 0, 1);
    const glm::vec4 b = ls.viewProjection * glm::vec4(glm::vec3(0, 1, 0) + light.direction, 1);
    EXPECT_NEAR(a.x, b.x, 1e-4f);
    EXPECT_NEAR(a.y, b.y, 1e-4f);
    EXPECT_GT(b.z, a.z);
}

TEST(LightSpace, SpotFitUsesConeAndDepthRange) {
    LightInfo light{};
    light.type = LightType::Spot;
    light.position = {0, 8, 0};
    light.direction = {0, -1, 0};
    light.spotOuterAngle = glm::radians(30.0f);
    const Bounds bounds{{-3, 0, -3}, {3, 1, 3}};
    const LightSpace ls = fitLightSpace(light, bounds);
    EXPECT_TRUE(ls.perspective);
    EXPECT_NEAR(ls.nearPlane, 7.0f * 0.99f, 1e-3f);
    EXPECT_GE(ls.farPlane, 8.0f);
    // A point on the cone's edge at the ground projects to the map's border.
    const glm::vec3 edge(std::tan(light.spotOuterAngle) * 8.0f, 0.0f, 0.0f);
    const glm::vec4 clip = ls.viewProjection * glm::vec4(edge, 1.0f);
    EXPECT_NEAR(std::abs(clip.x / clip.w), 1.0f / 1.02f, 0.02f);
}

TEST(Stats, PercentilesInterpolateBetweenRanks) {
    std::vector<double> values;
    for (int i = 100; i >= 1; --i) values.push_back(double(i));   // unsorted on purpose
    const TimingSummary s = summarize(values);
    EXPECT_EQ(s.count, 100u);
    EXPECT_DOUBLE_EQ(s.median, 50.5);
    EXPECT_NEAR(s.p5, 5.95, 1e-12);
    EXPECT_NEAR(s.p95, 95.05, 1e-12);
    EXPECT_DOUBLE_EQ(s.mean, 50.5);
    EXPECT_DOUBLE_EQ(percentile({3.0}, 0.95), 3.0);
    EXPECT_DOUBLE_EQ(summarize({}).median, 0.0);
}

// The linear-time selection gives exactly what interpolating in a sorted copy gives, ties included.
// The median's distribution-free 95% interval: ranks n/2 -+ 1.96 sqrt(n)/2 of the sorted set.
TEST(Stats, MedianConfidenceHalfWidthFollowsTheOrderStatistics) {
    EXPECT_TRUE(std::isinf(medianRelativeHalfWidth95({1, 2, 3, 4, 5})));   // too few
    EXPECT_EQ(medianRelativeHalfWidth95(std::vector<double>(40, 2.0)), 0.0);
    // n = 100: ranks floor(50 - 9.8) = 40 and ceil(51 + 9.8) = 61 (1-based) of 1..100, median 50.5.
    std::vector<double> values;
    for (int i = 100; i >= 1; --i) values.push_back(double(i));
    EXPECT_NEAR(medianRelativeHalfWidth95(values), (61.0 - 40.0) / (2.0 * 50.5), 1e-12);
    // More samples of the same spread narrow it (about as 1 / sqrt(n)).
    std::mt19937 random(3);
    std::normal_distribution<double> noise(10.0, 0.5);
    std::vector<double> few(16), many(256);
    for (double& v : few) v = noise(random);
    for (double& v : many) v = noise(random);
    EXPECT_LT(medianRelativeHalfWidth95(many), 0.5 * medianRelativeHalfWidth95(few));
    // The stop rule: not before minFrames, and only when the interval is narrow enough.
    const TimingStop stop{12, 0.01};
    EXPECT_FALSE(stop.reached(std::vector<double>(11, 3.0)));
    EXPECT_TRUE(stop.reached(std::vector<double>(12, 3.0)));
    EXPECT_FALSE(stop.reached(few));
    EXPECT_FALSE(TimingStop{}.reached(std::vector<double>(100, 3.0)));   // within 0: every frame
}

TEST(Stats, PercentilesEqualThoseOfASortedCopy) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> small(0, 40);   // many ties
    for (int trial = 0; trial < 20; ++trial) {
        std::vector<double> values(size_t(1 + trial * 37));
        for (double& v : values) v = trial % 2 ? double(small(random)) : std::ldexp(double(random()), -20);
        std::vector<double> sorted = values;
        std::sort(sorted.begin(), sorted.end());
        for (const double fraction : {0.0, 0.05, 0.5, 0.95, 1.0, 0.333}) {
            const double rank = fraction * double(sorted.size() - 1);
            const size_t below = size_t(std::floor(rank)), above = std::min(below + 1, sorted.size() - 1);
            const double expected = sorted[below] + (sorted[above] - sorted[below]) * (rank - double(below));
            EXPECT_EQ(percentile(values, fraction), expected) << trial << " " << fraction;
        }
    }
}
