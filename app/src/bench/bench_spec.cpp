// Benchmark specs: parsing and the whole-sweep check (see bench_spec.h).
#include "bench/bench_spec.h"

#include <charconv>
#include <cmath>
#include <set>
#include <sstream>

#include "scene/scene.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

using nlohmann::json;

// How a spec's part is called where it came from: an option on the command line, a field in JSON.
std::string nameOf(const BenchSpec& spec, const std::string& option, const std::string& field) {
    return spec.fromCommandLine ? option : field;
}

std::string sweepName(const BenchSpec& spec, const std::string& key) {
    return spec.fromCommandLine ? "--sweep " + key + "=..." : "sweep." + key;
}

std::string baseName(const BenchSpec& spec, const std::string& assignment) {
    return spec.fromCommandLine ? "--set " + assignment : "base." + assignment.substr(0, assignment.find('='));
}


std::string describe(const json& value) {
    if (value.is_string()) return "\"" + value.get<std::string>().substr(0, 60) + "\"";
    const std::string text = value.dump();
    return text.size() > 60 ? text.substr(0, 60) + "..." : text;
}

bool readStrings(const json& node, const std::string& field, bool nonEmpty, std::vector<std::string>& out,
                 std::string& error) {
    if (!node.is_array() || (nonEmpty && node.empty())) {
        error = field + ": expected " + (nonEmpty ? "a non-empty array" : "an array") + " of strings, got " + describe(node);
        return false;
    }
    out.clear();
    for (const json& item : node) {
        if (!item.is_string()) {
            error = field + ": expected strings, got " + describe(item);
            return false;
        }
        out.push_back(item.get<std::string>());
    }
    return true;
}

bool readWholeNumber(const json& node, const std::string& field, int minimum, int maximum, int& out, std::string& error) {
    const bool number = node.is_number();
    const double value = number ? node.get<double>() : 0.0;
    if (!number || value != std::floor(value) || value < minimum || value > maximum) {
        error = field + ": expected a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum) +
                ", got " + describe(node);
        return false;
    }
    out = static_cast<int>(value);
    return true;
}

bool readBool(const json& node, const std::string& field, bool& out, std::string& error) {
    if (!node.is_boolean()) {
        error = field + ": expected true or false, got " + describe(node);
        return false;
    }
    out = node.get<bool>();
    return true;
}

bool isScalar(const json& value) { return value.is_number() || value.is_string() || value.is_boolean(); }

} // namespace

bool parseSize(const std::string& text, glm::ivec2& size, std::string& error, const std::string& option) {
    const size_t x = text.find_first_of("xX");
    int w = 0, h = 0;
    bool valid = x != std::string::npos && x > 0 && x + 1 < text.size();
    if (valid) {
        const char* end = text.data() + text.size();
        const auto first = std::from_chars(text.data(), text.data() + x, w);
        const auto second = std::from_chars(text.data() + x + 1, end, h);
        valid = first.ec == std::errc() && first.ptr == text.data() + x && second.ec == std::errc() && second.ptr == end &&
                w >= kMinRenderSize && h >= kMinRenderSize && w <= kMaxRenderSize && h <= kMaxRenderSize;
    }
    if (!valid) {
        error = option + " '" + text + "': expected WIDTHxHEIGHT between " + std::to_string(kMinRenderSize) + " and " +
                std::to_string(kMaxRenderSize) + ", e.g. 1280x720";
        return false;
    }
    size = {w, h};
    return true;
}

std::string specValueText(const json& value) { return value.is_string() ? value.get<std::string>() : value.dump(); }

std::optional<double> parseNumberText(const std::string& text) {
    const char* begin = text.data();
    const char* end = begin + text.size();
    if (begin != end && *begin == '+') ++begin;
    double value = 0.0;
    const auto result = std::from_chars(begin, end, value);
    if (begin == end || result.ec != std::errc() || result.ptr != end || !std::isfinite(value)) return std::nullopt;
    return value;
}

