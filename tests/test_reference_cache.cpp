// The reference cache (issue 32): every technique measured on one frame shares one trace, with
// figures identical to tracing each time, and any change of what the reference depends on misses.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bench/bench.h"
#include "groundtruth/reference_cache.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

// Every figure a row holds, less the ones that time something (they differ between any two runs).
bool isTiming(const std::string& key) {
    return key.find("_ms") != std::string::npos || key == "date" || key.rfind("stat.", 0) == 0 || key == "trace_seconds" ||
           key.rfind("seconds_", 0) == 0;
}

} // namespace

TEST(ReferenceCache, ASweepGivesTheSameFiguresWithAndWithoutIt) {
    BenchSpec spec;
    spec.techniques = {"shadowmap", "pcf", "translucent-shadows"};
    spec.scenes = {"teapot-glass"};   // translucent receivers: their layers are traced too
    spec.sizes = {{96, 64}};
    spec.frames = 1;
    spec.warmupFrames = 0;
    spec.accuracy = true;
    spec.reference = "both";
    spec.referenceSamples = 64;
    std::vector<nlohmann::json> cachedRows, tracedRows;
    uint64_t hits = 0;
    for (const bool cached : {true, false}) {
        auto app = test::makeHeadlessApp("teapot-glass", {96, 64});
        ASSERT_TRUE(app);
        app->referenceCache().enabled = cached;
        std::string error;
        ASSERT_TRUE(runBench(*app, spec, cached ? cachedRows : tracedRows, error)) << error;
        if (cached) hits = app->referenceCache().hits;
        else EXPECT_EQ(app->referenceCache().hits, 0u);
    }
    // Three techniques on one frame: the hard and soft physical references (and the opaque one of
    // the two opaque-model techniques) are each traced once.
    EXPECT_GE(hits, 4u);
    ASSERT_EQ(cachedRows.size(), tracedRows.size());
    size_t compared = 0;
    for (size_t r = 0; r < cachedRows.size(); ++r) {
        for (const auto& [key, value] : tracedRows[r].items()) {
            if (isTiming(key)) continue;
            ASSERT_TRUE(cachedRows[r].contains(key)) << key;
            EXPECT_EQ(cachedRows[r][key], value) << "row " << r << " " << key;   // bit for bit
            compared += key.find("mae") != std::string::npos;
        }
    }
    EXPECT_GT(compared, 20u);
}

TEST(ReferenceCache, AChangeOfAnyIngredientMisses) {
    const int width = 4, height = 3;
    std::vector<glm::vec4> positions(size_t(width * height), glm::vec4(1.0f, 2.0f, 3.0f, 1.0f));
    std::vector<glm::vec4> normals(size_t(width * height), glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
    const GBufferView gbuffer{width, height, positions.data(), normals.data()};
    LightInfo light;
    ReferenceOptions options;
    using Key = ReferenceCache::Key;
    const Key base = ReferenceCache::keyOf(gbuffer, light, options, 7);
    EXPECT_EQ(ReferenceCache::keyOf(gbuffer, light, options, 7), base);
    options.threads = 3;   // changes no sample
    EXPECT_EQ(ReferenceCache::keyOf(gbuffer, light, options, 7), base);
    options.threads = 0;

    auto expectMiss = [&](const char* what, auto change) {
        std::vector<glm::vec4> p = positions, n = normals;
        LightInfo l = light;
        ReferenceOptions o = options;
        uint64_t generation = 7;
        GBufferView g{width, height, p.data(), n.data()};
        change(p, n, l, o, generation, g);
        EXPECT_NE(ReferenceCache::keyOf(g, l, o, generation), base) << what;
    };
    using P = std::vector<glm::vec4>;
    expectMiss("one position", [](P& p, P&, LightInfo&, ReferenceOptions&, uint64_t&, GBufferView&) {
        p[5].x = std::nextafter(p[5].x, 2.0f);
    });
    expectMiss("one normal", [](P&, P& n, LightInfo&, ReferenceOptions&, uint64_t&, GBufferView&) { n[11].z = 1e-7f; });
    expectMiss("size", [](P&, P&, LightInfo&, ReferenceOptions&, uint64_t&, GBufferView& g) {
        g.width = 3;
        g.height = 4;
    });
    expectMiss("light direction", [](P&, P&, LightInfo& l, ReferenceOptions&, uint64_t&, GBufferView&) { l.direction.x = 0.01f; });
    expectMiss("light position", [](P&, P&, LightInfo& l, ReferenceOptions&, uint64_t&, GBufferView&) { l.position.y += 1.0f; });
    expectMiss("light size", [](P&, P&, LightInfo& l, ReferenceOptions&, uint64_t&, GBufferView&) { l.size = 0.02f; });
    expectMiss("light type", [](P&, P&, LightInfo& l, ReferenceOptions&, uint64_t&, GBufferView&) { l.type = LightType::Spot; });
    expectMiss("spot cone", [](P&, P&, LightInfo& l, ReferenceOptions&, uint64_t&, GBufferView&) { l.spotOuterAngle = 0.6f; });
    expectMiss("mode", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.mode = ReferenceOptions::Mode::Soft; });
    expectMiss("rays", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.samplesPerPixel = 65; });
    expectMiss("seed", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.seed = 2; });
    expectMiss("model", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) {
        o.model = TranslucencyModel::Physical;
    });
    expectMiss("adaptive", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.adaptive = true; });
    expectMiss("first batch", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.firstBatch = 16; });
    expectMiss("refine radius", [](P&, P&, LightInfo&, ReferenceOptions& o, uint64_t&, GBufferView&) { o.refineRadius = 3; });
    expectMiss("scene generation", [](P&, P&, LightInfo&, ReferenceOptions&, uint64_t& g, GBufferView&) { g = 8; });
}

