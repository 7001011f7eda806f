// Benchmark sweeps (see bench.h).
#include "bench/bench.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <set>
#include <memory>
#include <sstream>
#include <thread>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "app.h"
#include "bench/accuracy_columns.h"
#include "bench/path_run.h"
#include "util/progress.h"
#include "util/log.h"
#include "util/text_file.h"

namespace shadowlab {

extern const char* const kBuildCommit;

namespace {

TimingStop timingStopOf(const BenchSpec& spec) { return TimingStop{spec.minFrames, spec.stableWithin}; }

std::string columnName(std::string text) {
    for (char& c : text)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return text;
}

// The technique's own passes: every pass but the host's frame, main pass, depth pre-pass and
// eye-space blur (its term pass and the blur). The camera pre-pass counts: the technique asked for it.
// "translucent draws" (SHADOWLAB_EXT_TRANSLUCENT_DRAWS) is inside "main" and holds the technique's
// hooks: counted in main_ms, not twice.
bool isTechniquePass(const std::string& pass) {
    return pass != "frame" && pass != "main" && pass != "depth pre-pass" && pass != "eye blur term" && pass != "eye blur" &&
           pass != "translucent draws" && pass != "contact shadows" && pass != "contact pre-pass";
}

void addTiming(nlohmann::json& row, const Measurement& m) {
    double techniqueMs = 0.0;
    for (const auto& [pass, summary] : m.gpuMs) {
        const std::string name = "gpu_" + columnName(pass) + "_ms";
        row[name] = summary.median;
        row[name + "_p5"] = summary.p5;
        row[name + "_p95"] = summary.p95;
        if (isTechniquePass(pass)) techniqueMs += summary.median;
    }
    // The defined columns (docs/benchmarks.md, "Columns"): medians over the timed frames, which
    // write the colour target only.
    auto median = [&](const char* pass) {
        const auto it = m.gpuMs.find(pass);
        return it == m.gpuMs.end() ? 0.0 : it->second.median;
    };
    row["frame_ms"] = median("frame");
    row["main_ms"] = median("main");
    row["technique_passes_ms"] = techniqueMs;
    if (m.gpuMs.count("depth pre-pass")) row["depth_prepass_ms"] = median("depth pre-pass");
    if (m.gpuMs.count("eye blur")) row["eye_blur_ms"] = median("eye blur term") + median("eye blur");
    // Contact shadows' whole cost: the march, and the camera depth pre-pass where only it needed one.
    if (m.gpuMs.count("contact shadows")) row["contact_shadows_ms"] = median("contact shadows") + median("contact pre-pass");
    // Seed 001 sec. 5.3.1's "combined" time of composited translucent shadows: the technique's
    // passes plus the whole main pass, whose translucent loop holds its per-object passes.
    if (m.gpuMs.count("translucent draws")) row["translucent_draws_ms"] = median("translucent draws");
    row["cpu_frame_ms"] = m.cpuMs.median;
    row["cpu_frame_ms_p5"] = m.cpuMs.p5;
    row["cpu_frame_ms_p95"] = m.cpuMs.p95;
    row["cpu_wait_ms"] = m.cpuWaitMs.median;
    row["cpu_wait_ms_p95"] = m.cpuWaitMs.p95;
    row["cpu_wait_frames"] = m.framesWaited;
    row["frames"] = m.frames;
    if (std::isfinite(m.frameMedianHalfWidth)) row["frame_ms_ci95"] = m.frameMedianHalfWidth;
    if (m.stoppedHalfWidth) row["stopped_ci95"] = *m.stoppedHalfWidth;
    row["gbuffer_every_frame"] = false;
}

// What the host depth pre-pass did in the timed frames (issue 32): depth_prepass the decision
// taken (1: the timed frames ran it), depth_prepass_mode the setting (host.depth_prepass),
// depth_complexity the opaque fragments per pixel that auto decides from.
void addDepthPrepassColumns(nlohmann::json& row, const Measurement& m, DepthPrepassMode mode) {
    row["depth_prepass_mode"] = depthPrepassModeName(mode);
    row["depth_prepass"] = 2 * m.depthPrepassFrames > m.frames ? 1 : 0;
    if (m.depthComplexity) row["depth_complexity"] = *m.depthComplexity;
    if (m.depthPrepassFrames != 0 && m.depthPrepassFrames != m.frames) {
        // A still view should never switch (the rule's hysteresis); say so if it did.
        row["depth_prepass_frames"] = m.depthPrepassFrames;
        logWarning("bench: the depth pre-pass ran in " + std::to_string(m.depthPrepassFrames) + " of " +
                   std::to_string(m.frames) + " timed frames of this row");
    }
}

// One row to measure, planned before the first frame so progress can say "row N of M".
struct BenchJob {
    std::string scene;
    std::vector<BenchSetting> sceneSettings;
    glm::ivec2 size{0};
    const TechniqueInfo* technique = nullptr;   // nullptr: a depth-floor row
    std::vector<BenchSetting> settings;         // technique, light and host settings
    int depthFloorResolution = 0;
};

bool sameGroup(const BenchJob& a, const BenchJob& b) {
    return a.scene == b.scene && a.sceneSettings == b.sceneSettings && a.size == b.size;
}

} // namespace

std::string rowSettings(const nlohmann::json& row) {
    std::string text;
    for (const auto& [key, value] : row.items()) {
        if (key.rfind("param.", 0) != 0 && key.rfind("scene.", 0) != 0) continue;
        if (!text.empty()) text += ' ';
        text += key.substr(key.find('.') + 1) + "=" + specValueText(value);
    }
    return text;
}

void printBenchHeader() {
    std::printf("%-10s %-16s %-11s %9s %9s %11s %9s %9s %9s  %s\n", "scene", "technique", "size", "frame ms",
                "passes ms", "shadow term", "GPU MiB", "MAE hard", "MAE soft", "parameters");
}

void printBenchRow(const nlohmann::json& row) {
    auto mae = [&](const char* key) {
        char text[32] = "-";
        if (row.contains(key)) std::snprintf(text, sizeof(text), "%.4f", row[key].get<double>());
        return std::string(text);
    };
    const std::string size = std::to_string(row.value("width", 0)) + "x" + std::to_string(row.value("height", 0));
    char shadowTerm[32] = "-";
    if (row.contains("shadow_term_ms")) std::snprintf(shadowTerm, sizeof(shadowTerm), "%.3f", row["shadow_term_ms"].get<double>());
    std::printf("%-10s %-16s %-11s %9.3f %9.3f %11s %9.2f %9s %9s  %s\n", row.value("scene", "").c_str(),
                row.value("technique", "").c_str(), size.c_str(), row.value("frame_ms", 0.0),
                row.value("technique_passes_ms", 0.0), shadowTerm, double(row.value("gpu_bytes", size_t(0))) / 1048576.0,
                mae("hard_mae").c_str(), mae("soft_mae").c_str(), rowSettings(row).c_str());
    std::fflush(stdout);
}

nlohmann::json benchEnvironment(App& app) {
    const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    const auto* vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    return {{"gpu", glRendererString()}, {"driver", glVersionString()}, {"vendor", vendor ? vendor : "unknown"},
            {"backend", app.backend().description()}, {"date", date}, {"commit", kBuildCommit},
            {"reference_device", referenceDeviceName(app.referenceDevice())}};
}

// The plan: every row in order. Per scene, scene settings and size: the depth-floor rows, then
// `none` (the main-pass floor of every row after it), then the other techniques.
static std::vector<BenchJob> planBenchJobs(const BenchSpec& spec, const std::vector<const TechniqueInfo*>& measured,
                                           const TechniqueInfo* none) {
    auto number = [](const std::string& text) { return parseNumberText(text).value_or(0.0); };
    BenchSettingLists sceneLists;
    for (const auto& [key, values] : spec.sweeps)
        if (isSceneKey(key)) sceneLists.push_back({key, values});
    std::vector<const TechniqueInfo*> ordered;
    for (const TechniqueInfo* info : measured)
        if (info == none) ordered.push_back(info);
    for (const TechniqueInfo* info : measured)
        if (info != none) ordered.push_back(info);
    std::vector<BenchJob> jobs;
    for (const auto& sceneName : spec.scenes) {
        for (const auto& sceneSettings : benchCombinations(sceneLists)) {
            for (const glm::ivec2 size : spec.sizes) {
                BenchJob group;
                group.scene = sceneName;
                group.sceneSettings = sceneSettings;
                group.size = size;
                if (spec.depthFloor) {
                    std::vector<std::string> resolutions{"2048"};
                    if (auto it = spec.sweeps.find("resolution"); it != spec.sweeps.end()) resolutions = it->second;
                    for (const auto& resolution : resolutions) {
                        BenchJob job = group;
                        job.depthFloorResolution = static_cast<int>(number(resolution));
                        jobs.push_back(job);
                    }
                }
                for (const TechniqueInfo* info : ordered) {
                    BenchSettingLists lists;
                    bool swept = false;
                    for (const auto& [key, values] : spec.sweeps)
                        if (isLightKey(key) || isHostKey(key) || (!isSceneKey(key) && !benchParamFor(*info, key).empty())) {
                            lists.push_back({key, values});
                            swept = swept || (!isLightKey(key) && !isHostKey(key));
                        }
                    if (spec.sweptOnly && !swept && info != none) continue;
                    for (const auto& settings : benchCombinations(lists)) {
                        BenchJob job = group;
                        job.technique = info;
                        job.settings = settings;
                        jobs.push_back(job);
                    }
                }
            }
        }
    }
    return jobs;
}

// The first row of a group (scene, scene settings, size): the scene loaded with its settings, the
// render size set, and the columns every row of the group shares.
static bool startBenchGroup(App& app, const BenchSpec& spec, const BenchJob& job, const nlohmann::json& environment,
                            nlohmann::json& common, LightInfo& sceneLight, std::string& error) {
    auto number = [](const std::string& text) { return parseNumberText(text).value_or(0.0); };
    std::map<std::string, double> overrides;
    for (const auto& [key, value] : job.sceneSettings) overrides[key.substr(6)] = number(value);
    if (!app.loadScene(job.scene, overrides, error)) return false;
    sceneLight = app.light();
    if (!app.setRenderSize(job.size, error)) return false;
    common = environment;
    if (!spec.tag.empty()) common["spec"] = spec.tag;
    common["scene"] = app.scene().name;
    common["triangles"] = app.scene().triangleCount();
    for (const auto& [key, value] : job.sceneSettings) common[key] = number(value);
    common["width"] = job.size.x;
    common["height"] = job.size.y;
    common["pixels"] = job.size.x * job.size.y;
    return true;
}

// A depth-floor row: a bare depth-only pass at `resolution`, the floor of every shadow pass.
static bool addDepthFloorRow(App& app, const BenchSpec& spec, int resolution, nlohmann::json& row,
                             std::map<int, double>& depthFloor, std::string& error) {
    Measurement m;
    if (!app.measureDepthFloor(resolution, spec.warmupFrames, spec.frames, m, error)) return false;
    row["technique"] = "depth-floor";
    row["category"] = "floor";
    row["param.resolution"] = resolution;
    addTiming(row, m);
    row["technique_passes_ms"] = depthFloor[resolution] = m.gpuMs["depth floor"].median;
    return true;
}

// The ground-truth columns of a row (spec.accuracy), GL half: the last timed frame re-rendered
// untimed with the accuracy targets (App::captureEvaluation; the measure() before had the lit
// colour only). The CPU half (evaluateAccuracy) measures it against each reference mode and
// translucency model asked for, by the functions eval --json uses too (bench/accuracy_columns.h).
static bool captureRowAccuracy(App& app, const BenchSpec& spec, const TechniqueInfo* info, const LightInfo& rowLight,
                               AccuracyRequest& request, AccuracyCapture& capture, nlohmann::json& row, std::string& error) {
    app.light() = rowLight;
    if (!referenceModesFor(spec.reference, *info, request.modes)) {
        error = "reference '" + spec.reference + "': expected hard, soft, both or auto";
        return false;
    }
    request.samples = spec.referenceSamples;
    request.adaptive = spec.referenceAdaptive;
    request.contactBand = spec.contactBand;
    return captureAccuracy(app, *info, capture, row, error);
}

// A row whose evaluation (the reference traced, the metrics) runs on a worker thread while the GL
// thread times the next row (issue 32: on the H200 the main job's evaluations were a third of its
// sweep). The worker runs at a lower priority (nice 10) with the reference's threads one fewer
// than the cores, so the GL thread that submits timed frames is never starved; the figures are
// those of a serial run (the trace and the metrics are deterministic on any thread count; test
// BenchOverlap). It is joined before the next row completes, before a scene is loaded and when
// the sweep ends or fails, so rows come out in order and nothing outlives what it reads.
class PendingEvaluation {
public:
    PendingEvaluation(App& app, const TechniqueInfo& info, nlohmann::json row, AccuracyRequest request,
                      AccuracyCapture capture, bool keepEvaluations)
        : info_(info), row_(std::move(row)), request_(std::move(request)), capture_(std::move(capture)) {
        worker_ = std::thread([this, &app, keepEvaluations] {
            setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
            ok_ = evaluateAccuracy(app, request_, capture_, row_, error_, [&](const AccuracyPass& pass, const Evaluation& e) {
                if (keepEvaluations) evaluations_.emplace_back(pass, e);
            });
        });
    }
    ~PendingEvaluation() { join(); }
    PendingEvaluation(const PendingEvaluation&) = delete;
    PendingEvaluation& operator=(const PendingEvaluation&) = delete;
    void join() {
        if (worker_.joinable()) worker_.join();
    }
    // After join(): the row with its accuracy columns, each evaluation shown to `hook`.
    bool finish(nlohmann::json& row, std::string& error, const BenchEvaluationHook& hook) {
        join();
        if (!ok_) {
            error = error_;
            return false;
        }
        for (const auto& [pass, evaluation] : evaluations_)
            if (hook) hook(info_, pass, evaluation);
        row = std::move(row_);
        return true;
    }

private:
    const TechniqueInfo& info_;
    nlohmann::json row_;
    AccuracyRequest request_;
    AccuracyCapture capture_;
    std::vector<std::pair<AccuracyPass, Evaluation>> evaluations_;
    std::string error_;
    bool ok_ = false;
    std::thread worker_;
};

// A row's settings on top of the technique's defaults: the spec's base, then the row's sweep values
// (light size, host passes, the technique's parameters).
static bool applyRowSettings(App& app, const BenchSpec& spec, const BenchJob& job, const LightInfo& sceneLight,
                             const std::vector<double>& savedHost, std::string& error) {
    const TechniqueInfo* info = job.technique;
    app.params().resetToDefaults(*info);
    app.light() = sceneLight;
    app.params().values(hostParams()) = savedHost;   // each row's host.* from the command, then its sweep
    std::vector<std::string> assignments;
    for (const auto& text : spec.base) {
        const std::string param = benchParamFor(*info, text.substr(0, text.find('=')));
        if (!param.empty()) assignments.push_back(param + text.substr(text.find('=')));
    }
    for (const auto& [key, value] : job.settings) {
        if (isLightKey(key)) {
            const float v = static_cast<float>(parseNumberText(value).value_or(0.0));
            app.light().size = app.light().type == LightType::Directional ? glm::radians(v) : v;
        } else if (isHostKey(key)) {
            assignments.push_back(key + "=" + value);   // host.depth_prepass, host.shadow_blur, ... (plugin/host_params.h)
        } else {
            assignments.push_back(benchParamFor(*info, key) + "=" + value);
        }
    }
    return app.applyAssignments(assignments, info->id, error);
}

namespace {

// One sweep's state: the floors measured so far in the group, the row whose evaluation is still
// running, the progress line.
class BenchRun {
public:
    BenchRun(App& app, const BenchSpec& spec, std::vector<nlohmann::json>& rows, const BenchHooks& hooks, size_t jobs)
        : app_(app), spec_(spec), rows_(rows), hooks_(hooks), jobs_(jobs), none_(app.techniques().find("none")),
          environment_(benchEnvironment(app)), savedHost_(app.hostValues()), rowsBefore_(rows.size()) {}
    ~BenchRun() { app_.params().values(hostParams()) = savedHost_; }   // host.* sweeps change them per row