bool parseOnOff(const std::string& text, bool& value, std::string& error, const std::string& option) {
    if (text == "on" || text == "true" || text == "1") {
        value = true;
    } else if (text == "off" || text == "false" || text == "0") {
        value = false;
    } else {
        error = option + " '" + text.substr(0, 60) + "': expected on or off";
        return false;
    }
    return true;
}

bool addSweep(BenchSpec& spec, const std::string& text, std::string& error) {
    const auto equals = text.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
        error = "--sweep '" + text + "': expected key=value1,value2,...";
        return false;
    }
    std::vector<std::string> values;
    if (!splitList(text.substr(equals + 1), "--sweep " + text.substr(0, equals) + "=...", values, error)) return false;
    // A key swept twice would keep only the last list (a map): refused, like a JSON key given twice.
    if (!spec.sweeps.emplace(text.substr(0, equals), values).second) {
        error = "--sweep " + text.substr(0, equals) + "=...: the key is swept twice (give all its values in one --sweep)";
        return false;
    }
    return true;
}

bool parseBenchSpec(const json& spec, BenchSpec& out, std::string& error) {
    static const std::set<std::string> known{"techniques", "scenes", "sizes", "sweep", "base", "frames", "warmup", "minFrames", "stableWithin",
                                             "accuracy", "reference", "referenceSamples", "referenceAdaptive", "depthFloor", "contactBand",
                                             "sweptOnly",
                                             "description", "tag", "path", "pathFrames"};
    if (!spec.is_object()) {
        error = "a benchmark spec is a JSON object, got " + describe(spec);
        return false;
    }
    for (const auto& [key, value] : spec.items()) {
        if (!known.count(key)) {
            error = "unknown field '" + key + "'";
            return false;
        }
    }
    BenchSpec result = out;
    // An empty list would mean "every technique" (as the field left out does): refused, so that a
    // list emptied by mistake does not silently measure everything.
    if (const auto it = spec.find("techniques"); it != spec.end() && !readStrings(*it, "techniques", true, result.techniques, error))
        return false;
    if (const auto it = spec.find("scenes"); it != spec.end() && !readStrings(*it, "scenes", true, result.scenes, error))
        return false;
    if (const auto it = spec.find("sizes"); it != spec.end()) {
        std::vector<std::string> sizes;
        if (!readStrings(*it, "sizes", true, sizes, error)) return false;
        result.sizes.clear();
        for (const auto& text : sizes) {
            glm::ivec2 size;
            if (!parseSize(text, size, error, "sizes:")) return false;
            result.sizes.push_back(size);
        }
    }
    if (const auto it = spec.find("sweep"); it != spec.end()) {
        if (!it->is_object()) {
            error = "sweep: expected an object of arrays, got " + describe(*it);
            return false;
        }
        for (const auto& [key, values] : it->items()) {
            if (!values.is_array() || values.empty()) {
                error = "sweep." + key + ": expected a non-empty array";
                return false;
            }
            auto& list = result.sweeps[key];
            list.clear();
            for (const auto& v : values) {
                if (!isScalar(v)) {
                    error = "sweep." + key + ": expected numbers, strings or booleans, got " + describe(v);
                    return false;
                }
                list.push_back(specValueText(v));
            }
        }
    }
    if (const auto it = spec.find("base"); it != spec.end()) {
        if (!it->is_object()) {
            error = "base: expected an object of values, got " + describe(*it);
            return false;
        }
        for (const auto& [key, value] : it->items()) {
            if (!isScalar(value)) {
                error = "base." + key + ": expected a number, string or boolean, got " + describe(value);
                return false;
            }
            result.base.push_back(key + "=" + specValueText(value));
        }
    }
    if (const auto it = spec.find("frames"); it != spec.end() && !readWholeNumber(*it, "frames", 1, kMaxBenchFrames, result.frames, error))
        return false;
    if (const auto it = spec.find("stableWithin"); it != spec.end()) {
        if (!it->is_number() || !std::isfinite(it->get<double>()) || it->get<double>() <= 0.0 ||
            it->get<double>() > kMaxStableWithin) {
            error = "stableWithin: expected a fraction above 0 and at most " + specValueText(kMaxStableWithin) + ", got " +
                    describe(*it);
            return false;
        }
        result.stableWithin = it->get<double>();
    }
    if (const auto it = spec.find("minFrames"); it != spec.end()) {
        if (!readWholeNumber(*it, "minFrames", kMinStableFrames, kMaxBenchFrames, result.minFrames, error)) return false;
        result.minFramesGiven = true;
    }
    if (const auto it = spec.find("warmup"); it != spec.end() &&
                                             !readWholeNumber(*it, "warmup", 0, kMaxBenchFrames, result.warmupFrames, error))
        return false;
    if (const auto it = spec.find("referenceSamples"); it != spec.end() &&
        !readWholeNumber(*it, "referenceSamples", 1, kMaxReferenceSamples, result.referenceSamples, error))
        return false;
    if (const auto it = spec.find("contactBand"); it != spec.end() && !readBool(*it, "contactBand", result.contactBand, error))
        return false;
    if (const auto it = spec.find("referenceAdaptive");
        it != spec.end() && !readBool(*it, "referenceAdaptive", result.referenceAdaptive, error))
        return false;
    if (const auto it = spec.find("accuracy"); it != spec.end() && !readBool(*it, "accuracy", result.accuracy, error)) return false;
    if (const auto it = spec.find("depthFloor"); it != spec.end() && !readBool(*it, "depthFloor", result.depthFloor, error))
        return false;
    if (const auto it = spec.find("sweptOnly"); it != spec.end() && !readBool(*it, "sweptOnly", result.sweptOnly, error))
        return false;
    if (const auto it = spec.find("pathFrames"); it != spec.end() &&
                                                 !readWholeNumber(*it, "pathFrames", 1, kMaxBenchFrames, result.pathFrames, error))
        return false;
    for (const char* key : {"reference", "tag", "description", "path"}) {
        const auto it = spec.find(key);
        if (it == spec.end()) continue;
        if (!it->is_string()) {
            error = std::string(key) + ": expected a string, got " + describe(*it);
            return false;
        }
        if (std::string(key) == "reference") result.reference = it->get<std::string>();
        if (std::string(key) == "tag") result.tag = it->get<std::string>();
        if (std::string(key) == "path") {
            result.path = it->get<std::string>();
            if (result.path.empty() || result.path.size() > 4096) {
                error = "path: expected the name of a path (built-in or the scene's) or a path file, 1 to 4096 characters";
                return false;
            }
        }
    }
    out = std::move(result);
    return true;
}

