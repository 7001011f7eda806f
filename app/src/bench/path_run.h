// Running a technique along a camera and light path (scene/camera_path.h): every frame timed
// (`bench --path`), written out (`render --path`), or measured against the reference with the
// temporal metrics (groundtruth/temporal_metrics.h; `stress`). docs/stability.md.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app.h"
#include "app_paths.h"
#include "groundtruth/temporal_metrics.h"
#include "scene/camera_path.h"

namespace shadowlab {

struct PathTiming {
    std::vector<double> frameMs;     // GPU time of each frame of the path, in order
    std::vector<double> cpuMs;       // host CPU time of each
    double p5 = 0, p50 = 0, p95 = 0, max = 0;
    int maxFrame = -1;               // where the hitch is
};

// Warm-up frames at the path's first frame, then every frame of the path timed.
bool timePath(App& app, const std::string& technique, const CameraPath& path, const SceneCamera& camera,
              const LightInfo& light, int warmupFrames, PathTiming& out, std::string& error);

// One measured frame of a path.
struct PathFrameResult {
    int frame = 0;
    AccuracyMetrics metrics;                 // against the reference, over the region
    TemporalFrameMetrics temporal;           // against the previous frame (frame 0: none)
};

struct PathAccuracyOptions {
    ReferenceOptions reference;
    int warmupFrames = 2;
    // Pixels counted (world-space region of a stress case); empty function: every compared pixel.
    std::function<std::vector<uint8_t>(const Evaluation&)> region;
    // Called after each frame with its evaluation and, from frame 1, the changes against the previous.
    std::function<void(const PathFrameResult&, const Evaluation&, const TemporalChanges*)> onFrame;
};

struct PathAccuracy {
    std::vector<PathFrameResult> frames;
    TemporalSummary temporal;
};

// Every frame of the path rendered, evaluated against the reference traced from its own G-buffer,
// and compared with the frame before (temporal_metrics.h).
bool measurePath(App& app, const std::string& technique, const CameraPath& path, const SceneCamera& camera,
                 const LightInfo& light, const PathAccuracyOptions& options, PathAccuracy& out, std::string& error);

// The spatial metrics over the pixels of `region` only (mask AND region), with the view-depth
// thirds of the visible depth range (nearest to farthest compared pixel).
AccuracyMetrics regionMetrics(const Evaluation& evaluation, const std::vector<uint8_t>& region, const CameraInfo& camera);

// `bench --path`: each technique timed along the path on each scene (one row each: p5, p50, p95 and
// max of the frame time, the slowest frame, every frame's time; with `accuracy` the temporal
// metrics too). Returns the exit code (0, 1 machine, 2 bad input) with `error` set.
struct PathBenchOptions {
    std::vector<std::string> techniques, scenes;
    std::vector<std::string> sets;
    std::string path;
    int frames = 0;                  // 0: the path's own
    int warmupFrames = 20;
    bool accuracy = false;
    ReferenceOptions::Mode reference = ReferenceOptions::Mode::Hard;
};
int benchPath(App& app, const PathBenchOptions& options, std::vector<nlohmann::json>& rows,
              const std::function<void(const nlohmann::json&)>& onRow, std::string& error);

// `render --path`: every frame of the path as a numbered PNG in `outDir` (frame_00000.png, ...),
// and frames.mp4 when ffmpeg is on PATH. Returns the exit code with `error` set.
// `video` false: the frames only (`render --export` encodes them itself).
int renderPath(App& app, const std::string& technique, const std::string& pathText, int frames, const std::string& view,
               const std::filesystem::path& outDir, std::string& error, bool video = true);

} // namespace shadowlab
