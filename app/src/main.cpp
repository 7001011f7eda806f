// shadowlab: command line. Each command sets up an App and runs one job:
//   shadowlab                 the main job: the window if a display exists, else the report
//                             (every technique rendered to out/images, timings table, charts)
//   shadowlab list [--json]   techniques and their parameters (no GL needed)
//   shadowlab render ...      one frame headless to a PNG
// Exit codes: 0 success, 1 failure of the machine (no GL, ...), 2 bad input (with a message).
// Every input is checked before the first frame; whatever still escapes as an exception is
// reported by main()'s last-resort handler, never by std::terminate.
#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "util/strings.h"
#include "app.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/stress.h"
#include "bench/report.h"
#include "groundtruth/reference_technique.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "ui/tour_pages.h"
#include "util/gl_limits.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/text_file.h"
#include "shadowlab/translucent_layers_shared.h"

using namespace shadowlab;

namespace {

constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

struct CommonOptions {
    std::string scene;
    std::vector<std::string> sceneParams;
    std::string technique;
    std::string backend;
    std::string size = "1280x720";
    std::vector<std::string> sets;
    std::string lightDirection;
    std::string lightSize;      // text: checked against the scene's light type once it is known
    int msaa = 0;
    bool depthPrepass = false;
    int translucentLayers = 4;
    std::string referenceDevice = "cpu";
    std::string budget;
    bool quiet = false;
};

// Three finite numbers "x,y,z", not all zero, each within +-kMaxWorldCoordinate.
bool parseVec3(const std::string& text, glm::vec3& v, std::string& error) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
    bool valid = parts.size() == 3 && text.back() != ',';
    for (size_t i = 0; valid && i < 3; ++i) {
        const auto number = parseNumberText(parts[i]);
        valid = number && std::abs(*number) <= kMaxWorldCoordinate;
        if (valid) v[glm::length_t(i)] = static_cast<float>(*number);
    }
    if (!valid || !(glm::length(glm::dvec3(v)) > 1e-12)) {
        error = "--light-dir '" + text + "': expected three finite numbers x,y,z, not all zero";
        return false;
    }
    return true;
}

std::optional<double> lightSizeOption(const CommonOptions& common) {
    if (common.lightSize.empty()) return std::nullopt;
    return parseNumberText(common.lightSize);
}

bool buildOptions(const CommonOptions& common, AppOptions& options, std::string& error) {
    options.scene = common.scene;
    options.msaaSamples = common.msaa;
    options.depthPrepass = common.depthPrepass;
    options.translucentLayers = common.translucentLayers;
    if (common.referenceDevice == "gpu") {
        options.referenceDevice = ReferenceDevice::Gpu;
    } else if (common.referenceDevice != "cpu") {
        error = "--reference-device '" + common.referenceDevice + "': expected cpu or gpu";
        return false;
    }
    if (!parseSize(common.size, options.size, error)) return false;
    // The budget part of the render-target check needs no GL: before a context or buffer exists.
    if (error = renderTargetBudgetProblem(options.size, options.msaaSamples, 0); !error.empty()) return false;
    if (!common.backend.empty()) {
        options.backend = parseBackend(common.backend);
        if (!options.backend) {
            error = "--backend '" + common.backend + "': expected glfw, egl or osmesa";
            return false;
        }
    }
    if (!common.lightDirection.empty()) {
        glm::vec3 dir;
        if (!parseVec3(common.lightDirection, dir, error)) return false;
        options.lightDirection = dir;
    }
    if (!common.lightSize.empty()) {
        const auto size = lightSizeOption(common);
        if (!size || *size < 0.0) {
            error = "--light-size '" + common.lightSize + "': expected a finite number >= 0 (degrees for directional "
                    "lights, 0 to 45; world units for spot and point lights)";
            return false;
        }
        options.lightSize = static_cast<float>(*size);
    }
    for (const auto& text : common.sceneParams) {
        const auto equals = text.find('=');
        const auto value = equals == std::string::npos ? std::nullopt : parseNumberText(text.substr(equals + 1));
        if (equals == 0 || !value) {
            error = "--scene-param '" + text + "': expected name=number";
            return false;
        }
        options.sceneParameters[text.substr(0, equals)] = *value;
    }
    return true;
}

void addCommonOptions(CLI::App& cmd, CommonOptions& o) {
    cmd.add_option("--scene", o.scene, "built-in scene name or path to a scene JSON file")->group("Scene");
    cmd.add_option("--scene-param", o.sceneParams, "override a scene parameter: name=value (repeatable)")->group("Scene");
    cmd.add_option("--light-dir", o.lightDirection, "light travel direction x,y,z (directional and spot lights)")->group("Scene");
    cmd.add_option("--light-size", o.lightSize, "light radius (world units), or angular radius in degrees for directional lights")->group("Scene");
    cmd.add_option("--technique,-t", o.technique, "technique id (see `shadowlab list`)")->group("Technique");
    cmd.add_option("--set", o.sets, "parameter value key=value or technique.key=value (repeatable)")->group("Technique");
    cmd.add_option("--backend", o.backend, "glfw | egl | osmesa (default: glfw with a display, else egl)")->group("Output");
    cmd.add_option("--size", o.size, "render size WIDTHxHEIGHT (default 1280x720)")->group("Output");
    cmd.add_option("--msaa", o.msaa, "MSAA samples of the main pass (0 = off)")->check(CLI::IsMember({0, 2, 4, 8}))->group("Output");
    cmd.add_flag("--depth-prepass", o.depthPrepass,
                 "depth-only pre-pass of the opaque surfaces, then the main pass with depth test EQUAL: the shadow term "
                 "runs once per visible pixel")
        ->group("Output");
    cmd.add_option("--translucent-layers", o.translucentLayers,
                   "evaluation: translucent receivers peeled from the camera and measured, 0-8 (default 4; seed 001 "
                   "sec. 5.3.3)")
        ->check(CLI::Range(0, SHADOWLAB_MAX_TRANSLUCENT_LAYERS))
        ->group("Output");
    cmd.add_option("--reference-device", o.referenceDevice,
                   "the ground truth of eval, bench and Measure accuracy: cpu (Embree, default) | gpu (the GPU ray tracer "
                   "of issue 27, checked against Embree by the tests; docs/raytraced.md)")
        ->group("Output");
    cmd.add_option("--budget", o.budget,
                   "raise or lower the scene budget: objects=N,triangles=N,gpu-mib=N,file-mib=N (docs/scene-format.md, Limits)")
        ->group("Scene");
    cmd.add_flag("--quiet,-q", o.quiet, "only warnings and errors on stderr");
}

int fail(const std::string& error, int code) {
    logError(error);
    return code;
}

