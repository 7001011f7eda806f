// Benchmark sweeps (see bench.h).
#include "bench/bench.h"

#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include "app.h"
#include "util/log.h"

namespace shadowlab {

extern const char* const kBuildCommit;

namespace {

using Setting = std::pair<std::string, std::string>;
using SettingList = std::vector<std::pair<std::string, std::vector<std::string>>>;

bool isSceneKey(const std::string& key) { return key.rfind("scene.", 0) == 0; }
bool isLightKey(const std::string& key) { return key == "light.size"; }

// The parameter id `key` names for `info`: "resolution" if it declares it, "pcf.kernel" for pcf.
std::string paramFor(const TechniqueInfo& info, const std::string& key) {
    if (const auto dot = key.find('.'); dot != std::string::npos)
        return key.substr(0, dot) == info.id && info.findParam(key.substr(dot + 1)) ? key.substr(dot + 1) : "";
    return info.findParam(key) ? key : "";
}

std::vector<std::vector<Setting>> cartesian(const SettingList& lists) {
    std::vector<std::vector<Setting>> out{{}};
    for (const auto& [key, values] : lists) {
        std::vector<std::vector<Setting>> next;
        for (const auto& partial : out)
            for (const auto& value : values) {
                auto combination = partial;
                combination.push_back({key, value});
                next.push_back(std::move(combination));
            }
        out = std::move(next);
    }
    return out;
}

std::string columnName(std::string text) {
    for (char& c : text)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return text;
}

bool parseSize(const std::string& text, glm::ivec2& size) {
    char x = 0;
    std::istringstream in(text);
    return bool(in >> size.x >> x >> size.y) && (x == 'x' || x == 'X') && size.x >= 16 && size.y >= 16;
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

bool addSweep(BenchSpec& spec, const std::string& text, std::string& error) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
        error = "--sweep '" + text + "': expected key=value1,value2,...";
        return false;
    }
    std::vector<std::string> values;
    std::stringstream in(text.substr(equals + 1));
    std::string value;
    while (std::getline(in, value, ','))
        if (!value.empty()) values.push_back(value);
    spec.sweeps[text.substr(0, equals)] = values;
    return true;
}

bool parseBenchSpec(const nlohmann::json& json, BenchSpec& spec, std::string& error) {
    static const std::set<std::string> known{"techniques", "scenes", "sizes", "sweep", "base", "frames", "warmup",
                                             "accuracy", "reference", "referenceSamples", "depthFloor", "description", "tag"};
    if (!json.is_object()) {
        error = "a benchmark spec is a JSON object";
        return false;
    }
    try {
        for (const auto& [key, value] : json.items())
            if (!known.count(key)) {
                error = "unknown field '" + key + "'";
                return false;
            }
        if (json.contains("techniques")) spec.techniques = json["techniques"].get<std::vector<std::string>>();
        if (json.contains("scenes")) spec.scenes = json["scenes"].get<std::vector<std::string>>();
        if (json.contains("sizes")) {
            spec.sizes.clear();
            for (const auto& text : json["sizes"].get<std::vector<std::string>>()) {
                glm::ivec2 size;
                if (!parseSize(text, size)) {
                    error = "sizes: '" + text + "' is not WIDTHxHEIGHT";
                    return false;
                }
                spec.sizes.push_back(size);
            }
        }
        if (json.contains("sweep"))
            for (const auto& [key, values] : json["sweep"].items()) {
                if (!values.is_array() || values.empty()) {
                    error = "sweep." + key + ": expected a non-empty array";
                    return false;
                }
                auto& list = spec.sweeps[key];
                for (const auto& v : values) list.push_back(jsonValueText(v));
            }
        if (json.contains("base"))
            for (const auto& [key, value] : json["base"].items()) spec.base.push_back(key + "=" + jsonValueText(value));
        spec.frames = json.value("frames", spec.frames);
        spec.warmupFrames = json.value("warmup", spec.warmupFrames);
        spec.accuracy = json.value("accuracy", spec.accuracy);
        spec.reference = json.value("reference", spec.reference);
        spec.referenceSamples = json.value("referenceSamples", spec.referenceSamples);
        spec.depthFloor = json.value("depthFloor", spec.depthFloor);
        spec.tag = json.value("tag", spec.tag);
    } catch (const nlohmann::json::exception& e) {
        error = std::string("wrong type: ") + e.what();
        return false;
    }
    if (spec.frames < 1 || spec.warmupFrames < 0) {
        error = "frames must be >= 1 and warmup >= 0";
        return false;
    }
    return true;
}

bool loadBenchSpec(const std::filesystem::path& file, BenchSpec& spec, std::string& error) {
    std::ifstream in(file);
    if (!in) {
        error = file.string() + ": cannot open benchmark spec";
        return false;
    }
    try {
        const auto json = nlohmann::json::parse(in);
        if (!parseBenchSpec(json, spec, error)) {
            error = file.string() + ": " + error;
            return false;
        }
    } catch (const nlohmann::json::parse_error& e) {
        error = file.string() + ": JSON syntax error: " + e.what();
        return false;
    }
    return true;
}

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
    std::vector<const TechniqueInfo*> techniques;
    if (spec.techniques.empty()) {
        for (const auto& t : app.techniques().techniques())
            if (t.category != "reference") techniques.push_back(&t);
    } else {
        for (const auto& id : spec.techniques) {
            const TechniqueInfo* info = app.techniques().find(id);
            if (!info) {
                error = "benchmark: no technique '" + id + "'";
                return false;
            }
            techniques.push_back(info);
        }
    }
    // Every key must mean something, so a typo fails loudly instead of sweeping nothing.
    std::vector<std::string> keys;
    for (const auto& [key, values] : spec.sweeps) keys.push_back(key);
    for (const auto& text : spec.base) keys.push_back(text.substr(0, text.find('=')));
    for (const auto& key : keys) {
        if (isSceneKey(key) || isLightKey(key)) continue;
        bool used = false;
        for (const auto* t : techniques) used |= !paramFor(*t, key).empty();
        if (!used) {
            error = "benchmark: '" + key + "' is no parameter of the techniques measured (nor scene.*, light.size)";
            return false;
        }
    }

