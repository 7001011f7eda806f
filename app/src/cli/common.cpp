// The options and checks every command shares (see cli.h).
#include "cli/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include <fcntl.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/accuracy_columns.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/report.h"
#include "bench/stress.h"
#include "groundtruth/reference_technique.h"
#include "plugin/assignments.h"
#include "render/render_limits.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "bench/tour_pages.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/video_export.h"
#include "util/strings.h"
#include "util/text_file.h"
#include "host_shared/translucent_layers_shared.h"

namespace shadowlab::cli {

namespace {

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

} // namespace

std::optional<double> lightSizeOption(const CommonOptions& common) {
    if (common.lightSize.empty()) return std::nullopt;
    return parseNumberText(common.lightSize);
}

bool buildOptions(const CommonOptions& common, AppOptions& options, std::string& error) {
    options.scene = common.scene;
    options.msaaSamples = common.msaa;
    if (!common.depthPrepass.empty()) {
        std::string problem;
        const auto mode = parseParamValue(*hostParams().findParam("depth_prepass"), common.depthPrepass, problem);
        if (!mode) {
            error = "--depth-prepass '" + common.depthPrepass + "': expected auto, on or off (or 1/0)";
            return false;
        }
        options.depthPrepass = DepthPrepassMode(int(*mode));
    }
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
    cmd.add_option("--depth-prepass", o.depthPrepass,
                   "auto (default) | on | off; alone: on. A depth-only pre-pass of the opaque surfaces, then the main pass "
                   "with depth test EQUAL: the shadow term runs once per visible pixel. auto turns it on where the "
                   "frame's depth complexity is high (host.depth_prepass; docs/benchmarks.md)")
        ->expected(0, 1)
        ->default_str("on")
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

int techniqueOptionsProblem(const std::string& technique, const std::vector<std::string>& sets) {
    const std::vector<TechniqueInfo> found = describedTechniques();
    if (found.size() <= 1) return 0;   // no plugins: startApp names the folder
    const std::string target = technique.empty() ? found.front().id : technique;
    if (std::none_of(found.begin(), found.end(), [&target](const TechniqueInfo& t) { return t.id == target; })) {
        std::string known;
        for (const TechniqueInfo& t : found) appendListItem(known, t.id);
        return fail("--technique '" + target + "': no such technique (available: " + known + ")", kExitBadInput);
    }
    ParamStore values;
    std::string error;
    if (!applyAssignments(values, found, sets, target, error)) return fail(error, kExitBadInput);
    return 0;
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
    // --compare B, or B,C[,D]: a grid of three or four with --technique as A.
    std::vector<std::string> others;
    if (std::string error; !w.compare.empty() && !splitList(w.compare, "--compare", others, error)) return fail(error, kExitBadInput);
    for (const std::string& id : others) {
        if (app.techniques().find(id)) continue;
        std::string known;
        for (const auto& t : app.techniques().techniques()) appendListItem(known, t.id);
        return fail("--compare '" + id + "': no such technique (available: " + known + ")", kExitBadInput);
    }
    if (others.size() > size_t(kMaxGridSides - 1))
        return fail("--compare '" + w.compare + "': at most three techniques beside --technique (a grid of four)", kExitBadInput);
    out.compareTechnique = others.empty() ? std::string() : others.front();
    if (others.size() > 1) out.gridTechniques.assign(others.begin() + 1, others.end());
    if (!parseCompareLayout(w.compareLayout, out.compareLayout))
        return fail("--compare-layout '" + w.compareLayout + "': expected side-by-side, wipe, difference or grid", kExitBadInput);
    if (others.size() > 1 && out.compareLayout != CompareLayout::Grid && out.compareLayout != CompareLayout::SideBySide)
        return fail("--compare-layout " + w.compareLayout + ": compares two techniques; three or four share the view as a grid",
                    kExitBadInput);
    if (others.size() > 1) out.compareLayout = CompareLayout::Grid;
    out.wipe = float(w.wipe);
    out.uiScale = float(w.uiScale);
    out.showUi = !w.hideUi;
    out.presenter = w.presenter;
    out.playPath = w.playPath;
    out.pathSpeed = float(w.pathSpeed);
    if (!w.exportFile.empty()) {
        if (w.frames <= 0)
            return fail("--export " + w.exportFile + ": records the frames of a run of --frames N (a tour step, a path)",
                        kExitBadInput);
        if (const std::string problem = exportProblem("--export", w.exportFile); !problem.empty()) return fail(problem, kExitBadInput);
        out.exportFile = w.exportFile;
    }
    out.measure = w.measure;
    if (w.measureReference != "auto" && w.measureReference != "hard" && w.measureReference != "soft")
        return fail("--measure-reference '" + w.measureReference + "': expected auto, hard or soft", kExitBadInput);
    out.referenceMode = w.measureReference == "hard" ? 1 : w.measureReference == "soft" ? 2 : 0;
    out.referenceSamples = w.measureSamples;
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
    PluginScan scan = scanPlugins(pluginDir(), {referenceDescriptor().id});
    scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));   // built into the host
    return scan.techniques;
}