bool loadBenchSpecs(const std::filesystem::path& file, std::vector<BenchSpec>& specs, std::string& error) {
    json root;
    if (!readJsonFile(file, root, error, "benchmark spec")) return false;
    if (!root.is_array()) root = json::array({root});
    if (root.empty()) {
        error = file.string() + ": no spec in the file (an empty array)";
        return false;
    }
    for (size_t i = 0; i < root.size(); ++i) {
        BenchSpec spec;
        spec.source = file.string() + (root.size() > 1 ? ": spec " + std::to_string(i) : "");
        if (!parseBenchSpec(root[i], spec, error)) {
            error = spec.source + ": " + error;
            return false;
        }
        // A scene file is relative to the spec's folder (as a stress case's is to its cases file),
        // so a spec measures the same scenes from whatever folder it is run.
        for (std::string& scene : spec.scenes)
            if (scene.ends_with(".json") && std::filesystem::path(scene).is_relative())
                scene = (file.parent_path() / scene).lexically_normal().string();
        specs.push_back(spec);
    }
    return true;
}

std::string benchParamFor(const TechniqueInfo& info, const std::string& key) {
    if (const auto dot = key.find('.'); dot != std::string::npos)
        return key.substr(0, dot) == info.id && info.findParam(key.substr(dot + 1)) ? key.substr(dot + 1) : "";
    return info.findParam(key) ? key : "";
}