    SettingList sceneLists;
    for (const auto& [key, values] : spec.sweeps)
        if (isSceneKey(key)) sceneLists.push_back({key, values});
    const nlohmann::json environment = benchEnvironment(app);
    ReferenceOptions::Mode modes[2] = {ReferenceOptions::Mode::Hard, ReferenceOptions::Mode::Soft};

    for (const auto& sceneName : spec.scenes) {
        for (const auto& sceneSettings : cartesian(sceneLists)) {
            std::map<std::string, double> overrides;
            for (const auto& [key, value] : sceneSettings) {
                try {
                    overrides[key.substr(6)] = std::stod(value);
                } catch (const std::exception&) {
                    error = "benchmark: " + key + "=" + value + " is not a number";
                    return false;
                }
            }
            if (!app.loadScene(sceneName, overrides, error)) return false;
            const LightInfo sceneLight = app.light();
            for (const glm::ivec2 size : spec.sizes) {
                if (!app.setRenderSize(size, error)) return false;
                nlohmann::json common = environment;
                if (!spec.tag.empty()) common["spec"] = spec.tag;
                common["scene"] = app.scene().name;
                common["triangles"] = app.scene().triangleCount();
                for (const auto& [key, value] : sceneSettings) common[key] = std::stod(value);
                common["width"] = size.x;
                common["height"] = size.y;
                common["pixels"] = size.x * size.y;

                if (spec.depthFloor) {
                    std::vector<std::string> resolutions{"2048"};
                    if (auto it = spec.sweeps.find("resolution"); it != spec.sweeps.end()) resolutions = it->second;
                    for (const auto& resolution : resolutions) {
                        Measurement m;
                        app.light() = sceneLight;
                        if (!app.measureDepthFloor(std::stoi(resolution), spec.warmupFrames, spec.frames, m, error)) return false;
                        nlohmann::json row = common;
                        row["technique"] = "depth-floor";
                        row["category"] = "floor";
                        row["param.resolution"] = std::stoi(resolution);
                        addTiming(row, m);
                        row["gpu_technique_ms"] = m.gpuMs["depth floor"].median;
                        rows.push_back(row);
                        if (onRow) onRow(row);
                    }
                }

                for (const TechniqueInfo* info : techniques) {
                    SettingList lists;
                    for (const auto& [key, values] : spec.sweeps)
                        if (isLightKey(key) || (!isSceneKey(key) && !paramFor(*info, key).empty())) lists.push_back({key, values});
                    for (const auto& settings : cartesian(lists)) {
                        app.params().resetToDefaults(*info);
                        app.light() = sceneLight;
                        std::vector<std::string> assignments;
                        for (const auto& text : spec.base) {
                            const std::string param = paramFor(*info, text.substr(0, text.find('=')));
                            if (!param.empty()) assignments.push_back(param + text.substr(text.find('=')));
                        }
                        for (const auto& [key, value] : settings) {
                            if (isLightKey(key)) {
                                const float v = std::stof(value);
                                app.light().size = app.light().type == LightType::Directional ? glm::radians(v) : v;
                            } else {
                                assignments.push_back(paramFor(*info, key) + "=" + value);
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
    std::error_code ec;
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
    std::ofstream out(file);
    if (!out) {
        error = file.string() + ": cannot write results";
        return false;
    }
    if (file.extension() != ".csv") {
        out << nlohmann::json(rows).dump(1) << "\n";
        return bool(out);
    }
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
    return bool(out);
}

} // namespace shadowlab
