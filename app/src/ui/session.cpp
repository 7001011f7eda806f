// The classroom window's frame loop (see session.h). A frame, top to bottom:
//   input -> layout (panel beside the view, halves of a comparison) -> for each side: its
//   technique's frame at the side's size, presented into the display texture, blitted into its
//   rectangle -> the panel and the labels (ImGui) -> the commands the panel emitted (screenshot,
//   measure, load scene, tour step, load tour, save or load session) -> swap
// --tour and --session are the same commands, run once before the first frame.
#include "ui/session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

#include <GLFW/glfw3.h>

#include "bench/path_run.h"
#include "ui/tour_player.h"
#include "ui/ui.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/text_file.h"

namespace shadowlab {

MeasurementKey currentMeasurementKey(App& app, const std::string& technique) {
    MeasurementKey key;
    key.scene = app.scene().name;
    key.technique = technique;
    if (const TechniqueInfo* info = app.techniques().find(technique)) key.params = app.params().values(*info);
    key.size = app.renderer().size();
    key.viewProjection = app.camera().info(key.size).viewProjection;
    key.lightDirection = app.light().direction;
    key.lightSize = app.light().size;
    return key;
}

bool measureSide(App& app, const std::string& technique, const ReferenceOptions& options, SideMeasurement& out,
                 std::string& error) {
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info) {
        error = "no technique '" + technique + "'";
        return false;
    }
    // This side's own frame: the frame before may have been the other side's technique.
    if (!app.renderFrame(technique, error, FrameOutputs::Accuracy)) return false;
    Evaluation evaluation;
    if (!app.evaluate(options, evaluation, error)) return false;
    if (!app.presentView(technique, {}, ~0u, {}, error)) return false;
    const Image lit = app.readDisplay();
    out.technique = technique;
    out.label = technique;
    const auto& values = app.params().values(*info);
    for (size_t i = 0; i < info->params.size(); ++i)
        out.label += " " + info->params[i].id + "=" + formatParamValue(info->params[i], values[i]);
    std::string loadError;
    LoadedTechnique* loaded = app.techniques().get(technique, loadError);
    out.gpuBytes = loaded ? loaded->host().gpuBytes() : 0;
    out.metrics = evaluation.metrics;
    out.translucentMetrics = evaluation.translucentMetrics;
    out.translucentLayers = evaluation.translucentLayers.size();
    out.traceSeconds = evaluation.traceSeconds;
    out.heatmap = heatmapOverLit(lit, evaluation.technique, evaluation.reference, evaluation.mask);
    out.key = currentMeasurementKey(app, technique);
    return true;
}

namespace {

// GL objects of the window that are not the renderer's: the offscreen surface (headless), the
// copy of A's shadow term for the difference view, one heatmap texture per side. Created when a
// size changes or a measurement arrives, never per frame.
struct SessionTargets {
    GlTexture surfaceColor;
    GlFramebuffer surface;
    glm::ivec2 surfaceSize{0};
    GlTexture visibilityA;
    GlFramebuffer visibilityAFbo;
    glm::ivec2 visibilityASize{0};
    GlTexture heatmaps[2];
    glm::ivec2 heatmapSizes[2]{};
    ProgramId differenceProgram = 0;
};

GlTexture makeTexture(GLenum format, glm::ivec2 size) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    glTextureStorage2D(name, 1, format, size.x, size.y);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return GlTexture(name);
}

