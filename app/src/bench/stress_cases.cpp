// Reading the failure suite's cases file (see stress.h). No GL: the fuzzing harness compiles it.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "bench/bench_spec.h"
#include "bench/stress.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {

namespace {

using nlohmann::json;

struct Problem {
    std::string field, what;
};
[[noreturn]] void fail(const std::string& field, const std::string& what) { throw Problem{field, what}; }

void known(const json& node, const std::string& at, std::initializer_list<const char*> keys) {
    if (!node.is_object()) fail(at, "expected an object");
    for (const auto& item : node.items()) {
        std::string list;
        bool ok = false;
        for (const char* key : keys) {
            ok = ok || item.key() == key;
            appendListItem(list, key);
        }
        if (!ok) fail(at.empty() ? item.key() : at + "." + item.key(), "unknown field (expected one of: " + list + ")");
    }
}

double numberField(const json& node, const std::string& key, const std::string& at, double lo, double hi) {
    const json& v = node[key];
    if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < lo || v.get<double>() > hi)
        fail(at + "." + key, "expected a number from " + std::to_string(lo) + " to " + std::to_string(hi));
    return v.get<double>();
}

std::string stringField(const json& node, const std::string& key, const std::string& at, bool required = false) {
    if (!node.contains(key)) {
        if (required) fail(at + "." + key, "missing");
        return "";
    }
    if (!node[key].is_string() || node[key].get<std::string>().size() > 4096) fail(at + "." + key, "expected a string");
    return node[key].get<std::string>();
}

glm::vec3 vecField(const json& node, const std::string& key, const std::string& at) {
    const json& v = node[key];
    if (!v.is_array() || v.size() != 3) fail(at + "." + key, "expected an array of 3 numbers");
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        if (!v[size_t(i)].is_number() || !std::isfinite(v[size_t(i)].get<double>()) || std::abs(v[size_t(i)].get<double>()) > 1e9)
            fail(at + "." + key, "expected finite numbers within +-1e9");
        out[i] = v[size_t(i)].get<float>();
    }
    return out;
}

const std::map<std::string, StressMetric>& metricNames() {
    static const std::map<std::string, StressMetric> names = {
        {"false_shadow", StressMetric::FalseShadow}, {"false_light", StressMetric::FalseLight},
        {"mae", StressMetric::Mae}, {"mae_near_third", StressMetric::MaeNearThird},
        {"mae_far_third", StressMetric::MaeFarThird}, {"flicker", StressMetric::Flicker},
        {"popping", StressMetric::Popping}, {"noise", StressMetric::Noise},
        {"contact_false_light", StressMetric::ContactFalseLight}};
    return names;
}