// Creates the App headless (or windowed) and reports errors with the right exit code.
int startApp(App& app, const CommonOptions& common, bool windowed) {
    setLogQuiet(common.quiet);
    AppOptions options;
    std::string error;
    if (!buildOptions(common, options, error)) return fail(error, kExitBadInput);
    if (!windowed && options.backend == BackendKind::Glfw) windowed = true;
    bool badInput = false;
    if (!app.init(options, windowed, error, badInput)) return fail(error, badInput ? kExitBadInput : kExitFailure);
    // The one range for --light-size and scene files, which depends on the scene's light.
    if (options.lightSize) {
        if (const std::string problem = lightSizeProblem(app.scene().light.type, *options.lightSize); !problem.empty())
            return fail("--light-size " + common.lightSize + ": " + problem, kExitBadInput);
    }
    return 0;
}

// What the classroom window is asked to do (the main job with a display, or offscreen).
struct WindowOptions {
    int smokeFrames = 0;
    int frames = 0;
    std::string screenshot;
    std::string compare;
    std::string compareLayout = "side-by-side";
    double wipe = 0.5;
    double uiScale = 1.0;
    bool hideUi = false;
    bool measure = false;
    std::string screenshotDir = "screenshots";
    std::string tour;            // a built-in tour's name or a tour file
    int tourStep = 1;            // from 1
    std::string session;         // a session file applied at the start
    std::string sessionDir = "sessions";
    std::string probe;           // X,Y: the kernel view's pixel, in the view's pixels from its top left
    // Flags given that only the window reads (for the message when there is no window).
    std::vector<std::string> given;
};

// "X,Y": two whole numbers, pixels from the top left.
bool parseProbe(const std::string& text, glm::ivec2& pixel) {
    const auto comma = text.find(',');
    if (comma == std::string::npos || comma == 0 || comma + 1 >= text.size()) return false;
    const std::string x = text.substr(0, comma), y = text.substr(comma + 1);
    auto digits = [](const std::string& t) {
        return !t.empty() && t.size() <= 6 && std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    if (!digits(x) || !digits(y)) return false;
    pixel = {std::stoi(x), std::stoi(y)};
    return true;
}

// Checks the window options against each other and the techniques; fills `out`.
int windowOptionsProblem(App& app, const WindowOptions& w, const std::string& technique, InteractiveOptions& out) {
    out.technique = technique;
    out.compareTechnique = w.compare;
    if (!w.compare.empty() && !app.techniques().find(w.compare)) {
        std::string known;
        for (const auto& t : app.techniques().techniques()) appendListItem(known, t.id);
        return fail("--compare '" + w.compare + "': no such technique (available: " + known + ")", kExitBadInput);
    }
    if (!parseCompareLayout(w.compareLayout, out.compareLayout))
        return fail("--compare-layout '" + w.compareLayout + "': expected side-by-side, wipe or difference", kExitBadInput);
    out.wipe = float(w.wipe);
    out.uiScale = float(w.uiScale);
    out.showUi = !w.hideUi;
    out.measure = w.measure;
    out.screenshotFolder = w.screenshotDir;
    out.screenshot = w.screenshot;
    out.cycle = w.smokeFrames > 0;
    out.frames = w.smokeFrames > 0 ? w.smokeFrames : w.frames;
    out.session = w.session;
    out.sessionFolder = w.sessionDir;
    if (!w.probe.empty()) {
        glm::ivec2 pixel;
        if (!parseProbe(w.probe, pixel))
            return fail("--probe '" + w.probe + "': expected X,Y, the pixel of the view (from its top left) whose filter "
                        "kernel the kernel view shows",
                        kExitBadInput);
        out.probe = pixel;
    }
    return 0;
}

// The techniques as their descriptors say, without GL (list, and checking tours and sessions
// before anything is created).
std::vector<TechniqueInfo> describedTechniques() {
    PluginScan scan = scanPlugins(pluginDir());
    scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));   // built into the host
    return scan.techniques;
}

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

// `shadowlab tour TOUR --out DIR`: every step of a tour as a slide with its caption and figures.
int commandTour(const CommonOptions& common, const std::string& name, const TourPageOptions& pageOptions) {
    Tour tour;
    std::string error;
    if (!loadTour(name, describedTechniques(), tour, error)) return fail(error, kExitBadInput);
    CommonOptions first = common;
    if (first.scene.empty()) first.scene = tour.steps.front().scene;   // loaded once at start, not twice
    App app;
    if (int code = startApp(app, first, false)) return code;
    TourPageOptions options = pageOptions;
    if (!parseSize(common.size, options.size, error)) return fail(error, kExitBadInput);
    const int code = writeTourPages(app, tour, options, error);
    if (code) return fail(error, code);
    std::printf("tour: %zu steps written to %s (index.html, README.md)\n", tour.steps.size(), options.outDir.string().c_str());
    return 0;
}

int commandList(bool json) {
    PluginScan scan = scanPlugins(pluginDir());
    for (const auto& error : scan.errors) logWarning("skipped plugin: " + error);
    scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));   // built into the host
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const auto& t : scan.techniques) {
            nlohmann::json params = nlohmann::json::array();
            for (const auto& p : t.params) {
                static const char* types[] = {"float", "int", "bool", "enum"};
                nlohmann::json item = {{"id", p.id}, {"label", p.label}, {"type", types[int(p.type)]},
                                       {"min", p.minValue}, {"max", p.maxValue}, {"default", p.defaultValue},
                                       {"unit", p.unit}, {"help", p.help}};
                if (p.type == ParamType::Enum) item["values"] = p.enumLabels;
                params.push_back(item);
            }
            out.push_back({{"id", t.id}, {"name", t.displayName}, {"category", t.category},
                           {"explanation", t.explanation}, {"library", t.library.string()}, {"parameters", params}});
        }
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    for (const auto& t : scan.techniques) {
        std::cout << t.id << "  (" << t.category << ")  " << t.displayName << "\n";
        for (const auto& p : t.params)
            std::cout << "    " << p.id << " = " << formatParamValue(p, p.defaultValue) << "   ["
                      << formatParamValue(p, p.minValue) << " .. " << formatParamValue(p, p.maxValue) << "] "
                      << p.unit << "  " << p.help.substr(0, p.help.find('.') + 1) << "\n";
    }
    std::cout << "scenes: ";
    for (const auto& name : builtinSceneNames()) std::cout << name << " ";
    std::cout << "\n";
    return 0;
}

// --reference: hard | soft | both | auto (hard for hard techniques, both for filtered and soft).
bool referenceModes(const std::string& text, const TechniqueInfo& info, std::vector<ReferenceOptions::Mode>& modes,
                    std::string& error) {
    using Mode = ReferenceOptions::Mode;
    if (text == "hard") modes = {Mode::Hard};
    else if (text == "soft") modes = {Mode::Soft};
    else if (text == "both") modes = {Mode::Hard, Mode::Soft};
    else if (text == "auto")
        modes = (info.category == "hard" || info.category == "baseline") ? std::vector<Mode>{Mode::Hard}
                                                                         : std::vector<Mode>{Mode::Hard, Mode::Soft};
    else {
        error = "--reference '" + text + "': expected hard, soft, both or auto";
        return false;
    }
    return true;
}

