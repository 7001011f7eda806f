// Benchmark sweeps (see bench.h).
#include "bench/bench.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>
#include <set>
#include <sstream>

#include "app.h"
#include "util/log.h"
#include "util/text_file.h"

namespace shadowlab {

extern const char* const kBuildCommit;

namespace {

std::string columnName(std::string text) {
    for (char& c : text)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return text;
}

std::string jsonValueText(const nlohmann::json& value) {
    return value.is_string() ? value.get<std::string>() : value.dump();
}

void addTiming(nlohmann::json& row, const Measurement& m) {
    double techniqueMs = 0.0;
    for (const auto& [pass, summary] : m.gpuMs) {
        const std::string name = "gpu_" + columnName(pass) + "_ms";
        row[name] = summary.median;
        row[name + "_p5"] = summary.p5;
        row[name + "_p95"] = summary.p95;
        if (pass != "frame" && pass != "main") techniqueMs += summary.median;
    }
    row["gpu_technique_ms"] = techniqueMs;   // every pass the technique marked, summed
    row["cpu_frame_ms"] = m.cpuMs.median;
    row["cpu_frame_ms_p5"] = m.cpuMs.p5;
    row["cpu_frame_ms_p95"] = m.cpuMs.p95;
    row["frames"] = m.frames;
}

} // namespace

std::string rowSettings(const nlohmann::json& row) {
    std::string text;
    for (const auto& [key, value] : row.items()) {
        if (key.rfind("param.", 0) != 0 && key.rfind("scene.", 0) != 0) continue;
        if (!text.empty()) text += ' ';
        text += key.substr(key.find('.') + 1) + "=" + jsonValueText(value);
    }
    return text;
}

void printBenchHeader() {
    std::printf("%-10s %-16s %-11s %12s %14s %10s %10s %10s  %s\n", "scene", "technique", "size", "GPU frame ms",
                "technique ms", "GPU MiB", "MAE hard", "MAE soft", "parameters");
}

void printBenchRow(const nlohmann::json& row) {
    auto mae = [&](const char* key) {
        char text[32] = "-";
        if (row.contains(key)) std::snprintf(text, sizeof(text), "%.4f", row[key].get<double>());
        return std::string(text);
    };
    const std::string size = std::to_string(row.value("width", 0)) + "x" + std::to_string(row.value("height", 0));
    std::printf("%-10s %-16s %-11s %12.3f %14.3f %10.2f %10s %10s  %s\n", row.value("scene", "").c_str(),
                row.value("technique", "").c_str(), size.c_str(), row.value("gpu_frame_ms", 0.0),
                row.value("gpu_technique_ms", 0.0), double(row.value("gpu_bytes", size_t(0))) / 1048576.0,
                mae("hard_mae").c_str(), mae("soft_mae").c_str(), rowSettings(row).c_str());
    std::fflush(stdout);
}

nlohmann::json benchEnvironment(App& app) {
    const auto now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    char date[32];
    std::strftime(date, sizeof(date), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    const auto* vendor = reinterpret_cast<const char*>(glGetString(GL_VENDOR));
    return {{"gpu", glRendererString()}, {"driver", glVersionString()}, {"vendor", vendor ? vendor : "unknown"},
            {"backend", app.backend().description()}, {"date", date}, {"commit", kBuildCommit}};
}

bool runBench(App& app, const BenchSpec& spec, std::vector<nlohmann::json>& rows, std::string& error,
              const std::function<void(const nlohmann::json&)>& onRow) {
    // Every value checked before the first frame; below, conversions cannot fail.
    if (!checkBenchSpec(spec, app.techniques().techniques(), error)) {
        error = "benchmark: " + error;
        return false;
    }
    const auto measured = benchTechniques(spec, app.techniques().techniques(), error);
    if (!measured) return false;
    const std::vector<const TechniqueInfo*>& techniques = *measured;
    auto number = [](const std::string& text) { return parseNumberText(text).value_or(0.0); };

    BenchSettingLists sceneLists;
    for (const auto& [key, values] : spec.sweeps)
        if (isSceneKey(key)) sceneLists.push_back({key, values});
    const nlohmann::json environment = benchEnvironment(app);
    ReferenceOptions::Mode modes[2] = {ReferenceOptions::Mode::Hard, ReferenceOptions::Mode::Soft};

    for (const auto& sceneName : spec.scenes) {
        for (const auto& sceneSettings : benchCombinations(sceneLists)) {
            std::map<std::string, double> overrides;
            for (const auto& [key, value] : sceneSettings) overrides[key.substr(6)] = number(value);
            if (!app.loadScene(sceneName, overrides, error)) return false;
            const LightInfo sceneLight = app.light();
            for (const glm::ivec2 size : spec.sizes) {
                if (!app.setRenderSize(size, error)) return false;
                nlohmann::json common = environment;
                if (!spec.tag.empty()) common["spec"] = spec.tag;
                common["scene"] = app.scene().name;
                common["triangles"] = app.scene().triangleCount();
                for (const auto& [key, value] : sceneSettings) common[key] = number(value);
                common["width"] = size.x;
                common["height"] = size.y;
                common["pixels"] = size.x * size.y;

                if (spec.depthFloor) {
                    std::vector<std::string> resolutions{"2048"};
                    if (auto it = spec.sweeps.find("resolution"); it != spec.sweeps.end()) resolutions = it->second;
                    for (const auto& resolution : resolutions) {
                        Measurement m;
                        app.light() = sceneLight;
                        const int pixels = static_cast<int>(number(resolution));
                        if (!app.measureDepthFloor(pixels, spec.warmupFrames, spec.frames, m, error)) return false;
                        nlohmann::json row = common;
                        row["technique"] = "depth-floor";
                        row["category"] = "floor";
                        row["param.resolution"] = pixels;
                        addTiming(row, m);
                        row["gpu_technique_ms"] = m.gpuMs["depth floor"].median;
                        rows.push_back(row);
                        if (onRow) onRow(row);
                    }
                }

                for (const TechniqueInfo* info : techniques) {
                    BenchSettingLists lists;
                    for (const auto& [key, values] : spec.sweeps)
                        if (isLightKey(key) || (!isSceneKey(key) && !benchParamFor(*info, key).empty())) lists.push_back({key, values});
                    for (const auto& settings : benchCombinations(lists)) {
                        app.params().resetToDefaults(*info);
                        app.light() = sceneLight;
                        std::vector<std::string> assignments;
                        for (const auto& text : spec.base) {
                            const std::string param = benchParamFor(*info, text.substr(0, text.find('=')));
                            if (!param.empty()) assignments.push_back(param + text.substr(text.find('=')));
                        }
                        for (const auto& [key, value] : settings) {
                            if (isLightKey(key)) {
                                const float v = static_cast<float>(number(value));
                                app.light().size = app.light().type == LightType::Directional ? glm::radians(v) : v;
                            } else {
                                assignments.push_back(benchParamFor(*info, key) + "=" + value);
                            }
                        }
                        if (!app.applyAssignments(assignments, info->id, error)) return false;
                        Measurement m;
                        if (!app.measure(info->id, spec.warmupFrames, spec.frames, m, error)) return false;
                        nlohmann::json row = common;
                        row["technique"] = info->id;
                        row["category"] = info->category;
                        const auto& values = app.params().values(*info);
                        for (size_t i = 0; i < info->params.size(); ++i)
                            row["param." + info->params[i].id] = formatParamValue(info->params[i], values[i]);
                        row["light_size"] = app.light().type == LightType::Directional ? glm::degrees(app.light().size)
                                                                                        : app.light().size;
                        addTiming(row, m);
                        row["gpu_bytes"] = m.gpuBytes;
                        LoadedTechnique* loaded = app.techniques().get(info->id, error);
                        if (loaded)
                            for (const auto& [name, value] : loaded->host().statistics()) row["stat." + columnName(name)] = value;
                        if (spec.accuracy) {
                            const bool hardOnly = spec.reference == "hard" ||
                                                  (spec.reference == "auto" && (info->category == "hard" || info->category == "baseline"));
                            const bool softOnly = spec.reference == "soft";
                            for (const auto mode : modes) {
                                if ((mode == ReferenceOptions::Mode::Soft && hardOnly) ||
                                    (mode == ReferenceOptions::Mode::Hard && softOnly))
                                    continue;
                                ReferenceOptions options;
                                options.mode = mode;
                                options.samplesPerPixel = spec.referenceSamples;
                                options.adaptive = spec.referenceAdaptive;
                                Evaluation evaluation;
                                if (!app.evaluate(options, evaluation, error)) return false;
                                const std::string prefix = mode == ReferenceOptions::Mode::Hard ? "hard_" : "soft_";
                                const AccuracyMetrics& a = evaluation.metrics;
                                row[prefix + "mae"] = a.mae;
                                row[prefix + "rmse"] = a.rmse;
                                row[prefix + "false_shadow"] = a.falseShadowRate;
                                row[prefix + "false_light"] = a.falseLightRate;
                                row[prefix + "mae_penumbra"] = a.maePenumbra;
                                row[prefix + "mae_outside_penumbra"] = a.maeOutsidePenumbra;
                                row[prefix + "compared_fraction"] = a.comparedFraction;
                                row[prefix + "noise"] = a.noiseEnergy;
                                row["technique_penumbra_fraction"] = a.techniquePenumbraFraction;
                                if (mode == ReferenceOptions::Mode::Soft) {
                                    // The soft reference's own error: soft figures (and differences
                                    // between them) below about 4x the floor are not resolved.
                                    const ReferenceStats& r = evaluation.referenceStats;
                                    row["soft_reference_rays"] = r.samplesPerPixel;
                                    row["soft_reference_adaptive"] = r.adaptive;
                                    row["soft_reference_floor"] = evaluation.referenceFloor;
                                    row["soft_reference_refined_fraction"] =
                                        r.tracedPixels ? double(r.refinedPixels) / double(r.tracedPixels) : 0.0;
                                }
                            }
                        }
                        rows.push_back(row);
                        if (onRow) onRow(row);
                    }
                }
            }
        }
    }
    return true;
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