// The display texture (renderer size) into `target` at `rect` (window pixels, top-left origin),
// from the part of the display that starts `sourceX` pixels in.
void blitDisplay(App& app, GLuint target, glm::ivec2 surface, const PixelRect& rect, int sourceX) {
    if (rect.size.x <= 0 || rect.size.y <= 0) return;
    const glm::ivec2 size = app.renderer().size();
    const int w = std::min(rect.size.x, size.x - sourceX), h = std::min(rect.size.y, size.y);
    const int y0 = surface.y - (rect.origin.y + h);
    glBlitNamedFramebuffer(app.renderer().displayFramebuffer(), target, sourceX, 0, sourceX + w, h, rect.origin.x, y0,
                           rect.origin.x + w, y0 + h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image readSurface(GLuint framebuffer, glm::ivec2 size) {
    Image image{size.x, size.y, 4, std::vector<uint8_t>(size_t(size.x) * size_t(size.y) * 4)};
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(framebuffer == 0 ? GL_BACK : GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
    return image;
}

} // namespace

int App::runInteractive(const InteractiveOptions& options) {
    GLFWwindow* window = backend_->window();
    if (!window && options.frames <= 0) {
        logError("the offscreen window needs a number of frames to draw (--frames N)");
        return 2;
    }
    // --tour: every step's debug view checked before anything is drawn (a view would otherwise
    // only be found missing when its step comes up in class).
    if (std::string error; options.tour && !checkTourDebugViews(*this, *options.tour, error)) {
        logError(error);
        return 2;
    }
    Ui ui;
    if (!ui.init(window, options.uiScale)) {
        logError("could not initialise the user interface");
        return 1;
    }
    SessionTargets targets;
    {
        std::string error;
        targets.differenceProgram =
            shaders_->build(hostShaderRequest("fullscreen.vert", "compare_difference.frag", "comparison difference"), error);
        if (!targets.differenceProgram) logError(error);
    }
    UiState state;
    state.technique = options.technique.empty() ? firstTechnique() : options.technique;
    state.compareTechnique = options.compareTechnique;
    state.compareLayout = options.compareLayout;
    state.wipe = options.wipe;
    state.showUi = options.showUi;
    state.view = options.view;
    if (options.probe) setProbePixel(options.probe);
    state.uiScale = options.uiScale;
    state.msaaSamples = renderer_->msaaSamples();
    camera_.setFramingAspect(kSceneFramingAspect);
    int frame = 0;
    auto last = std::chrono::steady_clock::now();
    glm::dvec2 lastMouse{0.0};
    if (window) glfwGetCursorPos(window, &lastMouse.x, &lastMouse.y);
    const auto& all = techniques_->techniques();
    int exitCode = 0;
    const int smokeFrames = options.cycle ? options.frames : 0;

    // The commands the panel, the keys, tours and sessions emit; run between frames (and once
    // before the first, for --tour and --session).
    GLuint surface = 0;
    glm::ivec2 surfaceSize{0};
    std::function<void(const UiCommand&)> runCommand = [&](const UiCommand& command) {
        std::string error;
        switch (command.kind) {
        case UiCommand::Kind::Screenshot: {
            std::filesystem::path file = command.argument;
            if (file.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(options.screenshotFolder, ec);
                file = uniqueScreenshotPath(options.screenshotFolder, scene_->name, state.technique, state.compareTechnique,
                                            std::chrono::system_clock::now());
            }
            if (writePng(file, readSurface(surface, surfaceSize), error)) {
                logInfo("screenshot saved: " + file.string());
                state.lastScreenshot = "saved " + file.string();
            } else {
                logError(error);
                state.lastScreenshot = error;
                if (options.frames > 0) exitCode = 1;
            }
            break;
        }
        case UiCommand::Kind::Measure: {
            ReferenceOptions reference;
            reference.mode = state.referenceMode == 1 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
            reference.samplesPerPixel = state.referenceSamples;
            std::vector<SideMeasurement> results;
            state.measureError.clear();
            const std::string sides[2] = {state.technique, state.compareTechnique};
            for (int s = 0; s < (state.compareTechnique.empty() ? 1 : 2); ++s) {
                const TechniqueInfo* info = techniques_->find(sides[s]);
                reference.model = state.referenceModel == 1 && info ? info->translucencyModel : TranslucencyModel::Physical;
                SideMeasurement result;
                if (!measureSide(*this, sides[s], reference, result, error)) {
                    state.measureError = sides[s] + ": " + error;
                    break;
                }
                const auto frameMs = state.sideTimings[s].find("frame");
                result.gpuMs = frameMs == state.sideTimings[s].end() ? 0.0 : frameMs->second;
                state.measured.push_back({result.label, result.gpuMs, result.metrics.mae});
                char figures[128];
                std::snprintf(figures, sizeof(figures), ": MAE %.6f, %.3f ms GPU, %.2f MiB", result.metrics.mae, result.gpuMs,
                              double(result.gpuBytes) / (1024.0 * 1024.0));
                logInfo("accuracy of " + result.label + figures);
                // Its texture, for the heatmap view (re-created only when the size changed).
                const glm::ivec2 size{result.heatmap.width, result.heatmap.height};
                if (targets.heatmapSizes[s] != size) {
                    targets.heatmaps[s] = makeTexture(GL_RGBA8, size);
                    targets.heatmapSizes[s] = size;
                }
                glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
                glTextureSubImage2D(targets.heatmaps[s].get(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE,
                                    result.heatmap.pixels.data());
                results.push_back(std::move(result));
            }
            if (state.measureError.empty()) {
                state.measurement = std::move(results);
                if (state.compareLayout != CompareLayout::Difference) state.view = {ViewSelection::Kind::ErrorHeatmap, ""};
            }
            break;
        }
        case UiCommand::Kind::LoadScene:
            state.sceneError = loadScene(command.argument, {}, error) ? "" : error;
            if (state.sceneError.empty()) state.path.reset();   // a step's path belongs to its scene
            break;
        case UiCommand::Kind::TourStep: {
            if (!state.tour || state.tour->steps.empty()) break;
            const int last = int(state.tour->steps.size()) - 1;
            int index = state.tourStep;
            if (command.argument == "next") index = std::min(index + 1, last);
            else if (command.argument == "previous") index = std::max(index - 1, 0);
            else if (command.argument != "restart") index = std::clamp(std::atoi(command.argument.c_str()), 0, last);
            const std::string where = state.tour->source + ": steps[" + std::to_string(index) + "]";
            if (applyTourStep(*this, state.tour->steps[size_t(index)], state, error)) {
                state.tourStep = index;
                state.tourStatus.clear();
                state.tourStatusIsError = false;
                logInfo("tour step " + std::to_string(index + 1) + " of " + std::to_string(last + 1) + ": " +
                        state.tour->steps[size_t(index)].title);
            } else {
                state.tourStatus = where + ": " + error;
                state.tourStatusIsError = true;
                logError(state.tourStatus);
                if (options.frames > 0) exitCode = 1;
            }
            break;
        }
        case UiCommand::Kind::LoadTour: {
            auto tour = std::make_shared<Tour>();
            // Checked whole before its first step is shown, debug views included.
            if (!loadTour(command.argument, techniques_->techniques(), *tour, error) ||
                !checkTourDebugViews(*this, *tour, error)) {
                state.tourStatus = error;
                state.tourStatusIsError = true;
                logError(error);
                break;
            }
            state.tour = std::move(tour);
            state.tourStep = 0;
            runCommand({UiCommand::Kind::TourStep, "0"});
            break;
        }
        case UiCommand::Kind::SaveSession: {
            std::filesystem::path file = command.argument;
            if (file.empty()) {
                std::error_code ec;
                std::filesystem::create_directories(options.sessionFolder, ec);
                file = uniqueSessionPath(options.sessionFolder, scene_->name, state.technique, std::chrono::system_clock::now());
            }
            const TourStep step = captureSession(*this, state);
            if (writeWholeFile(file, tourStepJson(step).dump(2) + "\n", error)) {
                state.sessionStatus = "saved " + file.string();
                state.sessionStatusIsError = false;
                logInfo("session saved: " + file.string());
            } else {
                state.sessionStatus = error;
                state.sessionStatusIsError = true;
                logError(error);
                if (options.frames > 0) exitCode = 1;
            }
            break;
        }
        case UiCommand::Kind::LoadSession: {
            TourStep step;
            if (loadSession(command.argument, techniques_->techniques(), step, error) &&
                applyTourStep(*this, step, state, error)) {
                state.sessionStatus = "loaded " + command.argument;
                state.sessionStatusIsError = false;
                logInfo("session loaded: " + command.argument);
            } else {
                state.sessionStatus = error;
                state.sessionStatusIsError = true;
                logError(error);
                if (options.frames > 0) exitCode = 2;
            }
            break;
        }
        }
    };

    if (options.tour) {
        state.tour = options.tour;
        runCommand({UiCommand::Kind::TourStep, std::to_string(options.tourStep)});
    }
    if (!options.session.empty()) runCommand({UiCommand::Kind::LoadSession, options.session});

    while (!backend_->shouldClose()) {
        backend_->pollEvents();
        const auto now = std::chrono::steady_clock::now();
        const float seconds = std::chrono::duration<float>(now - last).count();
        last = now;

        // Camera input, unless the UI has the mouse or keyboard or the wipe divider is dragged.
        if (window) {
            glm::dvec2 mouse;
            glfwGetCursorPos(window, &mouse.x, &mouse.y);
            const glm::vec2 delta = glm::vec2(mouse - lastMouse);
            lastMouse = mouse;
            if (!ui.wantsMouse() && !state.draggingWipe) {
                if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) camera_.look(delta);
                if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS) camera_.pan(delta);
                if (state.scroll != 0.0f) camera_.zoom(state.scroll);
            }
            state.scroll = 0.0f;
            if (!ui.wantsKeyboard() && camera_.mode() == CameraController::Mode::Fly) {
                glm::vec3 move(0.0f);
                if (glfwGetKey(window, GLFW_KEY_W) == GLFW_PRESS) move.z += 1;
                if (glfwGetKey(window, GLFW_KEY_S) == GLFW_PRESS) move.z -= 1;
                if (glfwGetKey(window, GLFW_KEY_D) == GLFW_PRESS) move.x += 1;
                if (glfwGetKey(window, GLFW_KEY_A) == GLFW_PRESS) move.x -= 1;
                if (glfwGetKey(window, GLFW_KEY_E) == GLFW_PRESS) move.y += 1;
                if (glfwGetKey(window, GLFW_KEY_Q) == GLFW_PRESS) move.y -= 1;
                camera_.fly(move, seconds);
            }
        }

        if (smokeFrames > 0 && !all.empty()) {
            // Smoke test: cycle through every technique and every view while drawing the UI.
            const int perTechnique = std::max(1, smokeFrames / int(all.size()));
            state.technique = all[size_t(std::min(frame / perTechnique, int(all.size()) - 1))].id;
            if (state.view.kind != ViewSelection::Kind::ErrorHeatmap || frame > smokeFrames / 2 + 5)
                state.view.kind = (frame / 7) % 2 ? ViewSelection::Kind::Visibility : ViewSelection::Kind::Lit;
            // And the comparison for a while, in each layout; once, a measurement of both sides.
            state.compareTechnique = (frame % 50) >= 35 ? firstTechnique() : std::string();
            state.compareLayout = CompareLayout((frame / 50) % 3);
            if (frame == smokeFrames / 2) {
                state.compareTechnique = firstTechnique();
                state.compareLayout = CompareLayout::SideBySide;
                state.commands.push_back({UiCommand::Kind::Measure, ""});
            }
        }

        // The step's path: one path frame per window frame, looping (camera and light set before
        // the frame is drawn, so frame k of a step shows path frame k).
        if (state.path && state.pathPlaying && state.path->frames > 0) {
            state.pathFrame %= state.path->frames;
            setPathFrame(*this, *state.path, state.pathFrame, state.pathCamera, state.pathLight);
        }

        // --measure: late enough for the GPU timings (read kFramesInFlight frames late), early
        // enough that the last frames show the heatmap.
        const int measureFrame = options.frames > 0 ? std::max(1, std::min(options.frames - 2, GpuTimer::kFramesInFlight + 2))
                                                    : GpuTimer::kFramesInFlight + 2;
        if (options.measure && frame == measureFrame) state.commands.push_back({UiCommand::Kind::Measure, ""});

        // The surface: the window's framebuffer, or the offscreen one (created once).
        surfaceSize = window ? backend_->framebufferSize() : options_.size;
        if (!window && targets.surfaceSize != surfaceSize) {
            targets.surfaceColor = makeTexture(GL_RGBA8, surfaceSize);
            GLuint name = 0;
            glCreateFramebuffers(1, &name);
            targets.surface.reset(name);
            glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, targets.surfaceColor.get(), 0);
            const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE) {
                logError("the offscreen window's framebuffer is " + framebufferStatusName(status));
                ui.shutdown();
                return 1;
            }
            targets.surfaceSize = surfaceSize;
        }
        surface = window ? 0 : targets.surface.get();
        const bool comparing = !state.compareTechnique.empty();
        state.layout = computeViewLayout(surfaceSize, state.showUi, panelWidthFor(state.uiScale, surfaceSize.x), comparing,
                                         state.compareLayout, state.wipe);
        const ViewLayout& layout = state.layout;
        std::string error;
        if (surfaceSize.x > 0 && surfaceSize.y > 0) {
            if (!renderer_->resize(layout.renderSize, state.msaaSamples, error)) logError(error);
            glBindFramebuffer(GL_FRAMEBUFFER, surface);
            glViewport(0, 0, surfaceSize.x, surfaceSize.y);
            glDisable(GL_SCISSOR_TEST);
            glClearColor(0.09f, 0.09f, 0.11f, 1.0f);
            glClear(GL_COLOR_BUFFER_BIT);
            state.frameError.clear();
            const std::string sides[2] = {state.technique, state.compareTechnique};
            const bool difference = comparing && state.compareLayout == CompareLayout::Difference;
            const FrameOutputs outputs = difference || state.view.needsAccuracyTargets()
                                             ? FrameOutputs::Accuracy
                                             : FrameOutputs::Colour;
            // The kernel view probes the pixel under the mouse (over the view, not the panel); without
            // a mouse (offscreen) it keeps --probe's.
            if (window && state.view.kind == ViewSelection::Kind::Kernel && !ui.wantsMouse()) {
                glm::dvec2 mouse;
                glfwGetCursorPos(window, &mouse.x, &mouse.y);
                const PixelRect& rect = layout.halves[0];
                if (rect.contains(glm::vec2(mouse)) && rect.size.x > 0 && rect.size.y > 0)
                    setProbePixel(glm::ivec2((glm::vec2(mouse) - glm::vec2(rect.origin)) * glm::vec2(layout.renderSize) /
                                             glm::vec2(rect.size)));
            }
            for (int s = 0; s < (comparing ? 2 : 1); ++s) {
                if (!renderFrame(sides[s], error, outputs)) {
                    state.frameError = error;
                    if (s == 1) state.compareTechnique.clear();
                    break;
                }
                state.sideTimings[s] = timer_->latest();   // this side's: the sides alternate frame by frame
                if (difference) {
                    if (s == 0) {
                        // A's shadow term, kept while B renders into the same targets.
                        if (targets.visibilityASize != renderer_->size()) {
                            targets.visibilityA = makeTexture(GL_RGBA16F, renderer_->size());
                            targets.visibilityASize = renderer_->size();
                        }
                        const glm::ivec2 size = renderer_->size();
                        glCopyImageSubData(renderer_->target(MainTarget::Visibility), GL_TEXTURE_2D, 0, 0, 0, 0,
                                           targets.visibilityA.get(), GL_TEXTURE_2D, 0, 0, 0, 0, size.x, size.y, 1);
                        continue;
                    }
                    if (targets.differenceProgram) {
                        glBindFramebuffer(GL_FRAMEBUFFER, renderer_->displayFramebuffer());
                        glViewport(0, 0, renderer_->size().x, renderer_->size().y);
                        glDisable(GL_DEPTH_TEST);
                        glDisable(GL_BLEND);
                        glDisable(GL_FRAMEBUFFER_SRGB);
                        glUseProgram(shaders_->program(targets.differenceProgram));
                        glBindTextureUnit(0, targets.visibilityA.get());
                        glBindTextureUnit(1, renderer_->target(MainTarget::Visibility));
                        renderer_->drawFullscreenTriangle();
                        blitDisplay(*this, surface, surfaceSize, layout.view, 0);
                    }
                    continue;
                }
                const bool heatmap = state.view.kind == ViewSelection::Kind::ErrorHeatmap && size_t(s) < state.measurement.size() &&
                                     targets.heatmaps[s].get() != 0;
                if (heatmap) {
                    renderer_->present(PresentMode::Color, targets.heatmaps[s].get(), renderer_->displayFramebuffer(), renderer_->size());
                } else {
                    ViewSelection view = state.view.kind == ViewSelection::Kind::ErrorHeatmap ? ViewSelection{} : state.view;
                    if (!presentView(sides[s], view, ~0u, {}, error)) {
                        // B may lack A's debug image: it shows lit, A says why it could not.
                        if (s == 0) {
                            state.view = {};
                            state.frameError = error;
                        }
                        presentView(sides[s], {}, ~0u, {}, error);
                    }
                }
                const PixelRect& rect = layout.halves[s];
                const int sourceX = comparing && state.compareLayout == CompareLayout::Wipe ? rect.origin.x - layout.view.origin.x : 0;
                blitDisplay(*this, surface, surfaceSize, rect, sourceX);
            }
            if (!comparing) state.sideTimings[1].clear();
            // The heatmap and figures say when they no longer describe the view.
            state.staleReason.clear();
            for (size_t s = 0; s < state.measurement.size() && state.staleReason.empty(); ++s)
                state.staleReason = staleReason(state.measurement[s].key, currentMeasurementKey(*this, sides[s]));
            if (state.measurement.size() != (comparing ? 2u : 1u) && !state.measurement.empty())
                state.staleReason = "the comparison changed";
        }
        ui.draw(*this, state, seconds, surface, surfaceSize);

        // The panel's commands, outside the ImGui frame. The screenshot first: it saves the frame
        // just drawn, panel included.
        const bool finalShot = options.frames > 0 && frame + 1 == options.frames && !options.screenshot.empty();
        std::vector<UiCommand> commands;
        commands.swap(state.commands);
        if (finalShot) commands.insert(commands.begin(), UiCommand{UiCommand::Kind::Screenshot, options.screenshot});
        if (options.frames > 0)
            for (const auto& [at, file] : options.screenshotsAt)
                if (at == frame && !(finalShot && file == options.screenshot))
                    commands.insert(commands.begin(), UiCommand{UiCommand::Kind::Screenshot, file});
        if (state.path && state.pathPlaying) ++state.pathFrame;   // a step applied by a command below starts at 0
        for (const UiCommand& command : commands) runCommand(command);
        backend_->swapBuffers();
        ++frame;
        if (options.frames > 0 && frame >= options.frames) break;
        if (state.quitRequested) break;
    }
    if (targets.differenceProgram) shaders_->release(targets.differenceProgram);
    camera_.setFramingAspect(0.0f);
    ui.shutdown();
    return exitCode;
}

} // namespace shadowlab
