// The classroom window's frame loop (App::runInteractive): the panel beside the view, one or two
// techniques in the view (side by side, wipe or difference), and the commands the panel emits
// (measure, screenshot, load scene, tour steps, sessions), run between frames. It draws into a GLFW window, or with a
// headless backend into an offscreen framebuffer of the same layout, so slides come out the
// same without a display.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app.h"
#include "ui/classroom.h"
#include "ui/tour.h"

namespace shadowlab {

struct InteractiveOptions {
    std::string technique;
    std::string compareTechnique;                  // non-empty: compare `technique` (A) with it (B)
    std::vector<std::string> gridTechniques;       // the grid's C and D (compareLayout Grid)
    CompareLayout compareLayout = CompareLayout::SideBySide;
    float wipe = 0.5f;                             // Wipe: divider across the view, 0..1
    int frames = 0;                                // > 0: draw that many, save `screenshot`, return
    std::string screenshot;                        // with frames
    std::vector<std::pair<int, std::string>> screenshotsAt;   // with frames: also (frame from 0, file), a path's strip
    bool cycle = false;                            // smoke test: every technique and view in turn
    bool measure = false;                          // measure accuracy after a few frames (slides of the heatmap)
    int referenceMode = 0;                         // the panel's reference at the start: 0 own, 1 hard, 2 soft (UiState)
    int referenceSamples = 64;                     // its rays per pixel
    bool showUi = true;                            // false: the view (and comparison labels) only
    bool presenter = false;                        // presenter mode at the start (full screen, caption large)
    ViewSelection view;                            // the image shown at the start (lit, visibility, ...)
    std::optional<glm::ivec2> probe;               // the kernel view's pixel at the start (main-target pixels)
    float uiScale = 1.0f;
    std::filesystem::path screenshotFolder = "screenshots";   // F12
    std::filesystem::path exportFile;              // --export: every frame of the run into this .gif/.mp4/.webm
    std::filesystem::path exportFolder = "exports";          // the panel's "Export path"
    std::string playPath;                          // a path played from the start, as the panel's "Paths" plays one
    float pathSpeed = 1.0f;                        // path frames per window frame
    // A guided tour, started at `tourStep` (from 0), and/or a session file applied at the start
    // (both checked whole before: tour.h). The session folder is where "Save session" writes.
    std::shared_ptr<const Tour> tour;
    int tourStep = 0;
    std::string session;
    std::filesystem::path sessionFolder = "sessions";
};

// One side of the view measured against the reference, for its own technique.
struct SideMeasurement {
    std::string technique;      // id
    std::string label;          // id and parameter values
    double gpuMs = 0.0;         // the side's last GPU frame time
    size_t gpuBytes = 0;        // the side's technique memory
    AccuracyMetrics metrics;
    AccuracyMetrics translucentMetrics;   // the translucent receivers' layers (comparedPixels 0: none)
    size_t translucentLayers = 0;
    double traceSeconds = 0.0;
    Image heatmap;              // heatmapOverLit of this side's frame
    MeasurementKey key;         // what it was measured for (stale when the frame no longer matches)
};

// What a measurement of `technique` at the current render size and camera depends on.
MeasurementKey currentMeasurementKey(App& app, const std::string& technique);

// The side's technique, label (id and parameter values), memory and key as they are now.
bool describeSide(App& app, const std::string& technique, SideMeasurement& out, std::string& error);
// The figures and the heatmap (over `lit`, the side's lit view) of an evaluation of the side.
void fillSideFigures(const Evaluation& evaluation, const Image& lit, SideMeasurement& out);

// Renders one frame of `technique` (at the renderer's current size, with the accuracy targets),
// traces the reference for that frame and fills `out` (gpuMs is the caller's: timings are read
// a few frames late), all at once. The window does this with the GPU reference device (its
// tracer draws with GL); with Embree it measures without stopping (ui/async_measurement.h).
bool measureSide(App& app, const std::string& technique, const ReferenceOptions& options, SideMeasurement& out,
                 std::string& error);

} // namespace shadowlab