    bool run(const std::vector<BenchJob>& jobs, std::string& error) {
        for (size_t index = 0; index < jobs.size(); ++index) {
            const BenchJob& job = jobs[index];
            if (index == 0 || !sameGroup(job, jobs[index - 1])) {
                if (!finishPending(error)) return false;   // its trace reads the scene about to change
                if (!startBenchGroup(app_, spec_, job, environment_, common_, sceneLight_, error)) return false;
                mainFloor_.clear();
                depthFloor_.clear();
            }
            if (!measureRow(job, error)) {
                std::string pendingError;
                finishPending(pendingError);   // the rows finished before a failure or Ctrl-C are kept
                return false;
            }
        }
        return finishPending(error);
    }

private:
    bool measureRow(const BenchJob& job, std::string& error) {
        nlohmann::json row = common_;
        rowStart_ = std::chrono::steady_clock::now();
        if (!job.technique) {
            app_.light() = sceneLight_;
            return addDepthFloorRow(app_, spec_, job.depthFloorResolution, row, depthFloor_, error) &&
                   finishPending(error) && completeRow(row);
        }
        const TechniqueInfo* info = job.technique;
        if (!applyRowSettings(app_, spec_, job, sceneLight_, savedHost_, error)) return false;
        const LightInfo rowLight = app_.light();
        if (!timeTechnique(*info, rowLight, row, error)) return false;
        if (!spec_.accuracy) return finishPending(error) && completeRow(row);

        AccuracyRequest request;
        AccuracyCapture capture;
        if (!captureRowAccuracy(app_, spec_, info, rowLight, request, capture, row, error)) return false;
        const bool keep = hooks_.onCapture && hooks_.onCapture(*info);   // the report's images: the row's frame
        // With the GPU tracer the evaluation must stay on the GL thread.
        const bool overlap = spec_.overlapAccuracy && app_.referenceDevice() == ReferenceDevice::Cpu;
        request.threads = overlap ? int(std::max(1u, std::thread::hardware_concurrency() - 1)) : 0;
        row["seconds_row"] = secondsSince(rowStart_);
        if (!finishPending(error)) return false;
        pending_ = std::make_unique<PendingEvaluation>(app_, *info, std::move(row), std::move(request), std::move(capture), keep);
        return overlap || finishPending(error, true);
    }

