// The classroom window's frame loop (App::runInteractive; options in ui/session.h). A frame, top
// to bottom (WindowSession::frame):
//   input -> the smoke test's and the path's changes -> the surface and the layout (panel beside
//   the view, halves of a comparison) -> for each side: its technique's frame at the side's size,
//   presented into the display texture and composed into its rectangle (render/view_compositor.h)
//   -> the panel and the labels (ImGui, ui/ui.h) -> the commands the panel queued (screenshot,
//   measure, load scene, tour step, load tour, save or load session), each its own function ->
//   swap.
// --tour and --session are the same commands, run once before the first frame.
// "Measure accuracy" captures its frames at the click and traces on a worker
// (ui/async_measurement.h); every frame polls it first, and the result arrives frames later. A
// run of --frames N holds its script still (frame index, smoke test, path, screenshots) while a
// measurement runs, so its slides show the measured frame as before; frames go on being drawn.
#include "app.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include <GLFW/glfw3.h>

#include "app_paths.h"
#include "bench/accuracy_columns.h"
#include "render/view_compositor.h"
#include "ui/async_measurement.h"
#include "ui/keys.h"
#include "ui/session.h"
#include "ui/tour_player.h"
#include "ui/ui.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/progress.h"
#include "util/scratch_dir.h"
#include "util/text_file.h"
#include "util/video_export.h"

namespace shadowlab {

class WindowSession {
public:
    WindowSession(App& app, const InteractiveOptions& options)
        : app_(app), options_(options), window_(app.backend().window()), compositor_(app.shaders()) {}

    int run() {
        if (int code = start()) return code;
        while (!app_.backend().shouldClose()) {
            if (!frame()) break;
            if (options_.frames > 0 && frameIndex_ >= options_.frames) break;
            if (state_.quitRequested) break;
            if (interrupted()) {   // Ctrl-C in the terminal closes the window (util/progress.h)
                exitCode_ = kExitInterrupted;
                break;
            }
        }
        if (recording() && exitCode_ == 0) finishRecording();   // --export: the frames of the run
        cancelMeasurement("the window closed");   // the worker is joined before anything it reads goes
        app_.camera().setFramingAspect(0.0f);
        ui_.shutdown();
        return exitCode_;
    }

private:
    // Checks, the UI, the state from the options, then --tour and --session.
    int start() {
        if (!window_ && options_.frames <= 0) {
            logError("the offscreen window needs a number of frames to draw (--frames N)");
            return 2;
        }
        // --tour: every step's debug view checked before anything is drawn (a view would otherwise
        // only be found missing when its step comes up in class).
        if (std::string error; options_.tour && !checkTourDebugViews(app_, *options_.tour, error)) {
            logError(error);
            return 2;
        }
        if (!ui_.init(window_, options_.uiScale)) {
            logError("could not initialise the user interface");
            return 1;
        }
        state_.technique = options_.technique.empty() ? app_.firstTechnique() : options_.technique;
        state_.compareTechnique = options_.compareTechnique;
        state_.gridTechniques = options_.gridTechniques;
        state_.compareLayout = options_.compareLayout;
        state_.wipe = options_.wipe;
        state_.showUi = options_.showUi;
        if (options_.presenter) setPresenter(state_, true);
        state_.view = options_.view;
        if (options_.probe) app_.setProbePixel(options_.probe);
        state_.uiScale = options_.uiScale;
        state_.referenceMode = options_.referenceMode;
        state_.referenceSamples = options_.referenceSamples;
        state_.msaaSamples = app_.renderer().msaaSamples();
        app_.camera().setFramingAspect(kSceneFramingAspect);
        last_ = std::chrono::steady_clock::now();
        if (window_) glfwGetCursorPos(window_, &lastMouse_.x, &lastMouse_.y);
        if (options_.tour) {
            state_.tour = options_.tour;
            runCommand({UiCommand::Kind::TourStep, std::to_string(options_.tourStep)});
        }
        if (!options_.session.empty()) runCommand({UiCommand::Kind::LoadSession, options_.session});
        if (!options_.session.empty() && state_.sessionStatusIsError) return 2;   // refused before the first frame, as --tour
        state_.pathSpeed = options_.pathSpeed;
        if (!options_.playPath.empty()) {
            runCommand({UiCommand::Kind::PlayPath, options_.playPath});
            if (!state_.path) return 2;   // named in the log by playPath
        }
        if (!options_.exportFile.empty() && !startRecording(options_.exportFile, 0)) return 1;
        return 0;
    }