// Shadow term as grey (sRGB-encoded), pixels outside the comparison dark blue: `--view reference`.
Image visibilityImage(const std::vector<glm::vec3>& visibility, const std::vector<uint8_t>& mask, int width, int height) {
    Image image{width, height, 4, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
    for (size_t i = 0; i < visibility.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = std::clamp(visibility[i][c], 0.0f, 1.0f);
            const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
            image.pixels[i * 4 + size_t(c)] = mask[i] ? uint8_t(std::lround(srgb * 255.0f)) : uint8_t(c == 2 ? 38 : 13);
        }
    }
    return image;
}

ViewSelection parseView(const std::string& text) { return viewFromName(text); }

int commandRender(const CommonOptions& common, const std::string& out, const std::string& view, int frames,
                  const std::string& reference, int samples, const WindowOptions& compare, const std::string& path,
                  int pathFrames, const std::string& probe) {
    glm::ivec2 probePixel(0);
    if (!probe.empty()) {
        // Checked before the app starts: a bad value costs no context.
        if (!parseProbe(probe, probePixel))
            return fail("--probe '" + probe + "': expected X,Y, the pixel from the top left (e.g. 640,360)", kExitBadInput);
        if (view != "kernel")
            return fail("--probe: the kernel view draws the probe (--view kernel), not --view " + view, kExitBadInput);
        if (!compare.compare.empty() || !path.empty())
            return fail("--probe: one technique, one frame (without --compare or --path)", kExitBadInput);
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    if (!probe.empty()) {
        const glm::ivec2 size = app.renderer().size();
        if (probePixel.x >= size.x || probePixel.y >= size.y)
            return fail("--probe " + probe + ": outside the " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                            " image (x < " + std::to_string(size.x) + ", y < " + std::to_string(size.y) + ")",
                        kExitBadInput);
        app.setProbePixel(probePixel);
    }
    std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    if (!path.empty()) {
        // Every frame of a camera and light path, numbered, into the folder --out (docs/stability.md).
        if (!compare.compare.empty()) return fail("--path: one technique at a time (without --compare)", kExitBadInput);
        if (view == "error" || view == "reference") return fail("--path: --view " + view + " is not drawn per frame", kExitBadInput);
        if (!app.techniques().find(technique)) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
        std::string error;
        if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
        const int code = renderPath(app, technique, path, pathFrames, view, out, error);
        return code ? fail(error, code) : 0;
    }
    // --compare A,B (or --compare B with --technique A): both techniques in one image, labelled.
    std::string other;
    if (!compare.compare.empty()) {
        const auto comma = compare.compare.find(',');
        if (comma == std::string::npos) {
            other = compare.compare;
        } else {
            technique = compare.compare.substr(0, comma);
            other = compare.compare.substr(comma + 1);
        }
        if (technique.empty() || other.empty() || other.find(',') != std::string::npos)
            return fail("--compare '" + compare.compare + "': expected A,B (two technique ids, e.g. pcss,reference) or "
                        "one id to compare --technique with",
                        kExitBadInput);
        if (view != "lit" && view != "visibility")
            return fail("--view " + view + ": --compare shows lit or visibility", kExitBadInput);
    }
    std::string error;
    for (const std::string& id : {technique, other}) {
        if (id.empty() || app.techniques().find(id)) continue;
        std::string known;
        for (const auto& t : app.techniques().techniques()) appendListItem(known, t.id);
        return fail(std::string(other.empty() ? "--technique '" : "--compare: '") + id + "': no such technique (available: " +
                        known + ")",
                    kExitBadInput);
    }
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    if (!other.empty()) {
        WindowOptions w = compare;
        w.compare = other;
        w.frames = std::max(frames, 1);
        w.screenshot = out;
        w.hideUi = true;   // a slide: the view and the two labels
        InteractiveOptions options;
        if (int code = windowOptionsProblem(app, w, technique, options)) return code;
        options.view = parseView(view);
        const int code = app.runInteractive(options);
        if (code == 0) logInfo("wrote " + out);
        return code;
    }
    if (!probe.empty()) {
        // The kernel view as a slide: the window's frame loop offscreen without the panel, so the
        // footprint's numbers are drawn beside it, and printed.
        WindowOptions w;
        w.frames = std::max(frames, 1);
        w.screenshot = out;
        w.hideUi = true;
        InteractiveOptions options;
        if (int code = windowOptionsProblem(app, w, technique, options)) return code;
        options.view = parseView(view);
        options.probe = probePixel;
        const int code = app.runInteractive(options);
        if (code) return code;
        const KernelProbe& measured = app.lastProbe();
        std::printf("probe %d,%d: %s\n", probePixel.x, probePixel.y, describeProbe(measured).c_str());
        if (measured.valid)
            std::printf("probe %d,%d: kernel=%s n=%d kernel_texels=%.4f samples=%d early_out=%d lit=%.4f search_texels=%.4f "
                        "search_samples=%d blockers=%d blocker_depth=%.5f receiver_depth=%.5f penumbra_texels=%.4f "
                        "penumbra_world=%.5f decision=%s\n",
                        probePixel.x, probePixel.y,
                        measured.kernel == FilterKernel::Box    ? "box"
                        : measured.kernel == FilterKernel::Disc ? "disc"
                                                                : "pcss",
                        measured.n, double(measured.kernelTexels), measured.samplesTaken, measured.earlyOut ? 1 : 0,
                        double(measured.lit), double(measured.searchRadiusTexels), measured.searchSamples, measured.blockers,
                        double(measured.averageBlockerDepth), double(measured.receiverDepth), double(measured.kernelTexels),
                        double(measured.penumbraWorld), measured.decision.empty() ? "-" : measured.decision.c_str());
        std::fflush(stdout);
        logInfo("wrote " + out);
        return 0;
    }
    for (int i = 0; i < std::max(frames, 1); ++i)
        if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
    Image image;
    if (view == "error" || view == "reference") {
        // Accuracy views: the reference traced from this frame's own G-buffer.
        std::vector<ReferenceOptions::Mode> modes;
        if (!referenceModes(reference == "auto" ? "hard" : reference, *app.techniques().find(technique), modes, error))
            return fail(error, kExitBadInput);
        ReferenceOptions options;
        options.mode = modes.front();
        options.samplesPerPixel = samples;
        options.adaptive = true;   // as eval and bench: all the rays only where a penumbra may be
        options.model = TranslucencyModel::Physical;
        Evaluation evaluation;
        if (!app.evaluate(options, evaluation, error)) return fail(error, kExitFailure);
        image = view == "error" ? evaluation.heatmap()
                                : visibilityImage(evaluation.reference, evaluation.mask, evaluation.width, evaluation.height);
    } else {
        if (!app.presentView(technique, parseView(view), ~0u, {}, error)) return fail(error, kExitBadInput);
        image = app.readDisplay();
        if (parseView(view).kind == ViewSelection::Kind::Kernel) std::printf("%s\n", describeProbe(app.lastProbe()).c_str());
    }
    if (!writePng(out, image, error)) return fail(error, kExitFailure);
    logInfo("wrote " + out);
    return 0;
}

std::string describeParams(App& app, const TechniqueInfo& info) {
    std::string text;
    const auto& values = app.params().values(info);
    for (size_t i = 0; i < info.params.size(); ++i) {
        if (!text.empty()) text += " ";
        text += info.params[i].id + "=" + formatParamValue(info.params[i], values[i]);
    }
    return text;
}

int commandEval(const CommonOptions& common, const std::string& reference, int samples, bool adaptive, int frames,
                bool json) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
    std::string error;
    std::vector<ReferenceOptions::Mode> modes;
    if (!referenceModes(reference, *info, modes, error)) return fail(error, kExitBadInput);
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    Measurement m;
    if (!app.measure(technique, 5, frames, m, error)) return fail(error, kExitFailure);

    nlohmann::json out = {{"scene", app.scene().name}, {"technique", technique}, {"parameters", describeParams(app, *info)},
                          {"width", app.renderer().size().x}, {"height", app.renderer().size().y},
                          {"renderer", glRendererString()}, {"gpu_bytes", m.gpuBytes}};
    for (const auto& [pass, summary] : m.gpuMs)
        out["gpu_ms"][pass] = {{"median", summary.median}, {"p5", summary.p5}, {"p95", summary.p95}};
    out["cpu_ms"] = {{"median", m.cpuMs.median}, {"p5", m.cpuMs.p5}, {"p95", m.cpuMs.p95}};
    out["translucency_model"] = translucencyModelName(info->translucencyModel);
    out["reference_device"] = referenceDeviceName(app.referenceDevice());
    // Against the physical model ("hard", "soft") and, where it differs, the technique's own
    // ("hard_own", "soft_own"): docs/benchmarks.md, "Translucency models".
    const std::vector<TranslucencyModel> models = judgedModels(info->translucencyModel, app.scene());
    for (const auto mode : modes) {
        for (const TranslucencyModel model : models) {
            ReferenceOptions options;
            options.mode = mode;
            options.samplesPerPixel = samples;
            options.adaptive = adaptive;
            options.model = model;
            Evaluation evaluation;
            if (!app.evaluate(options, evaluation, error)) return fail(error, kExitFailure);
            const std::string name = std::string(mode == ReferenceOptions::Mode::Hard ? "hard" : "soft") +
                                     (model == TranslucencyModel::Physical ? "" : "_own");
            out["accuracy"][name] = nlohmann::json::parse(metricsToJson(evaluation.metrics));
            out["accuracy"][name]["model"] = translucencyModelName(model);
            out["accuracy"][name]["trace_seconds"] = evaluation.traceSeconds;
            if (!evaluation.translucentLayers.empty()) {
                // The translucent receivers, every peeled layer together and layer by layer.
                nlohmann::json receivers = nlohmann::json::parse(metricsToJson(evaluation.translucentMetrics));
                for (const TranslucentLayerEvaluation& layer : evaluation.translucentLayers)
                    receivers["layers"].push_back(nlohmann::json::parse(metricsToJson(layer.metrics)));
                out["accuracy"][name]["translucent_receivers"] = receivers;
            }
            if (!out.contains("texel_footprint") && evaluation.footprint.maps > 0)
                out["texel_footprint"] = nlohmann::json::parse(footprintToJson(evaluation.footprint));
            if (mode == ReferenceOptions::Mode::Soft) {
                // The reference's own penumbra error: soft figures below about 4x it are not resolved.
                const ReferenceStats& r = evaluation.referenceStats;
                out["accuracy"][name]["reference_rays"] = r.samplesPerPixel;
                out["accuracy"][name]["reference_adaptive"] = r.adaptive;
                out["accuracy"][name]["reference_floor"] = evaluation.referenceFloor;
                out["accuracy"][name]["reference_refined_fraction"] =
                    r.tracedPixels ? double(r.refinedPixels) / double(r.tracedPixels) : 0.0;
                out["accuracy"][name]["reference_shadow_rays"] = r.shadowRays;
            }
        }
    }
    if (json) {
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    std::printf("scene %s, technique %s (%s), %dx%d, %s\n", app.scene().name.c_str(), technique.c_str(),
                describeParams(app, *info).c_str(), app.renderer().size().x, app.renderer().size().y,
                glRendererString().c_str());
    for (const auto& [pass, summary] : m.gpuMs)
        std::printf("  GPU %-20s median %8.3f ms  (p5 %.3f, p95 %.3f)\n", pass.c_str(), summary.median, summary.p5, summary.p95);
    std::printf("  host CPU per frame   median %8.3f ms;  GPU memory %.2f MiB\n", m.cpuMs.median, double(m.gpuBytes) / 1048576.0);
    if (out.contains("texel_footprint")) {
        // Seed 002 eq. 8.1's dp/ds: pixels one shadow-map texel covers along its worst direction.
        const auto& f = out["texel_footprint"];
        const auto& t = f["medianByViewDepth"];
        std::printf("  texel footprint m (pixels per texel, worst direction; > 1 undersampled): median %.3f  p95 %.3f  "
                    "max %.3g  undersampled %.1f%% of pixels  median by view-depth third %.3f / %.3f / %.3f  "
                    "projection cos(a)/cos(b) median %.3f p95 %.3f  (%zu maps, %zu px uncovered)\n",
                    f["median"].get<double>(), f["p95"].get<double>(), f["max"].get<double>(),
                    100.0 * f["undersampledFraction"].get<double>(), t[0].get<double>(), t[1].get<double>(),
                    t[2].get<double>(), f["projectionMedian"].get<double>(), f["projectionP95"].get<double>(),
                    f["maps"].get<size_t>(), f["uncoveredPixels"].get<size_t>());
    }
    for (const auto& [name, metrics] : out["accuracy"].items()) {
        std::printf("  vs %s reference (%s model): MAE %.4f  RMSE %.4f  false shadow %.3f%%  false light %.3f%%  "
                    "MAE penumbra %.4f  MAE elsewhere %.4f  noise %.4f  compared %.1f%% of pixels\n",
                    name.c_str(), metrics["model"].get<std::string>().c_str(), metrics["mae"].get<double>(), metrics["rmse"].get<double>(),
                    100.0 * metrics["falseShadowRate"].get<double>(), 100.0 * metrics["falseLightRate"].get<double>(),
                    metrics["maePenumbra"].get<double>(), metrics["maeOutsidePenumbra"].get<double>(),
                    metrics["noiseEnergy"].get<double>(), 100.0 * metrics["comparedFraction"].get<double>());
        const auto& thirds = metrics["maeByViewDepth"];
        const auto& thirdPixels = metrics["comparedPixelsByViewDepth"];
        std::printf("    MAE by view depth (thirds of near..far): near %.4f (%zu px)  mid %.4f (%zu px)  far %.4f (%zu px)\n",
                    thirds[0].get<double>(), thirdPixels[0].get<size_t>(), thirds[1].get<double>(),
                    thirdPixels[1].get<size_t>(), thirds[2].get<double>(), thirdPixels[2].get<size_t>());
        if (metrics.contains("translucent_receivers")) {
            const auto& t = metrics["translucent_receivers"];
            const auto& channel = t["maePerChannel"];
            std::printf("    translucent receivers (%zu layers, %zu px): MAE %.4f  (r %.4f g %.4f b %.4f)  false shadow %.3f%%  "
                        "false light %.3f%%;  by layer:",
                        t["layers"].size(), t["comparedPixels"].get<size_t>(), t["mae"].get<double>(),
                        channel[0].get<double>(), channel[1].get<double>(), channel[2].get<double>(),
                        100.0 * t["falseShadowRate"].get<double>(), 100.0 * t["falseLightRate"].get<double>());
            for (const auto& layer : t["layers"])
                std::printf(" %.4f (%zu px)", layer["mae"].get<double>(), layer["comparedPixels"].get<size_t>());
            std::printf("\n");
        }
        if (metrics.contains("reference_floor"))
            std::printf("    soft reference: %d rays per pixel%s (%.1f%% of pixels refined), traced in %.2f s; its own "
                        "penumbra error (floor) %.4f\n",
                        metrics["reference_rays"].get<int>(), metrics["reference_adaptive"].get<bool>() ? ", adaptive" : "",
                        100.0 * metrics["reference_refined_fraction"].get<double>(),
                        metrics["trace_seconds"].get<double>(), metrics["reference_floor"].get<double>());
    }
    return 0;
}

int commandBench(const CommonOptions& common, std::vector<BenchSpec> specs, const std::string& out) {
    // Everything checked before a context exists or a frame is drawn: techniques from their
    // descriptors (no GL), scenes with checkScene. The device's limits come right after.
    {
        PluginScan scan = scanPlugins(pluginDir());
        scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));
        std::string error;
        for (size_t i = 0; i < specs.size(); ++i) {
            if (!checkBenchSpec(specs[i], scan.techniques, error, lightSizeOption(common))) {
                return fail(specs.size() > 1 ? "benchmark spec " + std::to_string(i) + ": " + error : error, kExitBadInput);
            }
        }
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    for (const BenchSpec& spec : specs) {
        for (const glm::ivec2 size : spec.sizes) {
            std::string error;
            if (!checkRenderTargets(size, app.renderer().msaaSamples(), 0, error)) return fail(error, kExitBadInput);
        }
    }
    std::vector<nlohmann::json> rows;
    std::string error;
    // The file is rewritten after every row, so a run cut short keeps what it measured.
    std::vector<nlohmann::json> written;
    printBenchHeader();
    auto onRow = [&](const nlohmann::json& row) {
        printBenchRow(row);
        written.push_back(row);
        std::string writeError;
        if (!writeBenchResults(out, written, writeError)) logWarning(writeError);
    };
    for (const BenchSpec& spec : specs)
        if (!runBench(app, spec, rows, error, onRow)) return fail(error, kExitBadInput);
    if (!writeBenchResults(out, rows, error)) return fail(error, kExitFailure);
    logInfo("wrote " + std::to_string(rows.size()) + " rows to " + out);
    return 0;
}