StressCase parseCase(const json& node, const std::string& at) {
    known(node, at, {"id", "title", "scene", "requires", "camera", "light", "path", "frames", "texelsPerFrame", "set",
                     "reference", "samples", "region", "metric", "threshold", "expectedToFail", "expectedToPass", "claim", "source",
                     "footprint"});
    StressCase c;
    c.id = stringField(node, "id", at, true);
    if (c.id.empty() || c.id.size() > 64 || c.id.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-_.") != std::string::npos)
        fail(at + ".id", "expected 1 to 64 of a-z 0-9 - _ .");
    c.title = stringField(node, "title", at, true);
    c.scene = stringField(node, "scene", at, true);
    if (node.contains("requires")) c.requires_ = stringField(node, "requires", at);
    if (node.contains("camera")) {
        const json& camera = node["camera"];
        known(camera, at + ".camera", {"position", "target", "near", "far"});
        if (camera.contains("position")) c.cameraPosition = vecField(camera, "position", at + ".camera");
        if (camera.contains("target")) c.cameraTarget = vecField(camera, "target", at + ".camera");
        if (camera.contains("near")) c.cameraNear = float(numberField(camera, "near", at + ".camera", 1e-6, 1e9));
        if (camera.contains("far")) c.cameraFar = float(numberField(camera, "far", at + ".camera", 1e-6, 1e9));
        if (c.cameraNear && c.cameraFar && !(*c.cameraFar > *c.cameraNear)) fail(at + ".camera.far", "must be greater than near");
    }
    if (node.contains("light")) {
        const json& light = node["light"];
        known(light, at + ".light", {"elevation", "azimuth", "size"});
        if (light.contains("elevation") != light.contains("azimuth")) fail(at + ".light", "give both elevation and azimuth");
        if (light.contains("elevation"))
            c.lightAngles = glm::vec2(float(numberField(light, "elevation", at + ".light", 0.01, 90)),
                                      float(numberField(light, "azimuth", at + ".light", -360, 360)));
        if (light.contains("size")) c.lightSize = float(numberField(light, "size", at + ".light", 0, 45));
    }
    c.path = stringField(node, "path", at);
    if (!c.path.empty() && std::find(builtinPathNames().begin(), builtinPathNames().end(), c.path) == builtinPathNames().end())
        fail(at + ".path", "'" + c.path + "' is not a built-in path");
    if (node.contains("frames")) {
        const json& v = node["frames"];
        if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > 10000) fail(at + ".frames", "expected a whole number from 1 to 10000");
        c.frames = int(v.get<long long>());
    } else if (!c.path.empty()) {
        c.frames = 16;
    }
    if (!c.path.empty() && c.frames < 2) fail(at + ".frames", "a path needs at least 2 frames");
    if (node.contains("texelsPerFrame")) c.texelsPerFrame = numberField(node, "texelsPerFrame", at, 0.0, 100.0);
    if (node.contains("set")) {
        const json& sets = node["set"];
        if (!sets.is_array()) fail(at + ".set", "expected an array of \"key=value\" strings");
        for (size_t i = 0; i < sets.size(); ++i) {
            if (!sets[i].is_string() || sets[i].get<std::string>().find('=') == std::string::npos)
                fail(at + ".set[" + std::to_string(i) + "]", "expected \"key=value\"");
            c.sets.push_back(sets[i].get<std::string>());
        }
    }
    const std::string reference = node.contains("reference") ? stringField(node, "reference", at) : "hard";
    if (reference == "hard") c.reference = ReferenceOptions::Mode::Hard;
    else if (reference == "soft") c.reference = ReferenceOptions::Mode::Soft;
    else fail(at + ".reference", "expected \"hard\" or \"soft\"");
    if (node.contains("samples")) c.referenceSamples = int(numberField(node, "samples", at, 1, 4096));
    if (node.contains("region")) {
        const json& region = node["region"];
        known(region, at + ".region", {"centre", "radius", "object"});
        if (region.contains("object")) c.regionObject = stringField(region, "object", at + ".region");
        if (region.contains("centre")) {
            c.regionCentre = vecField(region, "centre", at + ".region");
            if (!region.contains("radius")) fail(at + ".region.radius", "missing (a centre needs a radius)");
            c.regionRadius = float(numberField(region, "radius", at + ".region", 1e-6, 1e9));
        }
        if (c.regionObject.empty() == !c.regionCentre) fail(at + ".region", "give either object or centre and radius");
    }
    const std::string metric = stringField(node, "metric", at, true);
    const auto found = metricNames().find(metric);
    if (found == metricNames().end()) {
        std::string list;
        for (const auto& [name, value] : metricNames()) appendListItem(list, name);
        fail(at + ".metric", "unknown metric '" + metric + "' (expected one of: " + list + ")");
    }
    c.metric = found->second;
    const bool temporal = c.metric == StressMetric::Flicker || c.metric == StressMetric::Popping || c.metric == StressMetric::Noise;
    if (temporal && c.path.empty()) fail(at + ".metric", "a temporal metric needs a path");
    if (c.metric == StressMetric::ContactFalseLight && c.reference != ReferenceOptions::Mode::Hard)
        fail(at + ".metric", "contact_false_light is measured against the hard reference");
    if (!node.contains("threshold")) fail(at + ".threshold", "missing");
    c.threshold = numberField(node, "threshold", at, 0.0, 1.0);
    auto idList = [&](const char* key, std::vector<std::string>& out) {
        if (!node.contains(key)) return;
        const json& list = node[key];
        if (!list.is_array()) fail(at + "." + key, "expected an array of technique ids");
        for (const json& id : list) {
            if (!id.is_string()) fail(at + "." + key, "expected an array of technique ids");
            out.push_back(id.get<std::string>());
        }
    };
    idList("expectedToFail", c.expectedToFail);
    idList("expectedToPass", c.expectedToPass);
    for (const std::string& id : c.expectedToPass)
        if (std::find(c.expectedToFail.begin(), c.expectedToFail.end(), id) != c.expectedToFail.end())
            fail(at + ".expectedToPass", "'" + id + "' is also in expectedToFail");
    c.claim = stringField(node, "claim", at, true);
    c.source = stringField(node, "source", at, true);
    if (node.contains("footprint")) {
        if (!node["footprint"].is_boolean()) fail(at + ".footprint", "expected true or false");
        c.footprint = node["footprint"].get<bool>();
    }
    return c;
}

} // namespace

const char* stressMetricName(StressMetric metric) {
    for (const auto& [name, value] : metricNames())
        if (value == metric) return name.c_str();
    return "?";
}

bool parseStressSuite(const json& node, const std::string& source, StressSuite& suite, std::string& error) {
    suite = {};
    suite.file = source;
    try {
        known(node, "", {"size", "cases", "description"});
        if (node.contains("size")) {
            std::string sizeError;
            if (!node["size"].is_string() || !parseSize(node["size"].get<std::string>(), suite.size, sizeError, "size"))
                fail("size", "expected \"WIDTHxHEIGHT\"");
        }
        if (!node.contains("cases") || !node["cases"].is_array() || node["cases"].empty() || node["cases"].size() > 1000)
            fail("cases", "expected an array of 1 to 1000 cases");
        std::set<std::string> ids;
        for (size_t i = 0; i < node["cases"].size(); ++i) {
            StressCase c = parseCase(node["cases"][i], "cases[" + std::to_string(i) + "]");
            if (!ids.insert(c.id).second) fail("cases[" + std::to_string(i) + "].id", "'" + c.id + "' is used twice");
            suite.cases.push_back(std::move(c));
        }
    } catch (const Problem& p) {
        error = source + (p.field.empty() ? "" : ": " + p.field) + ": " + p.what;
        return false;
    }
    return true;
}

bool loadStressSuite(const std::filesystem::path& file, StressSuite& suite, std::string& error) {
    json node;
    if (!readJsonFile(file, node, error, "stress cases file")) return false;
    return parseStressSuite(node, file.string(), suite, error);
}

} // namespace shadowlab
