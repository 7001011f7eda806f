// The main job, when no subcommand is given: the classroom window with a display (or drawn
// offscreen with --frames / --smoke-test), else the report of every technique.
#include "cli/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/report.h"
#include "bench/stress.h"
#include "groundtruth/reference_technique.h"
#include "render/render_limits.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "bench/tour_pages.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab::cli {
namespace {

// --tour and --session, read and checked whole before the first frame (exit 2 naming the file,
// the step and the problem).
int checkLessonOptions(const WindowOptions& w, std::shared_ptr<const Tour>& tour) {
    if (w.tour.empty() && w.session.empty()) return 0;
    const std::vector<TechniqueInfo> techniques = describedTechniques();
    std::string error;
    if (!w.tour.empty()) {
        auto loaded = std::make_shared<Tour>();
        if (!loadTour(w.tour, techniques, *loaded, error)) return fail("--tour: " + error, kExitBadInput);
        if (w.tourStep < 1 || w.tourStep > int(loaded->steps.size()))
            return fail("--tour-step " + std::to_string(w.tourStep) + ": " + loaded->source + " has steps 1 to " +
                            std::to_string(loaded->steps.size()),
                        kExitBadInput);
        tour = std::move(loaded);
    }
    if (!w.session.empty()) {
        TourStep step;
        if (!loadSession(w.session, techniques, step, error)) return fail("--session: " + error, kExitBadInput);
    }
    return 0;
}

} // namespace

void MainJob::declare(CLI::App& cli) {
    // Window options: without a display, --frames (or --smoke-test) draws the same window offscreen.
    auto windowOption = [&](CLI::Option* option) { return option->group("Window"); };
    windowOption(cli.add_option("--smoke-test", window_.smokeFrames, "window: draw N frames cycling every technique, then exit"))
        ->check(CLI::Range(1, 1000000));
    windowOption(cli.add_option("--compare", window_.compare,
                                "window: compare this technique (B) with --technique (A); B,C[,D]: a grid of three or four"));
    // Options that mean something only with another are refused alone (CLI11's needs: exit 2).
    CLI::Option* compare = cli.get_option("--compare");
    windowOption(cli.add_option("--compare-layout", window_.compareLayout, "side-by-side (default) | wipe | difference | grid (three or four techniques)"))
        ->needs(compare);
    windowOption(cli.add_option("--wipe", window_.wipe, "wipe divider position across the view, 0..1 (default 0.5)"))
        ->check(CLI::Range(0.0, 1.0))
        ->needs(compare);
    windowOption(cli.add_option("--frames", window_.frames,
                                "window: draw N frames, save --screenshot, exit (slides; offscreen without a display)"))
        ->check(CLI::Range(1, 1000000));
    windowOption(cli.add_option("--screenshot", window_.screenshot, "window: save a screenshot at the end of --smoke-test or --frames"));
    windowOption(cli.add_option("--ui-scale", window_.uiScale, "window: size of the panel's text and widgets (1.5-2 for a projector)"))
        ->check(CLI::Range(0.5, 4.0));
    windowOption(cli.add_flag("--hide-ui", window_.hideUi, "window: start with the panel hidden (F1 or H toggles it)"));
    windowOption(cli.add_option("--export", window_.exportFile,
                                "window: with --frames N, the N frames drawn (the view, without the panel) as FILE.gif, "
                                ".mp4 or .webm, e.g. a tour step's path (needs the ffmpeg program)"));
    windowOption(cli.add_option("--play-path", window_.playPath,
                                "window: play a camera or light path from the start, as the panel's \"Camera and light "
                                "paths\" does: built-in (orbit, dolly, sweep, walk, static) or a path file"));
    windowOption(cli.add_option("--path-speed", window_.pathSpeed, "window: path frames per window frame (0.1-4, default 1)"))
        ->check(CLI::Range(0.1, 4.0));
    windowOption(cli.add_flag("--presenter", window_.presenter,
                              "window: presenter mode (P toggles it): full screen, the panel hidden, the tour step's "
                              "caption large on the view with its figures beside it; ? lists every key"));
    windowOption(cli.add_option("--probe", window_.probe,
                                "window: X,Y, the pixel of the view (from its top left) the kernel view probes until the "
                                "mouse moves over the view (offscreen slides keep it)"));
    windowOption(cli.add_flag("--measure", window_.measure,
                              "window: measure accuracy after a few frames, each side of a comparison for its own "
                              "technique, and show the heatmap (with --frames: a slide of it)"));
    windowOption(cli.add_option("--measure-reference", window_.measureReference,
                                "window: the reference \"Measure accuracy\" traces: auto (default: hard for hard techniques, soft for "
                                "filtered and soft ones, as the tour pages) | hard | soft"));
    windowOption(cli.add_option("--measure-samples", window_.measureSamples,
                                "window: rays per pixel of the soft reference (4-256, default 64)"))
        ->check(CLI::Range(4, 256));
    windowOption(cli.add_option("--screenshot-dir", window_.screenshotDir, "window: folder of F12 screenshots (default screenshots)"));
    windowOption(cli.add_option("--tour", window_.tour,
                                "window: play a guided tour, a built-in name (assets/tours) or a tour file; with --frames "
                                "a slide of one step"));
    windowOption(cli.add_option("--tour-step", window_.tourStep, "window: the tour's step to start at (from 1)"))
        ->check(CLI::Range(1, int(kMaxTourSteps)))
        ->needs(cli.get_option("--tour"));
    windowOption(cli.add_option("--session", window_.session, "window: restore a saved session (a JSON tour step) at the start"));
    windowOption(cli.add_option("--session-dir", window_.sessionDir, "window: folder of saved sessions (default sessions)"));
    cli.add_option("--out-dir", outDir_, "headless main job: folder of the report (default out)");
}

