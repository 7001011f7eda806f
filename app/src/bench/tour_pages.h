// `shadowlab tour TOUR --out DIR`: every step of a tour drawn headless through the window's own
// path (App::runInteractive with the step applied by the same UiCommand the tour player uses,
// the panel hidden), each step's techniques timed by a short benchmark and measured against the
// ray-traced reference, written as DIR/index.html (images and captions, no script) and
// DIR/README.md (the same as Markdown).
#pragma once

#include <filesystem>
#include <string>

#include <glm/glm.hpp>

#include "app.h"
#include "ui/tour.h"

namespace shadowlab {

struct TourPageOptions {
    std::filesystem::path outDir;
    glm::ivec2 size{1280, 720};   // the App's --size: the slides' and the benchmark's
    int frames = 3;               // frames drawn before a step's slide is saved
    int warmupFrames = 5;
    int benchFrames = 30;         // timed frames of each technique of a step
    int referenceSamples = 256;   // soft reference rays per pixel (adaptive)
    int pathMeasureFrames = 8;    // a path step: its first frames measured for the temporal error (0: none)
};

// `shadowlab tour`'s exit code when every page was written but an expectation of a step failed.
constexpr int kExitTourExpectation = 3;

// Returns the exit code: 0, 1 (the machine: a write, GL), 2 (the tour: a view no technique has),
// 3 (kExitTourExpectation: a step's "expect" failed; the pages are written with it marked).
int writeTourPages(App& app, const Tour& tour, const TourPageOptions& options, std::string& error);

// For the HTML page: & < > " escaped.
std::string htmlEscape(const std::string& text);

} // namespace shadowlab