    // The timed frames of a row and the columns they give: floors, passes, memory, statistics.
    bool timeTechnique(const TechniqueInfo& info, const LightInfo& rowLight, nlohmann::json& row, std::string& error) {
        // The main-pass floor: `none` in the same view, light and pre-pass setting, this run.
        const std::pair<int, int> floorKey{int(std::lround(rowLight.size * 1e6f)), int(app_.depthPrepassMode())};
        const auto floorsStart = std::chrono::steady_clock::now();
        if (!mainFloor_.count(floorKey) && none_ && &info != none_) {
            Measurement floor;
            app_.params().resetToDefaults(*none_);
            if (!app_.measure(none_->id, spec_.warmupFrames, spec_.frames, floor, error, timingStopOf(spec_))) return false;
            mainFloor_[floorKey] = floor.gpuMs["main"].median;
        }
        Measurement m;
        const auto measureStart = std::chrono::steady_clock::now();
        if (!app_.measure(info.id, spec_.warmupFrames, spec_.frames, m, error, timingStopOf(spec_))) return false;
        row["seconds_timed_frames"] = secondsSince(measureStart);
        if (&info == none_ && !mainFloor_.count(floorKey)) mainFloor_[floorKey] = m.gpuMs["main"].median;
        row["technique"] = info.id;
        row["category"] = info.category;
        const auto& values = app_.params().values(info);
        for (size_t i = 0; i < info.params.size(); ++i)
            row["param." + info.params[i].id] = formatParamValue(info.params[i], values[i]);
        row["light_size"] = rowLight.type == LightType::Directional ? glm::degrees(rowLight.size) : rowLight.size;
        addDepthPrepassColumns(row, m, app_.depthPrepassMode());
        for (size_t i = 0; i < hostParams().params.size(); ++i)   // depth_prepass: depth_prepass_mode
            if (i != kHostDepthPrepass)
                row["host." + hostParams().params[i].id] = formatParamValue(hostParams().params[i], app_.hostValues()[i]);
        addTiming(row, m);
        if (mainFloor_.count(floorKey)) {
            row["floor_main_ms"] = mainFloor_[floorKey];
            row["shadow_term_ms"] = row["main_ms"].get<double>() - mainFloor_[floorKey];
        }
        if (const int p = info.paramIndex("resolution"); p >= 0) {
            double floorMs = 0.0;
            if (!measureDepthFloor(static_cast<int>(values[size_t(p)]), floorMs, error)) return false;
            row["floor_depth_ms"] = floorMs;
        }
        row["seconds_floors"] = secondsSince(floorsStart) - row["seconds_timed_frames"].get<double>();
        row["gpu_bytes"] = m.gpuBytes;
        if (LoadedTechnique* loaded = app_.techniques().get(info.id, error))
            for (const auto& [name, value] : loaded->host().statistics()) row["stat." + columnName(name)] = value;
        return true;
    }