std::vector<std::vector<BenchSetting>> benchCombinations(const BenchSettingLists& lists) {
    std::vector<std::vector<BenchSetting>> out{{}};
    for (const auto& [key, values] : lists) {
        std::vector<std::vector<BenchSetting>> next;
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

std::optional<std::vector<const TechniqueInfo*>> benchTechniques(const BenchSpec& spec,
                                                                 const std::vector<TechniqueInfo>& techniques,
                                                                 std::string& error) {
    std::vector<const TechniqueInfo*> out;
    if (spec.techniques.empty()) {
        for (const auto& t : techniques)
            if (t.category != "reference") out.push_back(&t);
        return out;
    }
    for (const auto& id : spec.techniques) {
        const TechniqueInfo* found = nullptr;
        for (const auto& t : techniques)
            if (t.id == id) found = &t;
        if (!found) {
            std::string known;
            for (const auto& t : techniques) appendListItem(known, t.id);
            error = nameOf(spec, "--techniques", "techniques") + ": no technique '" + id + "' (available: " + known + ")";
            return std::nullopt;
        }
        out.push_back(found);
    }
    return out;
}

// The sweeps: every key must mean something, so a typo fails loudly instead of sweeping nothing;
// every value must parse for every technique it will be given to.
static bool checkSweeps(const BenchSpec& spec, const std::vector<const TechniqueInfo*>& measured, std::string& error) {
    for (const auto& [key, values] : spec.sweeps) {
        if (values.empty()) {
            error = sweepName(spec, key) + ": no values";
            return false;
        }
        if (isSceneKey(key)) {
            if (key.size() == 6) {
                error = sweepName(spec, key) + ": names no scene parameter (scene.<name>)";
                return false;
            }
            for (const auto& value : values) {
                if (!parseNumberText(value)) {
                    error = sweepName(spec, key) + ": '" + value + "' is not a number";
                    return false;
                }
            }
            continue;
        }
        if (isLightKey(key)) {
            for (const auto& value : values) {
                if (!parseNumberText(value)) {
                    error = sweepName(spec, key) + ": '" + value + "' is not a number";
                    return false;
                }
            }
            continue;   // the range depends on each scene's light: below
        }
        if (isHostKey(key)) {   // host.depth_prepass: auto | on | off, 0 and 1 as off and on
            for (const auto& value : values) {
                std::string problem;
                if (!parseParamValue(*hostParams().findParam(key.substr(5)), value, problem)) {
                    error = sweepName(spec, key) + ": " + problem;
                    return false;
                }
            }
            continue;
        }
        bool used = false;
        for (const TechniqueInfo* t : measured) {
            const std::string param = benchParamFor(*t, key);
            if (param.empty()) continue;
            used = true;
            for (const auto& value : values) {
                std::string problem;
                if (!parseParamValue(*t->findParam(param), value, problem)) {
                    error = sweepName(spec, key) + ": " + t->id + ": " + problem;
                    return false;
                }
            }
        }
        if (!used) {
            std::string hostKeys;
            for (const auto& p : hostParams().params) hostKeys += ", host." + p.id;
            error = sweepName(spec, key) + ": '" + key + "' is no parameter of the techniques measured (nor scene.*, light.size" +
                    hostKeys + ")";
            return false;
        }
    }
    return true;
}

// Scenes: each with each combination of its swept parameters, as the run will load them, against
// the light sizes and render sizes it will get.
static bool checkBenchScenes(const BenchSpec& spec, std::optional<double> lightSize, std::string& error) {
    BenchSettingLists sceneLists;
    for (const auto& [key, values] : spec.sweeps)
        if (isSceneKey(key)) sceneLists.push_back({key, values});
    const auto lightSizes = spec.sweeps.find("light.size");
    for (const auto& scene : spec.scenes) {
        for (const auto& settings : benchCombinations(sceneLists)) {
            std::map<std::string, double> overrides;
            for (const auto& [key, value] : settings) overrides[key.substr(6)] = *parseNumberText(value);
            SceneCheck check;
            try {
                check = checkScene(scene, overrides);
            } catch (const SceneError& e) {
                error = nameOf(spec, "--scenes", "scenes") + " '" + scene + "': " + e.what();
                return false;
            }
            if (lightSizes != spec.sweeps.end()) {
                for (const auto& value : lightSizes->second) {
                    if (const std::string problem = lightSizeProblem(check.lightType, *parseNumberText(value)); !problem.empty()) {
                        error = sweepName(spec, "light.size") + ": '" + value + "' on scene '" + scene + "': " + problem;
                        return false;
                    }
                }
            }
            for (const glm::ivec2 size : spec.sizes) {
                if (const std::string problem = renderTargetBudgetProblem(size, 0, check.gpuBytes); !problem.empty()) {
                    error = nameOf(spec, "--size", "sizes") + " on scene '" + scene + "': " + problem;
                    return false;
                }
            }
            if (lightSize) {
                if (const std::string problem = lightSizeProblem(check.lightType, *lightSize); !problem.empty()) {
                    error = "--light-size on scene '" + scene + "': " + problem;
                    return false;
                }
            }
        }
    }
    return true;
}

static bool checkBenchSpecContent(const BenchSpec& spec, const std::vector<TechniqueInfo>& techniques, std::string& error,
                                  std::optional<double> lightSize);

bool checkBenchSpec(const BenchSpec& spec, const std::vector<TechniqueInfo>& techniques, std::string& error,
                    std::optional<double> lightSize) {
    if (checkBenchSpecContent(spec, techniques, error, lightSize)) return true;
    if (!spec.source.empty() && !error.starts_with(spec.source)) error = spec.source + ": " + error;
    return false;
}

static bool checkBenchSpecContent(const BenchSpec& spec, const std::vector<TechniqueInfo>& techniques, std::string& error,
                                  std::optional<double> lightSize) {
    if (spec.frames < 1 || spec.frames > kMaxBenchFrames || spec.warmupFrames < 0 || spec.warmupFrames > kMaxBenchFrames) {
        error = nameOf(spec, "--frames/--warmup", "frames/warmup") + ": frames must be 1 to " + std::to_string(kMaxBenchFrames) +
                " and warm-up frames 0 to " + std::to_string(kMaxBenchFrames);
        return false;
    }
    if (spec.minFramesGiven && spec.stableWithin <= 0.0) {
        error = nameOf(spec, "--min-frames", "minFrames") + ": only means something with " +
                nameOf(spec, "--stable-within", "stableWithin");
        return false;
    }
    if (spec.stableWithin < 0.0 || spec.stableWithin > kMaxStableWithin ||
        (spec.stableWithin > 0.0 && (spec.minFrames < kMinStableFrames || spec.minFrames > spec.frames))) {
        error = nameOf(spec, "--stable-within/--min-frames", "stableWithin/minFrames") +
                ": the fraction must be 0 to " + specValueText(kMaxStableWithin) + " and the frames " +
                std::to_string(kMinStableFrames) + " to frames (" + std::to_string(spec.frames) + ")";
        return false;
    }
    if (spec.reference != "hard" && spec.reference != "soft" && spec.reference != "both" && spec.reference != "auto") {
        error = nameOf(spec, "--reference", "reference") + " '" + spec.reference + "': expected hard, soft, both or auto";
        return false;
    }
    if (spec.referenceSamples < 1 || spec.referenceSamples > kMaxReferenceSamples) {
        error = nameOf(spec, "--samples", "referenceSamples") + " " + std::to_string(spec.referenceSamples) +
                ": expected 1 to " + std::to_string(kMaxReferenceSamples) + " rays per pixel";
        return false;
    }
    if (spec.sizes.empty() || spec.scenes.empty()) {
        error = nameOf(spec, "--size/--scenes", "sizes/scenes") + ": nothing to measure (an empty list)";
        return false;
    }
    for (const glm::ivec2 size : spec.sizes) {
        if (size.x < kMinRenderSize || size.y < kMinRenderSize || size.x > kMaxRenderSize || size.y > kMaxRenderSize) {
            error = nameOf(spec, "--size", "sizes") + " " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                    ": expected " + std::to_string(kMinRenderSize) + " to " + std::to_string(kMaxRenderSize);
            return false;
        }
    }
    const auto measured = benchTechniques(spec, techniques, error);
    if (!measured) return false;

    if (!checkSweeps(spec, *measured, error)) return false;
    for (const auto& text : spec.base) {
        const size_t equals = text.find('=');
        if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) {
            error = baseName(spec, text) + ": expected key=value";
            return false;
        }
        const std::string key = text.substr(0, equals), value = text.substr(equals + 1);
        if (isSceneKey(key) || isLightKey(key) || isHostKey(key)) {
            error = baseName(spec, text) + ": '" + key + "' is not a technique parameter (scene parameters and the light size are swept: " +
                    sweepName(spec, key) + ")";
            return false;
        }
        bool used = false;
        for (const TechniqueInfo* t : *measured) {
            const std::string param = benchParamFor(*t, key);
            if (param.empty()) continue;
            used = true;
            std::string problem;
            if (!parseParamValue(*t->findParam(param), value, problem)) {
                error = baseName(spec, text) + ": " + t->id + ": " + problem;
                return false;
            }
        }
        if (!used) {
            error = baseName(spec, text) + ": '" + key + "' is no parameter of the techniques measured";
            return false;
        }
    }
    if (spec.depthFloor) {
        std::vector<std::string> resolutions{"2048"};
        if (auto it = spec.sweeps.find("resolution"); it != spec.sweeps.end()) resolutions = it->second;
        for (const auto& text : resolutions) {
            const auto value = parseNumberText(text);
            if (!value || *value != std::floor(*value) || *value < kMinRenderSize || *value > kMaxRenderSize) {
                error = nameOf(spec, "--depth-floor", "depthFloor") + ": resolution '" + text +
                        "' is not a shadow-map resolution (a whole number from " + std::to_string(kMinRenderSize) + " to " +
                        std::to_string(kMaxRenderSize) + ")";
                return false;
            }
        }
    }

    if (!spec.path.empty()) {
        // bench --path's rows: one size, the technique's parameters per combination; with accuracy
        // bench --path --accuracy's temporal metrics against the hard or soft reference.
        if (spec.sizes.size() != 1 || spec.depthFloor || spec.stableWithin > 0.0) {
            error = nameOf(spec, "--path", "path") + " '" + spec.path +
                    "': a path group times every frame at one size (one entry in sizes; no depthFloor or stableWithin)";
            return false;
        }
        if (spec.accuracy && spec.reference != "hard" && spec.reference != "soft") {
            error = nameOf(spec, "--path", "path") + " '" + spec.path + "': with accuracy, a path group's reference is hard or soft, not '" +
                    spec.reference + "'";
            return false;
        }
        for (const auto& entry : spec.sweeps) {
            if (isSceneKey(entry.first) || isLightKey(entry.first) || entry.first.rfind("host.", 0) == 0) {
                error = sweepName(spec, entry.first) + ": a path group sweeps technique parameters only (the path moves the camera and light)";
                return false;
            }
        }
    }
    return checkBenchScenes(spec, lightSize, error);
}

} // namespace shadowlab
