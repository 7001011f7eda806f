// shadowlab: command line. Each command sets up an App and runs one job:
//   shadowlab                 the main job: the window if a display exists, else renders every
//                             technique on the default scene to out/ and prints its timings
//   shadowlab list [--json]   techniques and their parameters (no GL needed)
//   shadowlab render ...      one frame headless to a PNG
// Exit codes: 0 success, 1 failure of the machine (no GL, ...), 2 bad input (with a message).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "util/strings.h"
#include "app.h"
#include "util/log.h"
#include "util/paths.h"

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
    float lightSize = -1.0f;
    int msaa = 0;
    bool quiet = false;
};

bool parseSize(const std::string& text, glm::ivec2& size, std::string& error) {
    int w = 0, h = 0;
    char x = 0, rest = 0;
    std::istringstream in(text);
    if (!(in >> w >> x >> h) || (x != 'x' && x != 'X') || (in >> rest) || w < 16 || h < 16 || w > 16384 || h > 16384) {
        error = "--size '" + text + "': expected WIDTHxHEIGHT between 16 and 16384, e.g. 1280x720";
        return false;
    }
    size = {w, h};
    return true;
}

bool parseVec3(const std::string& text, glm::vec3& v, std::string& error) {
    std::istringstream in(text);
    char c1 = 0, c2 = 0, rest = 0;
    if (!(in >> v.x >> c1 >> v.y >> c2 >> v.z) || c1 != ',' || c2 != ',' || (in >> rest) || glm::length(v) == 0.0f) {
        error = "--light-dir '" + text + "': expected three numbers x,y,z, not all zero";
        return false;
    }
    return true;
}