int MainJob::run(const CommonOptions& common, const CLI::App& cli) {
    // The main job: the window. Without a display, --frames or --smoke-test draws it offscreen (a
    // slide from a machine without a screen); with neither, the report, unless a window option
    // says the window was meant.
    std::vector<std::string> windowFlags;
    for (const CLI::Option* option : cli.get_options())
        if (option->get_group() == "Window" && option->count() > 0) windowFlags.push_back(option->get_name());
    if (!window_.screenshot.empty() && window_.frames == 0 && window_.smokeFrames == 0)
        return fail("--screenshot " + window_.screenshot + ": needs --frames N (or --smoke-test N) to say when to take it",
                    kExitBadInput);
    if (window_.frames > 0 && window_.smokeFrames > 0) return fail("--frames and --smoke-test: give one of them", kExitBadInput);
    if (cli.get_option("--wipe")->count() > 0 && window_.compareLayout != "wipe")
        return fail("--wipe: places the divider of --compare-layout wipe", kExitBadInput);
    std::shared_ptr<const Tour> tour;
    if (int code = checkLessonOptions(window_, tour)) return code;
    const bool display = common.backend.empty() ? defaultBackend() == BackendKind::Glfw : common.backend == "glfw";
    const bool drawnFrames = window_.frames > 0 || window_.smokeFrames > 0;
    if (!display && !drawnFrames) {
        if (!windowFlags.empty())
            return fail(windowFlags.front() + ": no display to open the window on; add --frames N --screenshot FILE to "
                        "draw it offscreen, or use `shadowlab render --compare A,B`",
                        kExitBadInput);
        if (!common.technique.empty() || !common.sets.empty())
            logWarning(std::string(common.technique.empty() ? "--set" : "--technique") +
                       ": no display, so the main job is the report of every technique; add --frames N --screenshot "
                       "FILE to draw the window offscreen instead");
        return runReport(common, "", outDir_, "--out-dir");
    }
    if (cli.get_option("--out-dir")->count() > 0)
        return fail("--out-dir: the folder of the headless report, which this run does not write (the window is "
                    "drawn; --screenshot names its image)",
                    kExitBadInput);
    std::string error;
    if (!window_.screenshot.empty() && !outputProblem("--screenshot", window_.screenshot, false, error))
        return fail(error, kExitBadInput);
    if (int code = techniqueOptionsProblem(common.technique, common.sets)) return code;
    App app;
    if (int code = startApp(app, common, display)) return code;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    if (!app.techniques().find(technique)) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    InteractiveOptions options;
    if (int code = windowOptionsProblem(app, window_, technique, options)) return code;
    options.tour = tour;
    options.tourStep = window_.tourStep - 1;
    if (!display) logInfo("no display: drawing the window offscreen (" + std::string(backendName(app.backend().kind())) + ")");
    return app.runInteractive(options);
}

} // namespace shadowlab::cli