    // Floors are measured once per group, when first needed, with the row's warm-up and frames.
    bool measureDepthFloor(int resolution, double& ms, std::string& error) {
        if (auto it = depthFloor_.find(resolution); it != depthFloor_.end()) {
            ms = it->second;
            return true;
        }
        Measurement m;
        const LightInfo rowLight = app_.light();
        app_.light() = sceneLight_;
        const bool ok = app_.measureDepthFloor(resolution, spec_.warmupFrames, spec_.frames, m, error);
        app_.light() = rowLight;
        if (!ok) return false;
        ms = depthFloor_[resolution] = m.gpuMs["depth floor"].median;
        return true;
    }

    // `timeRow`: the row evaluated on the GL thread, whose wall time includes its evaluation.
    bool finishPending(std::string& error, bool timeRow = false) {
        if (!pending_) return true;
        nlohmann::json row;
        const bool ok = pending_->finish(row, error, hooks_.onEvaluation);
        pending_.reset();
        return ok && completeRow(row, timeRow);
    }

    bool completeRow(nlohmann::json& row, bool timeRow = true) {
        if (timeRow) row["seconds_row"] = secondsSince(rowStart_);
        rows_.push_back(row);
        const size_t done = rows_.size() - rowsBefore_;   // rows_ may hold earlier specs' rows
        const double elapsed = secondsSince(started_);
        const double left = elapsed / double(done) * double(jobs_ - std::min(jobs_, done));
        std::fprintf(stderr, "bench: row %zu of %zu, %s elapsed, about %s left\n", done, jobs_,
                     durationText(elapsed).c_str(), durationText(left).c_str());
        if (hooks_.onRow) hooks_.onRow(row);
        return true;
    }