TEST(ReferenceCache, KeepsTheNewestEntriesAndReturnsWhatWasStored) {
    ReferenceCache cache;
    ReferenceStats stats;
    stats.samplesPerPixel = 5;
    stats.sampleError = {0.25f};
    for (uint64_t i = 0; i < ReferenceCache::kMaxEntries + 2; ++i)
        cache.insert({i, ~i}, std::vector<glm::vec3>(3, glm::vec3(float(i))), stats);
    EXPECT_EQ(cache.find({0, ~0ull}), nullptr);   // the oldest were dropped
    EXPECT_EQ(cache.find({1, ~1ull}), nullptr);
    const ReferenceStats* found = nullptr;
    const auto* newest = cache.find({ReferenceCache::kMaxEntries + 1, ~uint64_t(ReferenceCache::kMaxEntries + 1)}, &found);
    ASSERT_NE(newest, nullptr);
    EXPECT_EQ((*newest)[2], glm::vec3(float(ReferenceCache::kMaxEntries + 1)));
    ASSERT_NE(found, nullptr);
    EXPECT_EQ(found->samplesPerPixel, 5);
    EXPECT_EQ(found->sampleError, std::vector<float>{0.25f});
    EXPECT_EQ(cache.hits, 1u);
    EXPECT_EQ(cache.misses, 2u);
    cache.enabled = false;
    EXPECT_EQ(cache.find({ReferenceCache::kMaxEntries + 1, ~uint64_t(ReferenceCache::kMaxEntries + 1)}), nullptr);
}

// A row's evaluation beside the next row's timed frames (issue 32, bench.cpp PendingEvaluation):
// the same rows in the same order with the same figures as evaluating each row before the next,
// across a scene change (the pending trace is joined before the scene is swapped) and with
// depth-floor rows between the evaluated ones.
TEST(BenchOverlap, RowsAndFiguresAreThoseOfASerialSweep) {
    BenchSpec spec;
    spec.techniques = {"shadowmap", "pcf"};
    spec.scenes = {"cube", "contact"};
    spec.sizes = {{96, 64}};
    spec.frames = 1;
    spec.warmupFrames = 0;
    spec.accuracy = true;
    spec.depthFloor = true;
    spec.reference = "both";
    spec.referenceSamples = 64;
    std::vector<nlohmann::json> overlapped, serial;
    for (const bool overlap : {true, false}) {
        auto app = test::makeHeadlessApp("cube", {96, 64});
        ASSERT_TRUE(app);
        app->referenceCache().enabled = false;   // every row traces: the worker has work to overlap
        spec.overlapAccuracy = overlap;
        std::string error;
        std::vector<std::string> seen;
        ASSERT_TRUE(runBench(*app, spec, overlap ? overlapped : serial, error,
                             [&](const nlohmann::json& row) { seen.push_back(row.value("technique", "")); }))
            << error;
        EXPECT_EQ(seen.size(), (overlap ? overlapped : serial).size());   // onRow once a row, in order
    }
    ASSERT_EQ(overlapped.size(), serial.size());
    size_t compared = 0;
    for (size_t r = 0; r < serial.size(); ++r) {
        EXPECT_EQ(overlapped[r].value("scene", ""), serial[r].value("scene", ""));
        for (const auto& [key, value] : serial[r].items()) {
            if (isTiming(key) || key == "frames" || key == "gpu_bytes") continue;
            ASSERT_TRUE(overlapped[r].contains(key)) << "row " << r << " " << key;
            EXPECT_EQ(overlapped[r][key], value) << "row " << r << " " << key;   // bit for bit
            compared += key.find("mae") != std::string::npos;
        }
    }
    EXPECT_GT(compared, 20u);
}