    // One frame; false when the window cannot go on (its offscreen surface failed).
    bool frame() {
        app_.backend().pollEvents();
        const auto now = std::chrono::steady_clock::now();
        const float seconds = std::chrono::duration<float>(now - last_).count();
        last_ = now;
        if (measurement_.running()) longestFrameGap_ = std::max(longestFrameGap_, seconds);
        pollMeasurement();
        const bool held = options_.frames > 0 && measurement_.running();
        handleInput(seconds);
        if (!held) {
            driveSmokeTest();
            advancePath();
            queueTimedMeasurement();
        }
        followPresenter();
        if (!prepareSurface()) return false;
        const bool comparing = !state_.compareTechnique.empty();
        state_.layout = computeViewLayout(surfaceSize_, state_.showUi, panelWidthFor(state_.uiScale, surfaceSize_.x), comparing,
                                          state_.compareLayout, state_.wipe);
        if (surfaceSize_.x > 0 && surfaceSize_.y > 0) {
            renderSides(comparing);
            markStaleMeasurement();
        }
        ui_.draw(app_, state_, seconds, surface_, surfaceSize_);
        if (!held) recordFrame();
        runQueuedCommands(held);
        app_.backend().swapBuffers();
        ++presentedFrames_;
        if (!held) ++frameIndex_;
        return true;
    }