    static double secondsSince(std::chrono::steady_clock::time_point t) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    }

    App& app_;
    const BenchSpec& spec_;
    std::vector<nlohmann::json>& rows_;
    const BenchHooks& hooks_;
    const size_t jobs_;
    const TechniqueInfo* none_;
    const nlohmann::json environment_;
    const std::vector<double> savedHost_;
    const size_t rowsBefore_;
    const std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
    std::chrono::steady_clock::time_point rowStart_;
    LightInfo sceneLight_;
    nlohmann::json common_;
    // none's main pass by (light size x 1e6, pre-pass mode: auto decides alike for every technique
    // of a group, whose scene, view and size are the same)
    std::map<std::pair<int, int>, double> mainFloor_;
    std::map<int, double> depthFloor_;   // bare depth pass ms by resolution
    std::unique_ptr<PendingEvaluation> pending_;
};

} // namespace

// A group with "path": `bench --path` per technique and combination of the parameters it declares,
// the rows tagged with the group ("spec") and the combination ("param.<key>"). Seed 000 sec. 4.3.2
// calls adaptive PCF's speed view dependent; one view per row cannot show that, a path can.
static bool runBenchPathGroup(App& app, const BenchSpec& spec, const std::vector<const TechniqueInfo*>& measured,
                              std::vector<nlohmann::json>& rows, std::string& error,
                              const std::function<void(const nlohmann::json&)>& onRow) {
    if (!app.setRenderSize(spec.sizes.front(), error)) return false;
    for (const TechniqueInfo* info : measured) {
        BenchSettingLists lists;
        for (const auto& [key, values] : spec.sweeps)
            if (!benchParamFor(*info, key).empty()) lists.emplace_back(key, values);
        for (const auto& settings : benchCombinations(lists)) {
            PathBenchOptions options;
            options.techniques = {info->id};
            options.scenes = spec.scenes;
            options.path = spec.path;
            options.frames = spec.pathFrames;
            options.warmupFrames = spec.warmupFrames;
            options.accuracy = spec.accuracy;   // reference: hard or soft (checkBenchSpec)
            options.reference = spec.reference == "soft" ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
            for (const auto& text : spec.base) {
                const std::string param = benchParamFor(*info, text.substr(0, text.find('=')));
                if (!param.empty()) options.sets.push_back(param + text.substr(text.find('=')));
            }
            for (const auto& [key, value] : settings) options.sets.push_back(benchParamFor(*info, key) + "=" + value);
            std::vector<nlohmann::json> measuredRows;
            auto tagged = [&](const nlohmann::json& row) {
                nlohmann::json out = row;
                if (!spec.tag.empty()) out["spec"] = spec.tag;
                for (const auto& [key, value] : settings) out["param." + benchParamFor(*info, key)] = value;
                rows.push_back(out);
                if (onRow) onRow(out);
            };
            if (benchPath(app, options, measuredRows, tagged, error) != 0) return false;
        }
    }
    // The next group starts from the scene's own view, not the path's last frame.
    app.camera().reset(app.scene().camera);
    return true;
}

