// The window's "Measure accuracy" on a worker thread (issue 32, ui/async_measurement.h): the
// frames captured at the start through a pixel-pack buffer and traced on the worker give exactly
// what the synchronous measurement gives (figures and heatmap), while the caller goes on drawing
// frames; a cancelled trace stops early, is never cached, and the object can be cancelled or
// destroyed mid-trace and started again on another scene.
#include <gtest/gtest.h>

#include <chrono>
#include <optional>
#include <thread>

#include "test_support.h"
#include "ui/async_measurement.h"

namespace shadowlab {
namespace {

using Clock = std::chrono::steady_clock;

ReferenceOptions referenceOptions(ReferenceOptions::Mode mode, int samples, TranslucencyModel model = TranslucencyModel::Physical) {
    ReferenceOptions options;
    options.mode = mode;
    options.samplesPerPixel = samples;
    options.model = model;
    options.threads = 1;   // as slow as it gets: the trace must not be over before the checks
    return options;
}

// Polls once per frame drawn, as the window does, until the measurement is no longer running;
// returns the frames drawn meanwhile.
int drawUntilDone(App& app, AsyncMeasurement& measurement, const std::string& technique, AsyncMeasurement::Status& status) {
    int frames = 0;
    std::string error;
    const auto deadline = Clock::now() + std::chrono::seconds(120);
    while ((status = measurement.poll()) == AsyncMeasurement::Status::Running && Clock::now() < deadline) {
        EXPECT_TRUE(app.renderFrame(technique, error)) << error;
        ++frames;
    }
    return frames;
}

// Draws frames until the worker is tracing (progress above 0) or the time runs out.
bool drawUntilTracing(App& app, AsyncMeasurement& measurement, const std::string& technique) {
    std::string error;
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (Clock::now() < deadline) {
        if (measurement.poll() != AsyncMeasurement::Status::Running) return false;
        if (measurement.progress() > 0.0f) return true;
        EXPECT_TRUE(app.renderFrame(technique, error)) << error;
    }
    return false;
}

void expectSameMeasurement(const SideMeasurement& async, const SideMeasurement& sync) {
    EXPECT_EQ(async.label, sync.label);
    EXPECT_EQ(async.metrics.mae, sync.metrics.mae);
    EXPECT_EQ(async.metrics.rmse, sync.metrics.rmse);
    EXPECT_EQ(async.metrics.comparedPixels, sync.metrics.comparedPixels);
    EXPECT_EQ(async.metrics.maePenumbra, sync.metrics.maePenumbra);
    EXPECT_EQ(async.translucentLayers, sync.translucentLayers);
    EXPECT_EQ(async.translucentMetrics.mae, sync.translucentMetrics.mae);
    EXPECT_EQ(async.translucentMetrics.comparedPixels, sync.translucentMetrics.comparedPixels);
    EXPECT_TRUE(async.key == sync.key);
    ASSERT_EQ(async.heatmap.width, sync.heatmap.width);
    ASSERT_EQ(async.heatmap.height, sync.heatmap.height);
    EXPECT_TRUE(async.heatmap.pixels == sync.heatmap.pixels) << "the heatmaps differ";
}

// The worker's figures and heatmap against measureSide's (the old synchronous path), the
// reference traced again for it (no cache): the captured G-buffer, layers and lit view are the
// frame's, byte for byte.
void checkAgainstSynchronous(const std::string& scene, const std::string& technique, const ReferenceOptions& options,
                             size_t expectedLayers) {
    auto app = test::makeHeadlessApp(scene, {320, 180});
    ASSERT_TRUE(app);
    std::string error;
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(app->renderFrame(technique, error)) << error;
    AsyncMeasurement measurement(*app);
    ASSERT_TRUE(measurement.start({{technique, options, 1.5}}, error)) << error;
    EXPECT_TRUE(measurement.running());
    AsyncMeasurement::Status status;
    const int frames = drawUntilDone(*app, measurement, technique, status);
    ASSERT_EQ(status, AsyncMeasurement::Status::Done);
    EXPECT_GT(frames, 0) << "start() or poll() waited for the trace";
    const std::vector<SideMeasurement> async = measurement.take(error);
    ASSERT_EQ(async.size(), 1u) << error;
    EXPECT_FALSE(measurement.running());
    EXPECT_EQ(async[0].gpuMs, 1.5);
    EXPECT_EQ(async[0].translucentLayers, expectedLayers);
    EXPECT_GT(async[0].metrics.comparedPixels, 1000u);

    app->referenceCache().enabled = false;
    SideMeasurement sync;
    ASSERT_TRUE(measureSide(*app, technique, options, sync, error)) << error;
    expectSameMeasurement(async[0], sync);
}

TEST(AsyncMeasurement, GivesTheSynchronousFiguresAndHeatmap) {
    checkAgainstSynchronous("contact", "pcss", referenceOptions(ReferenceOptions::Mode::Soft, 16), 0);
}

TEST(AsyncMeasurement, ReadsTheTranslucentLayersToo) {
    // Two panes over the ground: both layers peeled, read later and compared (seed 001 sec. 5.3.3).
    checkAgainstSynchronous("layered-quads", "translucent-shadows", referenceOptions(ReferenceOptions::Mode::Hard, 1), 2);
}

TEST(AsyncMeasurement, BothSidesOfAComparison) {
    auto app = test::makeHeadlessApp("contact", {320, 180});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    AsyncMeasurement measurement(*app);
    const ReferenceOptions hard = referenceOptions(ReferenceOptions::Mode::Hard, 1);
    ASSERT_TRUE(measurement.start({{"none", hard, 0.0}, {"shadowmap", hard, 0.0}}, error)) << error;
    EXPECT_EQ(measurement.techniques(), (std::vector<std::string>{"none", "shadowmap"}));
    AsyncMeasurement::Status status;
    drawUntilDone(*app, measurement, "shadowmap", status);
    ASSERT_EQ(status, AsyncMeasurement::Status::Done);
    const std::vector<SideMeasurement> sides = measurement.take(error);
    ASSERT_EQ(sides.size(), 2u) << error;
    EXPECT_EQ(sides[0].technique, "none");
    EXPECT_EQ(sides[1].technique, "shadowmap");
    // No shadows at all is far off where shadow mapping is close: each side is its own technique's.
    EXPECT_GT(sides[0].metrics.mae, 5.0 * sides[1].metrics.mae);
}

// Cancelled mid-trace: cancel() returns at once (the module takes no new row), nothing runs, and
// the incomplete image is not cached: measuring the same frame again misses the cache.
TEST(AsyncMeasurement, CancelStopsTheTraceAndCachesNothing) {
    auto app = test::makeHeadlessApp("contact", {640, 360});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("pcss", error)) << error;
    // 1024 rays a pixel on one thread: tens of seconds uncancelled.
    const ReferenceOptions slow = referenceOptions(ReferenceOptions::Mode::Soft, 1024);
    AsyncMeasurement measurement(*app);
    for (int attempt = 0; attempt < 2; ++attempt) {
        const uint64_t hits = app->referenceCache().hits, misses = app->referenceCache().misses;
        ASSERT_TRUE(measurement.start({{"pcss", slow, 0.0}}, error)) << error;
        ASSERT_TRUE(drawUntilTracing(*app, measurement, "pcss"));
        const float progress = measurement.progress();
        EXPECT_LT(progress, 0.5f);
        const auto before = Clock::now();
        measurement.cancel();
        EXPECT_LT(std::chrono::duration<double>(Clock::now() - before).count(), 2.0);
        EXPECT_FALSE(measurement.running());
        EXPECT_EQ(measurement.poll(), AsyncMeasurement::Status::Idle);
        EXPECT_EQ(app->referenceCache().hits, hits) << "attempt " << attempt << ": a cancelled trace was cached";
        EXPECT_EQ(app->referenceCache().misses, misses + 1);
        ASSERT_TRUE(app->renderFrame("pcss", error)) << error;   // same camera: the same G-buffer again
    }
}

// Destroyed while the worker traces (the window quitting): joined, no crash; then, as after a
// cancel for a scene change, a new scene is loaded and measured.
TEST(AsyncMeasurement, DestroyedMidTraceThenAnotherScene) {
    auto app = test::makeHeadlessApp("contact", {640, 360});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("pcss", error)) << error;
    std::optional<AsyncMeasurement> first(std::in_place, *app);
    ASSERT_TRUE(first->start({{"pcss", referenceOptions(ReferenceOptions::Mode::Soft, 1024), 0.0}}, error)) << error;
    ASSERT_TRUE(drawUntilTracing(*app, *first, "pcss"));
    const auto before = Clock::now();
    first.reset();
    EXPECT_LT(std::chrono::duration<double>(Clock::now() - before).count(), 2.0);
    ASSERT_TRUE(app->loadScene("cube", {}, error)) << error;
    ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
    AsyncMeasurement measurement(*app);
    ASSERT_TRUE(measurement.start({{"shadowmap", referenceOptions(ReferenceOptions::Mode::Hard, 1), 0.0}}, error)) << error;
    AsyncMeasurement::Status status;
    drawUntilDone(*app, measurement, "shadowmap", status);
    ASSERT_EQ(status, AsyncMeasurement::Status::Done);
    const std::vector<SideMeasurement> sides = measurement.take(error);
    ASSERT_EQ(sides.size(), 1u) << error;
    EXPECT_EQ(sides[0].key.scene, "cube");
    EXPECT_GT(sides[0].metrics.comparedPixels, 1000u);
}

} // namespace
} // namespace shadowlab