// `bench --path`: every frame of a path timed per technique and scene (docs/stability.md).
int commandBenchPath(const CommonOptions& common, const PathBenchOptions& options, const std::string& out) {
    {
        // The scenes are checked before a context exists.
        for (const std::string& scene : options.scenes) {
            try {
                checkScene(scene);
            } catch (const SceneError& e) {
                return fail(std::string("--scenes: ") + e.what(), kExitBadInput);
            }
        }
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    std::string error;
    for (const std::string& scene : options.scenes.empty() ? std::vector<std::string>{app.scene().name} : options.scenes) {
        // Each scene's path resolved up front, so a bad --path fails before the first frame.
        Scene loaded = loadScene(scene);
        CameraPath path;
        BuiltinPathOptions pathOptions;
        pathOptions.frames = options.frames;
        if (!resolvePath(options.path, loaded, pathOptions, path, error)) return fail(error, kExitBadInput);
    }
    std::vector<nlohmann::json> rows;
    auto onRow = [&](const nlohmann::json& row) {
        std::printf("%-12s %-20s path %-8s %4d frames  frame ms p5 %.3f  p50 %.3f  p95 %.3f  max %.3f (frame %d)%s\n",
                    row["scene"].get<std::string>().c_str(), row["technique"].get<std::string>().c_str(),
                    row["path"].get<std::string>().c_str(), row["frames"].get<int>(), row["frame_ms_p5"].get<double>(),
                    row["frame_ms_p50"].get<double>(), row["frame_ms_p95"].get<double>(), row["frame_ms_max"].get<double>(),
                    row["frame_ms_max_frame"].get<int>(),
                    row.contains("flicker_mean")
                        ? ("  flicker " + std::to_string(row["flicker_mean"].get<double>()) + "  popping " +
                           std::to_string(row["popping"].get<double>())).c_str()
                        : "");
        std::string writeError;
        if (!writeBenchResults(out, rows, writeError)) logWarning(writeError);
    };
    if (int code = benchPath(app, options, rows, onRow, error)) return fail(error, code);
    if (!writeBenchResults(out, rows, error)) return fail(error, kExitFailure);
    logInfo("wrote " + std::to_string(rows.size()) + " rows to " + out);
    return 0;
}

// `stress`: the failure suite (assets/stress/cases.json; docs/stability.md).
int commandStress(const CommonOptions& common, const std::string& casesFile, const std::string& sizeText, StressOptions options) {
    StressSuite suite;
    std::string error;
    if (!loadStressSuite(casesFile.empty() ? defaultStressCases() : std::filesystem::path(casesFile), suite, error))
        return fail(error, kExitBadInput);
    if (!sizeText.empty()) {
        glm::ivec2 size;
        if (!parseSize(sizeText, size, error, "--stress-size")) return fail(error, kExitBadInput);
        options.size = size;
    }
    App app;
    if (int code = startApp(app, common, false)) return code;
    std::vector<StressCell> cells;
    const int code = runStress(app, suite, options, cells, error);
    return code ? fail(error, code) : 0;
}

// Hot-reload latency: the plugin library is rewritten on disk (as a rebuild does) and the time to
// the end of the first frame drawn with the new library is measured, `trials` times.
int commandReloadLatency(const CommonOptions& common, int trials) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    const std::string technique = common.technique.empty() ? "shadowmap" : common.technique;
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info || info->library.empty()) return fail("--technique '" + technique + "': no plugin library", kExitBadInput);
    std::string error;
    std::ifstream in(info->library, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<double> latencies;
    for (int trial = 0; trial < trials; ++trial) {
        for (int i = 0; i < 5; ++i)
            if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
        glFinish();
        {
            std::ofstream out(info->library, std::ios::binary | std::ios::trunc);
            out.write(bytes.data(), std::streamsize(bytes.size()));
        }
        const auto start = std::chrono::steady_clock::now();
        bool reloaded = false;
        while (!reloaded && std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
            if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
            reloaded = std::find(app.lastReloaded().begin(), app.lastReloaded().end(), technique) != app.lastReloaded().end();
        }
        glFinish();   // the frame drawn with the new library has completed
        if (!reloaded) return fail("the rewritten library was not reloaded within 5 s", kExitFailure);
        latencies.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    const TimingSummary s = summarize(latencies);
    std::printf("hot reload of %s: median %.1f ms, p5 %.1f, p95 %.1f over %d trials (file written -> first frame drawn "
                "with it; polling every 50 ms and waiting for two equal polls)\n",
                technique.c_str(), s.median, s.p5, s.p95, trials);
    return 0;
}

// The report: the default sweep measured, charted and written up into `outDir`. Without a display
// this is the main job.
int commandReport(const CommonOptions& common, const std::string& specFile, const std::string& outDir) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    const bool software = glRendererString().find("llvmpipe") != std::string::npos;
    const std::filesystem::path spec = specFile.empty() ? defaultReportSpec(software) : std::filesystem::path(specFile);
    std::vector<BenchSpec> specs;
    std::string error;
    if (!loadBenchSpecs(spec, specs, error)) return fail(error, kExitBadInput);
    std::printf("shadowlab report: sweep %s on %s\n", spec.string().c_str(), glRendererString().c_str());
    const int code = runReport(app, specs, outDir, error, lightSizeOption(common));
    if (code) return fail(error, code);
    return 0;
}