bool buildOptions(const CommonOptions& common, AppOptions& options, std::string& error) {
    options.scene = common.scene;
    options.msaaSamples = common.msaa;
    if (!parseSize(common.size, options.size, error)) return false;
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
    if (common.lightSize >= 0.0f) options.lightSize = common.lightSize;
    for (const auto& text : common.sceneParams) {
        const auto equals = text.find('=');
        try {
            if (equals == std::string::npos) throw std::invalid_argument("no =");
            size_t used = 0;
            const double value = std::stod(text.substr(equals + 1), &used);
            if (used != text.size() - equals - 1) throw std::invalid_argument("trailing");
            options.sceneParameters[text.substr(0, equals)] = value;
        } catch (const std::exception&) {
            error = "--scene-param '" + text + "': expected name=number";
            return false;
        }
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
    return 0;
}

int commandList(bool json) {
    PluginScan scan = scanPlugins(pluginDir());
    for (const auto& error : scan.errors) logWarning("skipped plugin: " + error);
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

ViewSelection parseView(const std::string& text) {
    if (text == "lit" || text.empty()) return {};
    if (text == "visibility") return {ViewSelection::Kind::Visibility, ""};
    return {ViewSelection::Kind::DebugImage, text};
}

int commandRender(const CommonOptions& common, const std::string& out, const std::string& view, int frames,
                  const std::string& reference, int samples) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    std::string error;
    if (!app.techniques().find(technique)) {
        std::string known;
        for (const auto& t : app.techniques().techniques()) appendListItem(known, t.id);
        return fail("--technique '" + technique + "': no such technique (available: " + known + ")", kExitBadInput);
    }
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
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
        Evaluation evaluation;
        if (!app.evaluate(options, evaluation, error)) return fail(error, kExitFailure);
        image = view == "error" ? evaluation.heatmap()
                                : visibilityImage(evaluation.reference, evaluation.mask, evaluation.width, evaluation.height);
    } else {
        if (!app.presentView(technique, parseView(view), ~0u, {}, error)) return fail(error, kExitBadInput);
        image = app.readDisplay();
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

int commandEval(const CommonOptions& common, const std::string& reference, int samples, int frames, bool json) {
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
    for (const auto mode : modes) {
        ReferenceOptions options;
        options.mode = mode;
        options.samplesPerPixel = samples;
        Evaluation evaluation;
        if (!app.evaluate(options, evaluation, error)) return fail(error, kExitFailure);
        const std::string name = mode == ReferenceOptions::Mode::Hard ? "hard" : "soft";
        out["accuracy"][name] = nlohmann::json::parse(metricsToJson(evaluation.metrics));
        out["accuracy"][name]["trace_seconds"] = evaluation.traceSeconds;
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
    for (const auto& [name, metrics] : out["accuracy"].items()) {
        std::printf("  vs %s reference: MAE %.4f  RMSE %.4f  false shadow %.3f%%  false light %.3f%%  "
                    "MAE penumbra %.4f  MAE elsewhere %.4f  compared %.1f%% of pixels\n",
                    name.c_str(), metrics["mae"].get<double>(), metrics["rmse"].get<double>(),
                    100.0 * metrics["falseShadowRate"].get<double>(), 100.0 * metrics["falseLightRate"].get<double>(),
                    metrics["maePenumbra"].get<double>(), metrics["maeOutsidePenumbra"].get<double>(),
                    100.0 * metrics["comparedFraction"].get<double>());
    }
    return 0;
}

// The main job without a display: every technique on the default scene, a PNG each and a table.
int commandShowcase(const CommonOptions& common, const std::string& outDir) {
    App app;
    if (int code = startApp(app, common, false)) return code;
    std::printf("scene %s (%zu triangles), %dx%d, %s\n", app.scene().name.c_str(), app.scene().triangleCount(),
                app.renderer().size().x, app.renderer().size().y, glRendererString().c_str());
    std::printf("%-16s %12s %12s %12s %12s %10s  %s\n", "technique", "GPU frame ms", "shadow ms", "main ms",
                "host CPU ms", "GPU MiB", "image");
    int failures = 0;
    for (const auto& info : app.techniques().techniques()) {
        std::string error;
        Measurement m;
        if (!app.applyAssignments(common.sets, info.id, error) || !app.measure(info.id, 5, 30, m, error) ||
            !app.presentView(info.id, {}, ~0u, {}, error)) {
            logError(info.id + ": " + error);
            ++failures;
            continue;
        }
        const std::string file = outDir + "/" + info.id + ".png";
        if (!writePng(file, app.readDisplay(), error)) {
            logError(error);
            ++failures;
            continue;
        }
        double shadowMs = 0.0;
        for (const auto& [pass, summary] : m.gpuMs)
            if (pass != "frame" && pass != "main") shadowMs += summary.median;
        std::printf("%-16s %12.3f %12.3f %12.3f %12.3f %10.2f  %s\n", info.id.c_str(), m.gpuMs["frame"].median, shadowMs,
                    m.gpuMs["main"].median, m.cpuMs.median, double(m.gpuBytes) / (1024.0 * 1024.0), file.c_str());
    }
    std::printf("medians of 30 frames after 5 warm-up frames; on llvmpipe (CPU) timings show relative cost only\n");
    return failures ? kExitFailure : 0;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App cli{"shadowlab: real-time shadow techniques as plugins, measured for speed and accuracy"};
    cli.fallthrough();
    cli.require_subcommand(0, 1);
    CommonOptions common;
    addCommonOptions(cli, common);
    int smokeFrames = 0;
    std::string screenshot, outDir = "out";
    cli.add_option("--smoke-test", smokeFrames, "window: draw N frames cycling every technique, then exit");
    cli.add_option("--screenshot", screenshot, "window: save a screenshot at the end of the smoke test");
    cli.add_option("--out-dir", outDir, "headless main job: folder for the PNG files (default out)");

    auto* list = cli.add_subcommand("list", "list techniques and their parameters");
    bool listJson = false;
    list->add_flag("--json", listJson, "machine-readable output");

    auto* render = cli.add_subcommand("render", "render one frame headless to a PNG file");
    std::string renderOut, renderView = "lit";
    int renderFrames = 3;
    render->add_option("--out,-o", renderOut, "PNG file to write")->required();
    render->add_option("--view", renderView,
                       "lit | visibility | error (heatmap vs the reference) | reference | a debug image (e.g. 'shadow map')");
    render->add_option("--frames", renderFrames, "frames to render before saving (default 3)")->check(CLI::Range(1, 10000));
    std::string reference = "auto";
    int referenceSamples = 64;
    render->add_option("--reference", reference, "--view error/reference: hard | soft (default hard)");
    render->add_option("--samples", referenceSamples, "soft reference: rays per pixel (default 64)")->check(CLI::Range(1, 4096));

    auto* eval = cli.add_subcommand("eval", "accuracy against the ray-traced reference, with the frame timing of the same run");
    bool evalJson = false;
    int evalFrames = 50;
    eval->add_option("--reference", reference, "hard | soft | both | auto (default: hard for hard techniques, else both)");
    eval->add_option("--samples", referenceSamples, "soft reference: rays per pixel (default 64)")->check(CLI::Range(1, 4096));
    eval->add_option("--frames", evalFrames, "timed frames (default 50)")->check(CLI::Range(1, 100000));
    eval->add_flag("--json", evalJson, "machine-readable output");

    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = cli.exit(e);
        return code == 0 ? 0 : kExitBadInput;
    }

    if (*list) return commandList(listJson);
    if (*render) return commandRender(common, renderOut, renderView, renderFrames, reference, referenceSamples);
    if (*eval) return commandEval(common, reference, referenceSamples, evalFrames, evalJson);

    // The main job.
    const bool windowed = common.backend.empty() ? defaultBackend() == BackendKind::Glfw : common.backend == "glfw";
    if (!windowed) return commandShowcase(common, outDir);
    App app;
    if (int code = startApp(app, common, true)) return code;
    std::string error;
    const std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    if (!app.techniques().find(technique)) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    return app.runInteractive(technique, smokeFrames, screenshot);
}