bool runBench(App& app, const BenchSpec& spec, std::vector<nlohmann::json>& rows, std::string& error,
              const std::function<void(const nlohmann::json&)>& onRow, const BenchHooks& images) {
    // Every value checked before the first frame; below, conversions cannot fail.
    if (!checkBenchSpec(spec, app.techniques().techniques(), error)) {
        error = "benchmark: " + error;
        return false;
    }
    if (!spec.path.empty()) {
        const auto techniques = benchTechniques(spec, app.techniques().techniques(), error);
        return techniques && runBenchPathGroup(app, spec, *techniques, rows, error, onRow);
    }
    const auto measured = benchTechniques(spec, app.techniques().techniques(), error);
    if (!measured) return false;
    const std::vector<BenchJob> jobs = planBenchJobs(spec, *measured, app.techniques().find("none"));
    BenchHooks hooks = images;
    hooks.onRow = onRow;
    BenchRun run(app, spec, rows, hooks, jobs.size());
    return run.run(jobs, error);
}

bool writeBenchResults(const std::filesystem::path& file, const std::vector<nlohmann::json>& rows, std::string& error) {
    std::ostringstream out;
    if (file.extension() != ".csv") {
        out << nlohmann::json(rows).dump(1) << "\n";
    } else {
        std::vector<std::string> columns;
        std::set<std::string> seen;
        for (const auto& row : rows)
            for (const auto& [key, value] : row.items())
                if (seen.insert(key).second) columns.push_back(key);
        auto cell = [](const nlohmann::json& value) {
            std::string text = value.is_string() ? value.get<std::string>() : value.dump();
            if (text.find_first_of(",\"\n") != std::string::npos) {
                std::string quoted = "\"";
                for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
                return quoted + "\"";
            }
            return text;
        };
        for (size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i];
        out << "\n";
        for (const auto& row : rows) {
            for (size_t i = 0; i < columns.size(); ++i) {
                if (i) out << ",";
                if (row.contains(columns[i])) out << cell(row[columns[i]]);
            }
            out << "\n";
        }
    }
    // Every byte checked: a full disk (or /dev/full) is an error, not a results file that is not there.
    if (!writeWholeFile(file, out.str(), error)) {
        error += " (results)";
        return false;
    }
    return true;
}

} // namespace shadowlab