    // Camera input, unless the UI has the mouse or keyboard or the wipe divider is dragged.
    void handleInput(float seconds) {
        if (!window_) return;
        CameraController& camera = app_.camera();
        glm::dvec2 mouse;
        glfwGetCursorPos(window_, &mouse.x, &mouse.y);
        const glm::vec2 delta = glm::vec2(mouse - lastMouse_);
        lastMouse_ = mouse;
        // A press on the wipe's handle starts its drag before the camera sees the motion (the
        // overlay, drawn later in the frame, would start it a frame late and the camera orbit).
        if (!ui_.wantsMouse())
            for (const glm::vec2 press : state_.leftPresses)
                if (ui_.onWipeHandle(state_, press)) state_.draggingWipe = true;
        if (!ui_.wantsMouse() && !state_.draggingWipe) {
            if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) camera.look(delta);
            if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) camera.pan(delta);
            if (state_.scroll != 0.0f) camera.zoom(state_.scroll);
        }
        state_.scroll = 0.0f;
        if (!ui_.wantsKeyboard() && camera.mode() == CameraController::Mode::Fly) {
            glm::vec3 move(0.0f);
            // The held keys of the table (ui/keys.h), which the help overlay lists.
            auto pressed = [&](KeyAction action) {
                for (const int key : keysFor(action))
                    if (glfwGetKey(window_, key) == GLFW_PRESS) return 1.0f;
                return 0.0f;
            };
            move.z = pressed(KeyAction::FlyForward) - pressed(KeyAction::FlyBack);
            move.x = pressed(KeyAction::FlyRight) - pressed(KeyAction::FlyLeft);
            move.y = pressed(KeyAction::FlyUp) - pressed(KeyAction::FlyDown);
            camera.fly(move, seconds);
        }
    }

    // --smoke-test: every technique and view in turn while drawing the UI, the comparison for a
    // while in each layout, and once a measurement of both sides.
    void driveSmokeTest() {
        const int smokeFrames = options_.cycle ? options_.frames : 0;
        const auto& all = app_.techniques().techniques();
        if (smokeFrames <= 0 || all.empty()) return;
        const int perTechnique = std::max(1, smokeFrames / int(all.size()));
        state_.technique = all[size_t(std::min(frameIndex_ / perTechnique, int(all.size()) - 1))].id;
        if (state_.view.kind != ViewSelection::Kind::ErrorHeatmap || frameIndex_ > smokeFrames / 2 + 5)
            state_.view.kind = (frameIndex_ / 7) % 2 ? ViewSelection::Kind::Visibility : ViewSelection::Kind::Lit;
        state_.compareTechnique = (frameIndex_ % 50) >= 35 ? app_.firstTechnique() : std::string();
        state_.compareLayout = CompareLayout((frameIndex_ / 50) % 3);
        if (frameIndex_ == smokeFrames / 2) {
            state_.compareTechnique = app_.firstTechnique();
            state_.compareLayout = CompareLayout::SideBySide;
            state_.commands.push_back({UiCommand::Kind::Measure, ""});
        }
    }

    // The step's path: one path frame per window frame, looping (camera and light set before the
    // frame is drawn, so frame k of a step shows path frame k).
    void advancePath() {
        if (!state_.path || !state_.pathPlaying || state_.path->frames <= 0) return;
        state_.pathClock = std::fmod(std::max(state_.pathClock, 0.0f), float(state_.path->frames));
        state_.pathFrame = std::min(int(state_.pathClock), state_.path->frames - 1);
        setPathFrame(app_, *state_.path, state_.pathFrame, state_.pathCamera, state_.pathLight);
    }

    // --measure: late enough for the GPU timings (read kFramesInFlight frames late), early enough
    // that the last frames show the heatmap.
    void queueTimedMeasurement() {
        const int at = options_.frames > 0 ? std::max(1, std::min(options_.frames - 2, GpuTimer::kFramesInFlight + 2))
                                           : GpuTimer::kFramesInFlight + 2;
        if (options_.measure && frameIndex_ == at) state_.commands.push_back({UiCommand::Kind::Measure, ""});
    }

    // Presenter mode takes the whole screen and gives the window back when it ends (offscreen:
    // the surface keeps --size).
    void followPresenter() {
        if (!window_ || state_.presenter == fullscreen_) return;
        fullscreen_ = state_.presenter;
        GLFWmonitor* monitor = glfwGetPrimaryMonitor();
        const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
        if (fullscreen_ && mode) {
            glfwGetWindowPos(window_, &windowedRect_.x, &windowedRect_.y);
            glfwGetWindowSize(window_, &windowedRect_.z, &windowedRect_.w);
            glfwSetWindowMonitor(window_, monitor, 0, 0, mode->width, mode->height, mode->refreshRate);
            logInfo("presenter mode: full screen at " + std::to_string(mode->width) + "x" + std::to_string(mode->height));
        } else if (fullscreen_) {
            glfwMaximizeWindow(window_);   // no monitor to take: as large as the desktop allows
            logInfo("presenter mode: no monitor reported, the window maximised");
        } else if (windowedRect_.z > 0) {
            glfwSetWindowMonitor(window_, nullptr, windowedRect_.x, windowedRect_.y, windowedRect_.z, windowedRect_.w, 0);
            logInfo("presenter mode ended");
        }
    }

    // The surface: the window's framebuffer, or the offscreen one.
    bool prepareSurface() {
        surfaceSize_ = window_ ? app_.backend().framebufferSize() : app_.options().size;
        if (!window_) {
            std::string error;
            if (!compositor_.prepareOffscreen(surfaceSize_, error)) {
                logError(error);
                exitCode_ = 1;
                return false;
            }
        }
        surface_ = window_ ? 0 : compositor_.offscreenFramebuffer();
        return true;
    }

    // Each side's frame at its size, composed into its rectangle of the surface.
    void renderSides(bool comparing) {
        const ViewLayout& layout = state_.layout;
        Renderer& renderer = app_.renderer();
        std::string error;
        if (!renderer.resize(layout.renderSize, state_.msaaSamples, error)) logError(error);
        glBindFramebuffer(GL_FRAMEBUFFER, surface_);
        glViewport(0, 0, surfaceSize_.x, surfaceSize_.y);
        glDisable(GL_SCISSOR_TEST);
        glClearColor(0.09f, 0.09f, 0.11f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        state_.frameError.clear();
        const std::vector<std::string> sides = shownTechniques(state_);
        const bool difference = comparing && state_.compareLayout == CompareLayout::Difference;
        const FrameOutputs outputs =
            difference || state_.view.needsAccuracyTargets() ? FrameOutputs::Accuracy : FrameOutputs::Colour;
        probeUnderMouse();
        // One camera and scene: both sides share one camera pre-pass (the full one if either needs it).
        if (comparing) app_.beginSharedView(sides);
        for (int s = 0; s < int(sides.size()); ++s) {
            if (!app_.renderFrame(sides[size_t(s)], error, outputs)) {
                state_.frameError = error;
                if (s == 1) state_.compareTechnique.clear();
                if (s > 1) state_.gridTechniques.clear();
                break;
            }
            state_.sideTimings[s] = app_.timer().latest();   // this side's: the sides alternate frame by frame
            if (difference) {
                // A's shadow term is kept while B renders into the same targets; then |A - B|.
                if (s == 0) compositor_.keepFirstTerm(renderer);
                else if (compositor_.drawDifference(renderer))
                    ViewCompositor::blitDisplay(renderer, surface_, surfaceSize_, layout.view.origin, layout.view.size, 0);
                continue;
            }
            presentSide(s, sides[size_t(s)]);
            const PixelRect& rect = layout.cells[s];
            const int sourceX = comparing && state_.compareLayout == CompareLayout::Wipe ? rect.origin.x - layout.view.origin.x : 0;
            ViewCompositor::blitDisplay(renderer, surface_, surfaceSize_, rect.origin, rect.size, sourceX);
        }
        app_.endSharedView();
        for (size_t s = sides.size(); s < size_t(kMaxGridSides); ++s) state_.sideTimings[s].clear();
    }

    // The kernel view probes the pixel under the mouse (over the view, not the panel); without a
    // mouse (offscreen) it keeps --probe's.
    void probeUnderMouse() {
        if (!window_ || state_.view.kind != ViewSelection::Kind::Kernel || ui_.wantsMouse()) return;
        glm::dvec2 mouse;
        glfwGetCursorPos(window_, &mouse.x, &mouse.y);
        const PixelRect& rect = state_.layout.halves[0];
        if (rect.contains(glm::vec2(mouse)) && rect.size.x > 0 && rect.size.y > 0)
            app_.setProbePixel(glm::ivec2((glm::vec2(mouse) - glm::vec2(rect.origin)) * glm::vec2(state_.layout.renderSize) /
                                          glm::vec2(rect.size)));
    }

    // Side `s`'s view (or its error heatmap) into the display texture.
    void presentSide(int s, const std::string& technique) {
        Renderer& renderer = app_.renderer();
        const bool heatmap = state_.view.kind == ViewSelection::Kind::ErrorHeatmap && size_t(s) < state_.measurement.size() &&
                             compositor_.heatmap(s) != 0;
        if (heatmap) {
            renderer.present(PresentMode::Color, compositor_.heatmap(s), renderer.displayFramebuffer(), renderer.size());
            return;
        }
        std::string error;
        const ViewSelection view = state_.view.kind == ViewSelection::Kind::ErrorHeatmap ? ViewSelection{} : state_.view;
        if (!app_.presentView(technique, view, ~0u, {}, error)) {
            // B may lack A's debug image: it shows lit, A says why it could not.
            if (s == 0) {
                state_.view = {};
                state_.frameError = error;
            }
            app_.presentView(technique, {}, ~0u, {}, error);
        }
    }

    // The heatmap and figures say when they no longer describe the view.
    void markStaleMeasurement() {
        const std::vector<std::string> sides = shownTechniques(state_);
        state_.staleReason.clear();
        for (size_t s = 0; s < state_.measurement.size() && s < sides.size() && state_.staleReason.empty(); ++s)
            state_.staleReason = staleReason(state_.measurement[s].key, currentMeasurementKey(app_, sides[s]));
        if (state_.measurement.size() != sides.size() && !state_.measurement.empty())
            state_.staleReason = "the comparison changed";
    }

    // The panel's commands, outside the ImGui frame. The screenshot first: it saves the frame just
    // drawn, panel included. A held frame (a --frames run waiting for its measurement) takes no
    // scripted screenshot and does not advance the path.
    void runQueuedCommands(bool held) {
        const bool finalShot =
            !held && options_.frames > 0 && frameIndex_ + 1 == options_.frames && !options_.screenshot.empty();
        std::vector<UiCommand> commands;
        commands.swap(state_.commands);
        if (finalShot) commands.insert(commands.begin(), UiCommand{UiCommand::Kind::Screenshot, options_.screenshot});
        if (options_.frames > 0 && !held)
            for (const auto& [at, file] : options_.screenshotsAt)
                if (at == frameIndex_ && !(finalShot && file == options_.screenshot))
                    commands.insert(commands.begin(), UiCommand{UiCommand::Kind::Screenshot, file});
        // The path's speed in path frames per window frame (1 in tours); a step applied by a
        // command below starts at 0.
        if (state_.path && state_.pathPlaying && !held) state_.pathClock += state_.pathSpeed;
        for (const UiCommand& command : commands) runCommand(command);
    }

    void runCommand(const UiCommand& command) {
        switch (command.kind) {
        case UiCommand::Kind::Screenshot: return screenshot(command.argument);
        case UiCommand::Kind::Measure: return measure();
        case UiCommand::Kind::CancelMeasure: return cancelMeasurement("Cancel was pressed");
        case UiCommand::Kind::LoadScene: return cancelMeasurement("the scene changed"), loadScene(command.argument);
        case UiCommand::Kind::TourStep: return cancelMeasurement("a tour step was applied"), tourStep(command.argument);
        case UiCommand::Kind::LoadTour: return cancelMeasurement("a tour was loaded"), loadTour(command.argument);
        case UiCommand::Kind::SaveSession: return saveSession(command.argument);
        case UiCommand::Kind::LoadSession: return cancelMeasurement("a session was loaded"), loadSession(command.argument);
        case UiCommand::Kind::PlayPath: return playPath(command.argument);
        case UiCommand::Kind::ExportPath: return exportPath();
        }
    }

    // An error of a command: on the panel, in the log, and, in a run of --frames N (slides, CI),
    // the exit code.
    void failed(std::string& status, bool& isError, const std::string& error, int code) {
        status = error;
        isError = true;
        logError(error);
        if (options_.frames > 0 && code) exitCode_ = code;
    }

    void screenshot(const std::string& argument) {
        std::filesystem::path file = argument;
        if (file.empty()) {
            std::error_code ec;
            std::filesystem::create_directories(options_.screenshotFolder, ec);
            file = uniqueScreenshotPath(options_.screenshotFolder, app_.scene().name, state_.technique, state_.compareTechnique,
                                        std::chrono::system_clock::now());
        }
        std::string error;
        if (writePng(file, ViewCompositor::readSurface(surface_, surfaceSize_), error)) {
            logInfo("screenshot saved: " + file.string());
            state_.lastScreenshot = "saved " + file.string();
        } else {
            bool unused = false;
            failed(state_.lastScreenshot, unused, error, 1);
        }
    }

    // Each side measured against the reference for its own technique; the heatmaps replace the
    // view until it changes. With Embree the frames are captured now and traced on a worker
    // (pollMeasurement takes the result); the GPU tracer draws with GL, so it measures here, at once.
    void measure() {
        state_.measureError.clear();
        const std::vector<std::string> sides = shownTechniques(state_);
        std::vector<AsyncMeasurement::Side> requests;
        for (size_t s = 0; s < sides.size(); ++s) {
            const TechniqueInfo* info = app_.techniques().find(sides[s]);
            AsyncMeasurement::Side side{sides[s], {}, 0.0};
            side.options.mode = state_.referenceMode == 2 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
            if (state_.referenceMode == 0 && info) side.options.mode = ownReferenceMode(*info);   // as the tour pages
            side.options.samplesPerPixel = state_.referenceSamples;
            side.options.model = state_.referenceModel == 1 && info ? info->translucencyModel : TranslucencyModel::Physical;
            // One core stays with the frame loop (the thread count changes no sample).
            side.options.threads = std::max(1, int(std::thread::hardware_concurrency()) - 1);
            const auto frameMs = state_.sideTimings[s].find("frame");
            side.gpuMs = frameMs == state_.sideTimings[s].end() ? 0.0 : frameMs->second;
            requests.push_back(std::move(side));
        }
        if (app_.referenceDevice() == ReferenceDevice::Gpu) return measureNow(requests);
        std::string error;
        const auto captureStart = std::chrono::steady_clock::now();
        if (!measurement_.start(requests, error)) {
            state_.measureError = error;
            logError("measure accuracy: " + error);
            return;
        }
        measureStartFrame_ = presentedFrames_;
        longestFrameGap_ = 0.0f;
        measureStart_ = std::chrono::steady_clock::now();
        state_.measuring = true;
        state_.measureProgress = 0.0f;
        state_.measureStage = measurement_.stage();
        const double captureMs = std::chrono::duration<double, std::milli>(measureStart_ - captureStart).count();
        char text[160];
        std::snprintf(text, sizeof(text), "measuring accuracy on a worker thread from presented frame %ld (frames captured in %.0f ms)",
                      presentedFrames_, captureMs);
        logInfo(text);
    }

    void measureNow(const std::vector<AsyncMeasurement::Side>& requests) {
        cancelMeasurement("a new measurement started");
        std::vector<SideMeasurement> results;
        for (const AsyncMeasurement::Side& side : requests) {
            SideMeasurement result;
            std::string error;
            if (!measureSide(app_, side.technique, side.options, result, error)) {
                state_.measureError = side.technique + ": " + error;
                return;
            }
            result.gpuMs = side.gpuMs;
            results.push_back(std::move(result));
        }
        showMeasurement(std::move(results));
    }

    // Once a frame, before anything is drawn: a measurement of techniques no longer shown is
    // cancelled; a finished one is shown.
    void pollMeasurement() {
        if (measurement_.running()) {
            const std::vector<std::string> measured = measurement_.techniques();
            if (measured != shownTechniques(state_)) cancelMeasurement("the technique changed");
        }
        switch (measurement_.poll()) {
        case AsyncMeasurement::Status::Idle: state_.measuring = false; return;
        case AsyncMeasurement::Status::Running:
            state_.measureProgress = measurement_.progress();
            state_.measureStage = measurement_.stage();
            return;
        case AsyncMeasurement::Status::Done:
        case AsyncMeasurement::Status::Failed: break;
        }
        state_.measuring = false;
        std::string error;
        std::vector<SideMeasurement> results = measurement_.take(error);
        if (!error.empty()) {
            state_.measureError = error;
            logError("measure accuracy: " + error);
            return;
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - measureStart_).count();
        char text[200];
        std::snprintf(text, sizeof(text),
                      "accuracy measured in %.2f s on a worker thread: %ld frames presented meanwhile, at most %.0f ms apart",
                      seconds, presentedFrames_ - measureStartFrame_, 1000.0 * double(longestFrameGap_));
        logInfo(text);
        showMeasurement(std::move(results));
    }

    void showMeasurement(std::vector<SideMeasurement> results) {
        for (size_t s = 0; s < results.size(); ++s) {
            const SideMeasurement& result = results[s];
            state_.measured.push_back({result.label, result.gpuMs, result.metrics.mae});
            char figures[128];
            std::snprintf(figures, sizeof(figures), ": MAE %.6f, %.3f ms GPU, %.2f MiB", result.metrics.mae, result.gpuMs,
                          double(result.gpuBytes) / (1024.0 * 1024.0));
            logInfo("accuracy of " + result.label + figures);
            compositor_.setHeatmap(int(s), result.heatmap);   // uploaded here, on the GL thread
        }
        state_.measurement = std::move(results);
        if (state_.compareLayout != CompareLayout::Difference) state_.view = {ViewSelection::Kind::ErrorHeatmap, ""};
    }

    void cancelMeasurement(const std::string& reason) {
        if (!measurement_.running()) return;
        measurement_.cancel();   // joins the worker
        state_.measuring = false;
        logInfo("measurement cancelled: " + reason);
    }

    void loadScene(const std::string& name) {
        std::string error;
        state_.sceneError = app_.loadScene(name, {}, error) ? "" : error;
        if (state_.sceneError.empty()) state_.path.reset();   // a step's path belongs to its scene
    }

    // "next", "previous", "restart" or a step index from 0.
    void tourStep(const std::string& argument) {
        if (!state_.tour || state_.tour->steps.empty()) return;
        const int last = int(state_.tour->steps.size()) - 1;
        int index = state_.tourStep;
        if (argument == "next") index = std::min(index + 1, last);
        else if (argument == "previous") index = std::max(index - 1, 0);
        else if (argument != "restart") index = std::clamp(std::atoi(argument.c_str()), 0, last);
        const std::string where = state_.tour->source + ": steps[" + std::to_string(index) + "]";
        std::string error;
        if (!applyTourStep(app_, state_.tour->steps[size_t(index)], state_, error))
            return failed(state_.tourStatus, state_.tourStatusIsError, where + ": " + error, 1);
        state_.tourStep = index;
        state_.tourStatus.clear();
        state_.tourStatusIsError = false;
        logInfo("tour step " + std::to_string(index + 1) + " of " + std::to_string(last + 1) + ": " +
                state_.tour->steps[size_t(index)].title);
    }

    // Checked whole before its first step is shown, debug views included.
    void loadTour(const std::string& file) {
        auto tour = std::make_shared<Tour>();
        std::string error;
        if (!shadowlab::loadTour(file, app_.techniques().techniques(), *tour, error) || !checkTourDebugViews(app_, *tour, error))
            return failed(state_.tourStatus, state_.tourStatusIsError, error, 0);
        state_.tour = std::move(tour);
        state_.tourStep = 0;
        tourStep("0");
    }

    // The panel's "Paths" section outside tours: a built-in path or a file, made from the camera
    // and light on screen now, played as a tour step's ("" stops it).
    void playPath(const std::string& name) {
        state_.pathStatus.clear();
        if (name.empty()) {
            state_.path.reset();
            state_.pathName.clear();
            return;
        }
        TourStep step;
        step.technique = state_.technique;
        step.path = name;
        CameraPath path;
        std::string error;
        const SceneCamera camera = app_.camera().pose();
        if (!resolveTourPath(app_, step, camera, app_.light(), path, error)) {
            bool unused = false;
            return failed(state_.pathStatus, unused, "path '" + name + "': " + error, 2);
        }
        state_.pathCamera = camera;
        state_.pathLight = app_.light();
        state_.path = std::move(path);
        // A path file by its absolute name, so a session saved on it loads from any folder.
        std::error_code ec;
        state_.pathName = std::filesystem::is_regular_file(name, ec) ? std::filesystem::absolute(name).lexically_normal().string() : name;
        state_.pathFrames = 0;
        state_.pathFrame = 0;
        state_.pathClock = 0.0f;
        state_.pathPlaying = true;
        logInfo("path " + name + ": " + std::to_string(state_.path->frames) + " frames, playing");
    }

    // Export (--export, or the panel's "Export path"): the view of each frame drawn (the panel
    // cropped off; overlays such as labels and presenter captions kept) written as a numbered
    // PNG, then encoded by ffmpeg (util/video_export.h). Reading the surface back waits for the
    // GPU: it happens only while exporting, as a screenshot does.
    bool recording() const { return !recordOut_.empty(); }

    bool startRecording(const std::filesystem::path& out, int frames) {
        std::string error;
        const std::filesystem::path scratch = scratchDir(error);
        if (scratch.empty()) return logError(error), false;
        recordFolder_ = scratch / ("export-" + std::to_string(++recordings_));
        std::error_code ec;
        std::filesystem::remove_all(recordFolder_, ec);
        std::filesystem::create_directories(recordFolder_, ec);
        if (ec) return logError(recordFolder_.string() + ": " + ec.message()), false;
        recordOut_ = out;
        recordTarget_ = frames;
        recordedFrames_ = 0;
        logInfo("exporting to " + out.string() + (frames > 0 ? " (" + std::to_string(frames) + " frames)" : ""));
        return true;
    }

    void recordFrame() {
        if (!recording() || surfaceSize_.x <= 0) return;
        const Image surface = ViewCompositor::readSurface(surface_, surfaceSize_);
        const PixelRect& view = state_.layout.view;
        Image image{view.size.x, view.size.y, 4, std::vector<uint8_t>(size_t(view.size.x) * size_t(view.size.y) * 4)};
        const int y0 = surfaceSize_.y - (view.origin.y + view.size.y);   // rows are bottom-up
        for (int y = 0; y < view.size.y; ++y)
            std::copy_n(surface.pixels.begin() + ((ptrdiff_t(y0 + y) * surfaceSize_.x + view.origin.x) * 4), size_t(view.size.x) * 4,
                        image.pixels.begin() + ptrdiff_t(y) * view.size.x * 4);
        char name[32];
        std::snprintf(name, sizeof(name), "frame_%05d.png", recordedFrames_);
        std::string error;
        if (!writePng(recordFolder_ / name, image, error)) {
            bool unused = false;
            failed(state_.pathStatus, unused, error, 1);
            recordOut_.clear();
            return;
        }
        if (++recordedFrames_ == recordTarget_) finishRecording();
    }

    void finishRecording() {
        std::string error;
        const std::filesystem::path out = recordOut_;
        recordOut_.clear();
        const bool encoded = encodeFrames(recordFolder_, 30, out, error);
        std::error_code ec;
        std::filesystem::remove_all(recordFolder_, ec);
        if (!encoded) {
            bool unused = false;
            return failed(state_.pathStatus, unused, error, 1);
        }
        state_.pathStatus = "exported " + out.string() + " (" + std::to_string(recordedFrames_) + " frames)";
        logInfo("wrote " + out.string() + " (" + std::to_string(recordedFrames_) + " frames)");
    }

    // The panel's "Export path": one loop of the playing path from its first frame, into
    // exports/<scene>-<technique>-<date>.gif.
    void exportPath() {
        bool unused = false;
        if (!state_.path || state_.path->frames <= 0) return failed(state_.pathStatus, unused, "Export path: no path is playing", 0);
        std::error_code ec;
        std::filesystem::create_directories(options_.exportFolder, ec);
        std::filesystem::path file = uniqueScreenshotPath(options_.exportFolder, app_.scene().name, state_.technique,
                                                          state_.pathName.find('/') == std::string::npos ? state_.pathName : "path",
                                                          std::chrono::system_clock::now());
        file.replace_extension(".gif");
        if (const std::string problem = exportProblem("Export path", file); !problem.empty())
            return failed(state_.pathStatus, unused, problem, 0);
        state_.pathClock = 0.0f;
        state_.pathPlaying = true;
        startRecording(file, std::max(1, int(std::ceil(float(state_.path->frames) / std::max(state_.pathSpeed, 0.01f)))));
    }

    void saveSession(const std::string& argument) {
        std::filesystem::path file = argument;
        if (file.empty()) {
            std::error_code ec;
            std::filesystem::create_directories(options_.sessionFolder, ec);
            file = uniqueSessionPath(options_.sessionFolder, app_.scene().name, state_.technique, std::chrono::system_clock::now());
        }
        std::string error;
        const TourStep step = captureSession(app_, state_);
        if (!writeWholeFile(file, tourStepJson(step).dump(2) + "\n", error))
            return failed(state_.sessionStatus, state_.sessionStatusIsError, error, 1);
        state_.sessionStatus = "saved " + file.string();
        state_.sessionStatusIsError = false;
        logInfo("session saved: " + file.string());
    }

    void loadSession(const std::string& file) {
        TourStep step;
        std::string error;
        if (!shadowlab::loadSession(file, app_.techniques().techniques(), step, error) ||
            !checkStepView(app_, step, file, error) || !applyTourStep(app_, step, state_, error))
            return failed(state_.sessionStatus, state_.sessionStatusIsError, error, 2);
        state_.sessionStatus = "loaded " + file;
        state_.sessionStatusIsError = false;
        logInfo("session loaded: " + file);
    }

    App& app_;
    const InteractiveOptions& options_;
    GLFWwindow* window_;
    Ui ui_;
    UiState state_;
    ViewCompositor compositor_;
    GLuint surface_ = 0;
    glm::ivec2 surfaceSize_{0};
    int frameIndex_ = 0;
    int exitCode_ = 0;
    std::chrono::steady_clock::time_point last_;
    glm::dvec2 lastMouse_{0.0};
    bool fullscreen_ = false;
    std::filesystem::path recordOut_;  // the export being recorded ("" = none)
    std::filesystem::path recordFolder_;
    int recordTarget_ = 0;             // frames to record (0: until the run ends)
    int recordedFrames_ = 0;
    int recordings_ = 0;
    glm::ivec4 windowedRect_{0};       // x, y, width, height before presenter mode took the screen
    long presentedFrames_ = 0;         // swaps, held frames included
    long measureStartFrame_ = 0;
    float longestFrameGap_ = 0.0f;     // seconds between two frames while measuring (the click's frame included)
    std::chrono::steady_clock::time_point measureStart_;
    AsyncMeasurement measurement_{app_};   // last: joined and released before the rest goes
};

int App::runInteractive(const InteractiveOptions& options) {
    inWindowLoop_ = true;   // read-backs of the frame loop never wait (render/depth_range.h)
    const int code = WindowSession(*this, options).run();
    inWindowLoop_ = false;
    return code;
}

} // namespace shadowlab