int run(int argc, char** argv) {
    CLI::App cli{"shadowlab: real-time shadow techniques as plugins, measured for speed and accuracy"};
    cli.fallthrough();
    cli.require_subcommand(0, 1);
    CommonOptions common;
    addCommonOptions(cli, common);
    WindowOptions window;
    std::string outDir = "out";
    // Window options: without a display, --frames (or --smoke-test) draws the same window offscreen.
    auto windowOption = [&](CLI::Option* option) { return option->group("Window"); };
    windowOption(cli.add_option("--smoke-test", window.smokeFrames, "window: draw N frames cycling every technique, then exit"))
        ->check(CLI::Range(1, 1000000));
    windowOption(cli.add_option("--compare", window.compare, "window: compare this technique (B) with --technique (A)"));
    windowOption(cli.add_option("--compare-layout", window.compareLayout, "side-by-side (default) | wipe | difference"));
    windowOption(cli.add_option("--wipe", window.wipe, "wipe divider position across the view, 0..1 (default 0.5)"))
        ->check(CLI::Range(0.0, 1.0));
    windowOption(cli.add_option("--frames", window.frames,
                                "window: draw N frames, save --screenshot, exit (slides; offscreen without a display)"))
        ->check(CLI::Range(1, 1000000));
    windowOption(cli.add_option("--screenshot", window.screenshot, "window: save a screenshot at the end of --smoke-test or --frames"));
    windowOption(cli.add_option("--ui-scale", window.uiScale, "window: size of the panel's text and widgets (1.5-2 for a projector)"))
        ->check(CLI::Range(0.5, 4.0));
    windowOption(cli.add_flag("--hide-ui", window.hideUi, "window: start with the panel hidden (F1 or H toggles it)"));
    windowOption(cli.add_option("--probe", window.probe,
                                "window: X,Y, the pixel of the view (from its top left) the kernel view probes until the "
                                "mouse moves over the view (offscreen slides keep it)"));
    windowOption(cli.add_flag("--measure", window.measure,
                              "window: measure accuracy after a few frames, each side of a comparison for its own "
                              "technique, and show the heatmap (with --frames: a slide of it)"));
    windowOption(cli.add_option("--screenshot-dir", window.screenshotDir, "window: folder of F12 screenshots (default screenshots)"));
    windowOption(cli.add_option("--tour", window.tour,
                                "window: play a guided tour, a built-in name (assets/tours) or a tour file; with --frames "
                                "a slide of one step"));
    windowOption(cli.add_option("--tour-step", window.tourStep, "window: the tour's step to start at (from 1)"))
        ->check(CLI::Range(1, int(kMaxTourSteps)));
    windowOption(cli.add_option("--session", window.session, "window: restore a saved session (a JSON tour step) at the start"));
    windowOption(cli.add_option("--session-dir", window.sessionDir, "window: folder of saved sessions (default sessions)"));
    cli.add_option("--out-dir", outDir, "headless main job: folder of the report (default out)");

    auto* list = cli.add_subcommand("list", "list techniques and their parameters");
    bool listJson = false;
    list->add_flag("--json", listJson, "machine-readable output");

    auto* render = cli.add_subcommand("render", "render one frame headless to a PNG file");
    std::string renderOut, renderView = "lit";
    int renderFrames = 3;
    render->add_option("--out,-o", renderOut, "PNG file to write")->required();
    render->add_option("--view", renderView,
                       "lit | visibility | error (heatmap vs the reference) | reference | footprint (texel footprint m, log2 heat map) | "
                       "texel-grid | coverage (which map serves a pixel, and the light frusta) | focus-body (the focus body B, "
                       "seed 002 eq. 4.2, and the map's volume) | kernel (the filter kernel around --probe) | a debug image "
                       "(e.g. 'shadow map')");
    std::string renderProbe;
    render->add_option("--probe", renderProbe,
                       "with --view kernel: X,Y, the pixel (from the top left) whose filter kernel is drawn and measured; "
                       "its numbers are printed");
    render->add_option("--frames", renderFrames, "frames to render before saving (default 3)")->check(CLI::Range(1, 10000));
    std::string reference = "auto";
    int referenceSamples = BenchSpec{}.referenceSamples;
    render->add_option("--reference", reference, "--view error/reference: hard | soft (default hard)");
    render->add_option("--samples", referenceSamples, "soft reference: rays per pixel, traced adaptively (default 1024)")->check(CLI::Range(1, 4096));
    WindowOptions renderCompare;
    render->add_option("--compare", renderCompare.compare,
                       "A,B: both techniques in one image with their labels (B may be 'reference', the ground truth)");
    render->add_option("--compare-layout", renderCompare.compareLayout, "with --compare: side-by-side (default) | wipe | difference");
    render->add_option("--wipe", renderCompare.wipe, "with --compare-layout wipe: divider position, 0..1 (default 0.5)")
        ->check(CLI::Range(0.0, 1.0));
    render->add_option("--ui-scale", renderCompare.uiScale, "with --compare: size of the labels (default 1)")->check(CLI::Range(0.5, 4.0));
    std::string renderPathText;
    int renderPathFrames = 0;
    render->add_option("--path", renderPathText,
                       "camera and light path (a JSON file, a path of the scene or built-in: orbit, dolly, sweep, walk, "
                       "static): every frame to --out FOLDER/frame_NNNNN.png (and frames.mp4 with ffmpeg)");
    render->add_option("--path-frames", renderPathFrames, "with --path: frames along it (default: the path's own)")->check(CLI::Range(1, 100000));

    auto* bench = cli.add_subcommand("bench", "measure sweeps of techniques, scenes and parameters into CSV or JSON");
    BenchSpec benchSpec;
    std::string benchTechniques, benchScenes, benchSpecFile, benchOut;
    std::vector<std::string> benchSweeps, benchSizes;
    bench->add_option("--techniques", benchTechniques, "comma-separated technique ids (default: all but the reference)");
    bench->add_option("--scenes", benchScenes, "comma-separated scenes (default: cube)");
    bench->add_option("--sweep", benchSweeps, "key=v1,v2,...: technique parameter, scene.<param> or light.size (repeatable)");
    bench->add_option("--size", benchSizes, "output size WxH (repeatable; default 1280x720)");
    bench->add_option("--frames", benchSpec.frames, "timed frames per combination (default 200)")->check(CLI::Range(1, 100000));
    bench->add_option("--warmup", benchSpec.warmupFrames, "warm-up frames (default 20)")->check(CLI::Range(0, 100000));
    bench->add_flag("--accuracy", benchSpec.accuracy, "add the ground-truth metrics of each combination's last frame");
    std::string benchReference = "auto";
    int benchSamples = BenchSpec{}.referenceSamples;
    std::string benchAdaptive = "on";
    bench->add_option("--reference", benchReference, "with --accuracy: hard | soft | both | auto");
    bench->add_option("--samples", benchSamples, "soft reference rays per pixel (default 1024)");
    bench->add_option("--reference-adaptive", benchAdaptive,
                      "soft reference: a first batch everywhere, all --samples rays only near penumbrae: on | off (default on)");
    bench->add_flag("--depth-floor", benchSpec.depthFloor, "add a bare depth-only pass per shadow-map resolution");
    bench->add_option("--spec", benchSpecFile, "JSON spec (one object or an array); command-line lists are ignored then");
    bench->add_option("--out,-o", benchOut, "results file: .csv or .json")->required();
    std::string benchPathText;
    int benchPathFrames = 0;
    bench->add_option("--path", benchPathText,
                      "time every frame along a camera and light path (a JSON file, a path of the scene or built-in: "
                      "orbit, dolly, sweep, walk, static): p5/p50/p95/max per technique and scene; --accuracy adds the "
                      "temporal metrics");
    bench->add_option("--path-frames", benchPathFrames, "with --path: frames along it (default: the path's own)")->check(CLI::Range(1, 100000));

    auto* stress = cli.add_subcommand("stress", "the failure suite: named cases where techniques fail, table, chart and images");
    StressOptions stressOptions;
    std::string stressTechniques, stressCases, stressCasesFile, stressOut = "out/stress", stressSize;
    stress->add_option("--techniques", stressTechniques, "comma-separated technique ids (default: every technique found)");
    stress->add_option("--cases", stressCases, "comma-separated case ids (default: all)");
    stress->add_option("--cases-file", stressCasesFile, "cases file (default assets/stress/cases.json)");
    stress->add_option("--out,-o", stressOut, "output folder (default out/stress)");
    stress->add_option("--stress-size", stressSize, "render size WIDTHxHEIGHT (default: the cases file's, 160x120)");

    auto* report = cli.add_subcommand("report", "run the default sweep and write charts, images and a Markdown page");
    std::string reportSpec, reportOut = "out";
    report->add_option("--spec", reportSpec, "benchmark spec (default assets/bench/default.json; quick.json on llvmpipe)");
    report->add_option("--out,-o", reportOut, "output folder (default out)");

    auto* tourCommand = cli.add_subcommand("tour", "render every step of a guided tour into index.html and README.md");
    std::string tourName;
    TourPageOptions tourPages;
    std::string tourOut;
    tourCommand->add_option("tour", tourName, "a built-in tour (assets/tours/<name>.json) or a tour file")->required();
    tourCommand->add_option("--out,-o", tourOut, "output folder")->required();
    tourCommand->add_option("--frames", tourPages.frames, "frames drawn before each step's image (default 3)")->check(CLI::Range(1, 1000));
    tourCommand->add_option("--bench-frames", tourPages.benchFrames, "timed frames of each technique (default 30)")
        ->check(CLI::Range(1, 100000));
    tourCommand->add_option("--warmup", tourPages.warmupFrames, "warm-up frames before them (default 5)")->check(CLI::Range(0, 100000));
    tourCommand->add_option("--samples", tourPages.referenceSamples, "soft reference: rays per pixel (default 256)")
        ->check(CLI::Range(1, 4096));

    auto* reloadLatency = cli.add_subcommand("reload-latency", "measure hot-reload latency of a plugin library");
    int reloadTrials = 10;
    reloadLatency->add_option("--trials", reloadTrials, "number of reloads (default 10)")->check(CLI::Range(1, 1000));

    auto* eval = cli.add_subcommand("eval", "accuracy against the ray-traced reference, with the frame timing of the same run");
    bool evalJson = false;
    int evalFrames = 50;
    eval->add_option("--reference", reference, "hard | soft | both | auto (default: hard for hard techniques, else both)");
    int evalSamples = BenchSpec{}.referenceSamples;
    std::string evalAdaptive = "on";
    eval->add_option("--samples", evalSamples, "soft reference: rays per pixel (default 1024)")->check(CLI::Range(1, 4096));
    eval->add_option("--reference-adaptive", evalAdaptive,
                     "soft reference: a first batch everywhere, all --samples rays only near penumbrae: on | off (default on)");
    eval->add_option("--frames", evalFrames, "timed frames (default 50)")->check(CLI::Range(1, 100000));
    eval->add_flag("--json", evalJson, "machine-readable output");

    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = cli.exit(e);
        return code == 0 ? 0 : kExitBadInput;
    }
    if (!common.budget.empty()) {
        SceneBudget budget = sceneBudget();
        std::string error;
        if (!parseSceneBudget(common.budget, budget, error)) return fail(error, kExitBadInput);
        setSceneBudget(budget);
    }

    if (*list) return commandList(listJson);
    if (*tourCommand) {
        tourPages.outDir = tourOut;
        return commandTour(common, tourName, tourPages);
    }
    if (*render)
        return commandRender(common, renderOut, renderView, renderFrames, reference, referenceSamples, renderCompare,
                             renderPathText, renderPathFrames, renderProbe);
    auto split = [](const std::string& text) {
        std::vector<std::string> items;
        std::stringstream in(text);
        std::string item;
        while (std::getline(in, item, ','))
            if (!item.empty()) items.push_back(item);
        return items;
    };
    if (*stress) {
        stressOptions.techniques = split(stressTechniques);
        stressOptions.cases = split(stressCases);
        stressOptions.sets = common.sets;
        stressOptions.outDir = stressOut;
        stressOptions.quiet = common.quiet;
        return commandStress(common, stressCasesFile, stressSize, stressOptions);
    }
    if (*bench && !benchPathText.empty()) {
        if (!benchSpecFile.empty()) return fail("--path: with the command line's lists, not --spec", kExitBadInput);
        if (!benchSweeps.empty()) return fail("--path: times one setting per technique (no --sweep)", kExitBadInput);
        std::string error;
        PathBenchOptions options;
        options.techniques = split(benchTechniques);
        options.scenes = split(benchScenes);
        options.sets = common.sets;
        options.path = benchPathText;
        options.frames = benchPathFrames;
        options.warmupFrames = benchSpec.warmupFrames;
        options.accuracy = benchSpec.accuracy;
        if (benchReference == "soft") options.reference = ReferenceOptions::Mode::Soft;
        else if (benchReference != "hard" && benchReference != "auto")
            return fail("--reference '" + benchReference + "': with --path, hard or soft", kExitBadInput);
        if (benchSizes.size() > 1) return fail("--path: one --size", kExitBadInput);
        CommonOptions pathCommon = common;
        if (!benchSizes.empty()) pathCommon.size = benchSizes.front();
        return commandBenchPath(pathCommon, options, benchOut);
    }
    if (*bench) {
        std::vector<BenchSpec> specs;
        std::string error;
        if (!parseOnOff(benchAdaptive, benchSpec.referenceAdaptive, error, "--reference-adaptive"))
            return fail(error, kExitBadInput);
        if (!benchSpecFile.empty()) {
            if (!loadBenchSpecs(benchSpecFile, specs, error)) return fail(error, kExitBadInput);
        } else {
            benchSpec.fromCommandLine = true;
            benchSpec.reference = benchReference;
            benchSpec.referenceSamples = benchSamples;
            benchSpec.techniques = split(benchTechniques);
            if (!benchScenes.empty()) benchSpec.scenes = split(benchScenes);
            for (const auto& sweep : benchSweeps)
                if (!addSweep(benchSpec, sweep, error)) return fail(error, kExitBadInput);
            if (!benchSizes.empty()) benchSpec.sizes.clear();
            for (const auto& text : benchSizes) {
                glm::ivec2 size;
                if (!parseSize(text, size, error, "--size")) return fail(error, kExitBadInput);
                benchSpec.sizes.push_back(size);
            }
            benchSpec.base = common.sets;
            specs.push_back(benchSpec);
        }
        return commandBench(common, specs, benchOut);
    }
    if (*reloadLatency) return commandReloadLatency(common, reloadTrials);
    if (*report) return commandReport(common, reportSpec, reportOut);
    if (*eval) {
        bool adaptive = true;
        std::string error;
        if (!parseOnOff(evalAdaptive, adaptive, error, "--reference-adaptive")) return fail(error, kExitBadInput);
        return commandEval(common, reference, evalSamples, adaptive, evalFrames, evalJson);
    }

    // The main job: the window. Without a display, --frames or --smoke-test draws it offscreen (a
    // slide from a machine without a screen); with neither, the report, unless a window option
    // says the window was meant.
    std::vector<std::string> windowFlags;
    for (const CLI::Option* option : cli.get_options())
        if (option->get_group() == "Window" && option->count() > 0) windowFlags.push_back(option->get_name());
    if (!window.screenshot.empty() && window.frames == 0 && window.smokeFrames == 0)
        return fail("--screenshot " + window.screenshot + ": needs --frames N (or --smoke-test N) to say when to take it",
                    kExitBadInput);
    if (window.frames > 0 && window.smokeFrames > 0) return fail("--frames and --smoke-test: give one of them", kExitBadInput);
    std::shared_ptr<const Tour> tour;
    if (int code = checkLessonOptions(window, tour)) return code;
    const bool display = common.backend.empty() ? defaultBackend() == BackendKind::Glfw : common.backend == "glfw";
    const bool drawnFrames = window.frames > 0 || window.smokeFrames > 0;
    if (!display && !drawnFrames) {
        if (!windowFlags.empty())
            return fail(windowFlags.front() + ": no display to open the window on; add --frames N --screenshot FILE to "
                        "draw it offscreen, or use `shadowlab render --compare A,B`",
                        kExitBadInput);
        if (!common.technique.empty() || !common.sets.empty())
            logWarning(std::string(common.technique.empty() ? "--set" : "--technique") +
                       ": no display, so the main job is the report of every technique; add --frames N --screenshot "
                       "FILE to draw the window offscreen instead");
        return commandReport(common, "", outDir);
    }
    App app;
    if (int code = startApp(app, common, display)) return code;
    std::string error;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    if (!app.techniques().find(technique)) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    InteractiveOptions options;
    if (int code = windowOptionsProblem(app, window, technique, options)) return code;
    options.tour = tour;
    options.tourStep = window.tourStep - 1;
    if (!display) logInfo("no display: drawing the window offscreen (" + std::string(backendName(app.backend().kind())) + ")");
    return app.runInteractive(options);
}

} // namespace

int main(int argc, char** argv) {
    // The last resort: every input is checked where it is read, but an exception that still
    // escapes is reported as an error naming what it says, never std::terminate (exit 134).
    int code = 0;
    try {
        code = run(argc, argv);
    } catch (const SceneError& e) {
        logError(e.what());
        code = kExitBadInput;
    } catch (const std::bad_alloc&) {
        logError("out of memory (lower the scene or output size, or the --budget; docs/scene-format.md, \"Limits\")");
        code = kExitFailure;
    } catch (const std::exception& e) {
        logError(std::string("unexpected error: ") + e.what());
        code = kExitBadInput;
    } catch (...) {
        logError("unexpected error (an exception of unknown type)");
        code = kExitBadInput;
    }
    // Output lost to a full disk or /dev/full is a failure, not a success.
    std::string error;
    if (!flushStandardOutput(error)) {
        std::fprintf(stderr, "shadowlab: %s\n", error.c_str());
        if (code == 0) code = kExitFailure;
    }
    return code;
}