// --reference: hard | soft | both | auto (hard for hard techniques, both for filtered and soft).
bool referenceModes(const std::string& text, const TechniqueInfo& info, std::vector<ReferenceOptions::Mode>& modes,
                    std::string& error) {
    if (referenceModesFor(text, info, modes)) return true;
    error = "--reference '" + text + "': expected hard, soft, both or auto";
    return false;
}

bool optionList(const std::string& text, const std::string& option, std::vector<std::string>& items, std::string& error) {
    items.clear();
    return text.empty() || splitList(text, option, items, error);
}

void requireNonEmptyValues(CLI::App& app) {
    const CLI::Validator nonEmpty(
        [](std::string& value) {
            return value.empty() ? std::string("an empty value (give a value, or leave the option out for its default)")
                                 : std::string();
        },
        "", "non-empty");
    for (CLI::Option* option : app.get_options())
        if (option->get_type_size_max() > 0 && option->get_name() != "--help") option->check(nonEmpty);
    for (CLI::App* sub : app.get_subcommands(std::function<bool(CLI::App*)>{})) requireNonEmptyValues(*sub);
}

int repeatedKeyProblem(const CommonOptions& common) {
    for (const auto& [option, values] : {std::pair{"--set", &common.sets}, std::pair{"--scene-param", &common.sceneParams}}) {
        std::set<std::string> keys;
        for (const std::string& text : *values) {
            const std::string key = text.substr(0, text.find('='));
            if (!keys.insert(key).second)
                return fail(std::string(option) + " " + key + "=...: the key is given twice (the last would win unseen)",
                            kExitBadInput);
        }
    }
    return 0;
}

int unusedOptionProblem(const CLI::App& parser, const std::string& command, const std::vector<Command::Unused>& unused) {
    for (const Command::Unused& u : unused) {
        const CLI::Option* option = parser.get_option_no_throw(u.option);
        if (option && option->count() > 0)
            return fail(u.option + ": `" + command + "` does not use it (" + u.instead + ")", kExitBadInput);
    }
    return 0;
}

bool outputProblem(const std::string& option, const std::filesystem::path& path, bool folder, std::string& error) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path dir = folder ? path : path.parent_path();
    if (!dir.empty()) fs::create_directories(dir, ec);
    if (!dir.empty() && !fs::is_directory(dir, ec)) {
        error = option + " " + path.string() + ": cannot create the folder " + dir.string() +
                (ec ? " (" + ec.message() + ")" : " (a file is in the way)");
        return false;
    }
    if (!folder && fs::is_directory(path, ec)) {
        error = option + " " + path.string() + ": a folder, expected a file";
        return false;
    }
    // Open for writing without truncating (an existing file keeps its content until the real
    // write; /dev/full opens, and its failure to write stays exit 1 when it happens); a new file
    // is created, then removed again.
    const fs::path probe = folder ? path / (".shadowlab-write-test-" + std::to_string(::getpid())) : path;
    const bool existed = !folder && fs::exists(path, ec);
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | O_NOCTTY | O_NONBLOCK, 0644);
    if (fd < 0) {
        error = option + " " + path.string() + ": cannot write " + (folder ? "in the folder" : "the file") + " (" +
                std::strerror(errno) + ")";
        return false;
    }
    ::close(fd);
    if (!existed) ::unlink(probe.c_str());
    return true;
}

} // namespace shadowlab::cli
