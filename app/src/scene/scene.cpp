// Scene loading: JSON scene descriptions (docs/scene-format.md) turned into meshes, materials,
// objects, one light and a camera; the built-in scenes embedded from assets/scenes/; and the few
// queries the host asks of a scene (bounds, triangle count, draw sets).
// Parsing is strict on purpose: every field is checked for type, length and range, and a field
// nobody reads (a typo) is an error, because a silently ignored field quietly changes an experiment.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <climits>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "scene/object_transform.h"
#include "scene/scene.h"
#include "util/progress.h"
#include "util/log.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {

// Generated from assets/scenes/*.json by cmake/EmbedScenes.cmake: {name, JSON text}.
extern const std::pair<std::string_view, std::string_view> kBuiltinScenes[];
extern const unsigned kBuiltinSceneCount;

namespace {

using nlohmann::json;

constexpr float kRadiansPerDegree = glm::pi<float>() / 180.0f;
constexpr int kMaxInstances = 1'000'000;   // a typo like count=5000000 should fail, not swap
constexpr int kMaxSegments = 4096;
constexpr size_t kMaxNameLength = 100;    // object and scene names (shown in lists and copied per instance)
constexpr size_t kMaxTextLength = 4096;   // descriptions and other strings
constexpr size_t kMaxFallbackObjects = 1000;   // objects in one fallback group (each may repeat)
constexpr const char* kShapes = "plane, terrain, box, sphere, cylinder, torus, tree, bumpy, teapot, obj";
// Per object, the renderer's transform buffer holds a model and a normal matrix.
constexpr uint64_t kGpuBytesPerObject = 2 * sizeof(glm::mat4);
constexpr const char* kBudgetHelp = "docs/scene-format.md, \"Limits\"";

SceneBudget& processBudget() {
    static SceneBudget budget;
    return budget;
}

std::string formatBytes(uint64_t bytes) {
    char text[32];
    if (bytes >= (uint64_t(1) << 30)) std::snprintf(text, sizeof(text), "%.1f GiB", double(bytes) / double(1 << 30));
    else std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1 << 20));
    return text;
}

std::string joined(const std::vector<std::string>& items) {
    std::string text;
    for (const std::string& item : items) appendListItem(text, item);
    return text;
}

std::string describe(const json& value) {
    switch (value.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array of " + std::to_string(value.size()) + " elements";
    case json::value_t::string: return "the string \"" + value.get<std::string>() + "\"";
    case json::value_t::boolean: return value.get<bool>() ? "true" : "false";
    case json::value_t::null: return "null";
    default: return "the number " + value.dump();
    }
}

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) previous[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        current[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                              std::tolower(static_cast<unsigned char>(b[j - 1]));
            current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (same ? 0 : 1)});
        }
        std::swap(previous, current);
    }
    return previous[b.size()];
}

// The known name nearest to `name` when it is near enough to be a typo of it, else "".
std::string likelyMeant(const std::string& name, const std::vector<std::string>& known) {
    std::string best;
    size_t bestDistance = std::max<size_t>(2, name.size() / 3) + 1;
    for (const std::string& candidate : known) {
        const size_t distance = editDistance(name, candidate);
        if (distance < bestDistance) {
            best = candidate;
            bestDistance = distance;
        }
    }
    return best;
}

// A file named in a scene: relative to the scene's folder, or under the shared test-model folder
// when it starts with "@assets/" ($SHADOWLAB_ASSETS_DIR, else ../shared/assets beside the source
// tree), so built-in scenes can use models that are never copied into the repository.
std::filesystem::path sceneFilePath(const std::filesystem::path& baseDir, const std::string& name) {
    constexpr std::string_view assets = "@assets/";
    if (name.starts_with(assets)) {
        const char* dir = std::getenv("SHADOWLAB_ASSETS_DIR");
        const std::filesystem::path root = dir && *dir ? std::filesystem::path(dir)
                                                       : std::filesystem::path(SHADOWLAB_SOURCE_DIR) / ".." / "shared" / "assets";
        return (root / name.substr(assets.size())).lexically_normal();
    }
    return (baseDir / name).lexically_normal();
}

std::string childPath(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string elementPath(const std::string& path, size_t index) { return path + "[" + std::to_string(index) + "]"; }

// What every reader needs: where errors point to, and the values "$name" stands for.
struct ParseContext {
    std::string source;
    std::map<std::string, double> parameters;

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        throw SceneError(source + ": " + (path.empty() ? "" : path + ": ") + problem);
    }

    std::string parameterList() const {
        std::vector<std::string> names;
        for (const auto& entry : parameters) names.push_back(entry.first);
        return names.empty() ? "this scene has no parameters" : "this scene has: " + joined(names);
    }
};

enum class Range { Any, NonNegative, Positive };

double readNumber(const json& value, const std::string& path, const ParseContext& context, Range range = Range::Any) {
    double number = 0.0;
    if (value.is_number()) {
        number = value.get<double>();
    } else if (value.is_string() && value.get_ref<const std::string&>().starts_with('$')) {
        const std::string name = value.get<std::string>().substr(1);
        const auto found = context.parameters.find(name);
        if (found == context.parameters.end()) {
            context.fail(path, "unknown parameter '$" + name + "' (" + context.parameterList() + ")");
        }
        number = found->second;
    } else {
        context.fail(path, std::string("expected a number") + (value.is_string() ? " or \"$parameter\"" : "") +
                               ", got " + describe(value));
    }
    if (!std::isfinite(number)) context.fail(path, "must be a finite number");
    if (range == Range::Positive && !(number > 0.0)) {
        context.fail(path, "must be positive (got " + formatNumber(number) + ")");
    }
    if (range == Range::NonNegative && number < 0.0) {
        context.fail(path, "must not be negative (got " + formatNumber(number) + ")");
    }
    return number;
}

// A double as it will be stored: in a float. 1e300 would become inf and 1e-300 zero, so the range
// of float is checked here, after any "must be positive" on the double.
float toFloat(double number, const std::string& path, const ParseContext& context, Range range) {
    if (std::abs(number) > double(std::numeric_limits<float>::max())) {
        context.fail(path, "too large for single precision (at most 3.4e38, got " + formatNumber(number) + ")");
    }
    const float value = static_cast<float>(number);
    if (range == Range::Positive && !(value >= std::numeric_limits<float>::min())) {
        context.fail(path, "too small: " + formatNumber(number) +
                               " is zero (or denormal) in single precision; the smallest positive value is 1.2e-38");
    }
    return value;
}

float readFloat(const json& value, const std::string& path, const ParseContext& context, Range range = Range::Any) {
    return toFloat(readNumber(value, path, context, range), path, context, range);
}

int readInteger(const json& value, const std::string& path, const ParseContext& context, int minimum, int maximum) {
    const double number = readNumber(value, path, context);
    if (number != std::floor(number)) context.fail(path, "expected a whole number, got " + formatNumber(number));
    if (number < minimum || number > maximum) {
        context.fail(path, "must be between " + std::to_string(minimum) + " and " + std::to_string(maximum) +
                               " (got " + formatNumber(number, 12) + ")");
    }
    return static_cast<int>(number);
}

template <glm::length_t N>
glm::vec<N, float> readVector(const json& value, const std::string& path, const ParseContext& context,
                              Range range = Range::Any) {
    if (!value.is_array() || value.size() != N) {
        context.fail(path, "expected an array of " + std::to_string(N) + " numbers, got " + describe(value));
    }
    glm::vec<N, float> result{};
    for (glm::length_t i = 0; i < N; ++i) {
        const size_t index = static_cast<size_t>(i);
        result[i] = readFloat(value.at(index), elementPath(path, index), context, range);
    }
    return result;
}

// One JSON object being read. Every field the parser understands is asked for by name, so whatever
// is left at finish() is a field nobody reads: reported with the name it probably meant.
class FieldReader {
public:
    FieldReader(const json& node, std::string path, const ParseContext& context)
        : node_(node), path_(std::move(path)), context_(context) {
        if (!node_.is_object()) context_.fail(path_, "expected an object, got " + describe(node_));
    }

    std::string pathOf(const std::string& key) const { return childPath(path_, key); }
    [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
        context_.fail(pathOf(key), problem);
    }
    const ParseContext& context() const { return context_; }
    bool has(const std::string& key) const { return node_.contains(key); }

    // The field, or nullptr when it is absent; either way `key` is now a known field.
    const json* find(const std::string& key) {
        if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
        const auto found = node_.find(key);
        return found == node_.end() ? nullptr : &*found;
    }

    const json& required(const std::string& key, const std::string& why) {
        const json* value = find(key);
        if (!value) fail(key, "missing (" + why + ")");
        return *value;
    }

    float number(const std::string& key, float fallback, Range range = Range::Any) {
        const json* value = find(key);
        return value ? readFloat(*value, pathOf(key), context_, range) : fallback;
    }

    int integer(const std::string& key, int fallback, int minimum, int maximum) {
        const json* value = find(key);
        return value ? readInteger(*value, pathOf(key), context_, minimum, maximum) : fallback;
    }

    template <glm::length_t N>
    glm::vec<N, float> vec(const std::string& key, glm::vec<N, float> fallback, Range range = Range::Any) {
        const json* value = find(key);
        return value ? readVector<N>(*value, pathOf(key), context_, range) : fallback;
    }

    bool boolean(const std::string& key, bool fallback) {
        const json* value = find(key);
        if (!value) return fallback;
        if (!value->is_boolean()) fail(key, "expected true or false, got " + describe(*value));
        return value->get<bool>();
    }

    std::string string(const std::string& key, const std::string& fallback, size_t maxLength = kMaxTextLength) {
        const json* value = find(key);
        if (!value) return fallback;
        if (!value->is_string()) fail(key, "expected a string, got " + describe(*value));
        const std::string& text = value->get_ref<const std::string&>();
        if (text.size() > maxLength) {
            fail(key, "longer than " + std::to_string(maxLength) + " characters (" + std::to_string(text.size()) + ")");
        }
        return text;
    }

    void finish(const std::string& what) const {
        for (const auto& item : node_.items()) {
            if (std::find(known_.begin(), known_.end(), item.key()) != known_.end()) continue;
            const std::string guess = likelyMeant(item.key(), known_);
            fail(item.key(), "unknown field " + (guess.empty() ? "(" + what + " has: " + joined(known_) + ")"
                                                               : "(did you mean '" + guess + "'?)"));
        }
    }

private:
    const json& node_;
    std::string path_;
    const ParseContext& context_;
    std::vector<std::string> known_;
};

// How to make an object's mesh, and a key naming it: objects with the same key share one mesh.
// Procedural recipes know their size before they run (the budget is checked with it); an OBJ
// file's size is known once it is read.
struct MeshRecipe {
    std::string key;
    std::function<Mesh()> make;
    std::optional<MeshSize> size;                      // nullopt: read from a file, size unknown
    bool isPlane = false;
    std::optional<glm::vec2> terrain = std::nullopt;   // amplitude and wavelength of a terrain shape
};

std::string recipeKey(const std::string& shape, std::initializer_list<double> arguments) {
    std::string key = shape;
    for (double argument : arguments) {
        key += ' ';
        key += formatNumber(argument, 9);
    }
    return key;
}

MeshRecipe readShape(FieldReader& fields, const std::string& shape, const std::filesystem::path& baseDir) {
    if (shape == "plane") {
        const glm::vec2 size = fields.vec("size", glm::vec2(10.0f), Range::Positive);
        const int subdivisions = fields.integer("subdivisions", 1, 1, kMaxSegments);
        return {recipeKey(shape, {size.x, size.y, double(subdivisions)}),
                [=] { return makePlane(size.x, size.y, subdivisions); }, planeSize(size.x, size.y, subdivisions), true};
    }
    if (shape == "box") {
        const glm::vec3 size = fields.vec("size", glm::vec3(1.0f), Range::Positive);
        return {recipeKey(shape, {size.x, size.y, size.z}), [=] { return makeBox(size); }, boxSize(size)};
    }
    if (shape == "sphere") {
        const float radius = fields.number("radius", 0.5f, Range::Positive);
        const int segments = fields.integer("segments", 32, 3, kMaxSegments);
        const int rings = fields.integer("rings", 16, 2, kMaxSegments);
        return {recipeKey(shape, {radius, double(segments), double(rings)}),
                [=] { return makeSphere(radius, segments, rings); }, sphereSize(radius, segments, rings)};
    }
    if (shape == "cylinder") {
        const float radius = fields.number("radius", 0.5f, Range::Positive);
        const float height = fields.number("height", 1.0f, Range::Positive);
        const int segments = fields.integer("segments", 32, 3, kMaxSegments);
        return {recipeKey(shape, {radius, height, double(segments)}),
                [=] { return makeCylinder(radius, height, segments); }, cylinderSize(radius, height, segments)};
    }
    if (shape == "torus") {
        const float majorRadius = fields.number("majorRadius", 0.5f, Range::Positive);
        const float minorRadius = fields.number("minorRadius", 0.2f, Range::Positive);
        if (minorRadius >= majorRadius) {
            fields.fail("minorRadius", "must be smaller than majorRadius (" + formatNumber(majorRadius) + ")");
        }
        const int segments = fields.integer("segments", 48, 3, kMaxSegments);
        const int sides = fields.integer("sides", 16, 3, kMaxSegments);
        return {recipeKey(shape, {majorRadius, minorRadius, double(segments), double(sides)}),
                [=] { return makeTorus(majorRadius, minorRadius, segments, sides); },
                torusSize(majorRadius, minorRadius, segments, sides)};
    }
    if (shape == "tree") {
        const float height = fields.number("height", 2.0f, Range::Positive);
        const float crownRadius = fields.number("crownRadius", 0.6f, Range::Positive);
        const int segments = fields.integer("segments", 12, 3, kMaxSegments);
        return {recipeKey(shape, {height, crownRadius, double(segments)}),
                [=] { return makeTree(height, crownRadius, segments); }, treeSize(height, crownRadius, segments)};
    }
    if (shape == "terrain") {
        const glm::vec2 size = fields.vec("size", glm::vec2(100.0f), Range::Positive);
        const int subdivisions = fields.integer("subdivisions", 128, 1, kMaxSegments);
        const float amplitude = fields.number("amplitude", 2.0f, Range::NonNegative);
        const float wavelength = fields.number("wavelength", 60.0f, Range::Positive);
        MeshRecipe recipe{recipeKey(shape, {size.x, size.y, double(subdivisions), amplitude, wavelength}),
                          [=] { return makeTerrain(size.x, size.y, subdivisions, amplitude, wavelength); },
                          terrainSize(size.x, size.y, subdivisions, amplitude)};
        recipe.terrain = glm::vec2(amplitude, wavelength);
        return recipe;
    }
    if (shape == "bumpy") {
        const float radius = fields.number("radius", 0.5f, Range::Positive);
        const float amplitude = fields.number("amplitude", 0.15f, Range::NonNegative);
        const float frequency = fields.number("frequency", 6.0f, Range::Positive);
        const int segments = fields.integer("segments", 96, 3, kMaxSegments);
        return {recipeKey(shape, {radius, amplitude, frequency, double(segments)}),
                [=] { return makeBumpySphere(radius, amplitude, frequency, segments); },
                bumpySphereSize(radius, amplitude, segments)};
    }
    if (shape == "teapot") {
        const float size = fields.number("size", 1.0f, Range::Positive);
        const int segments = fields.integer("segments", 32, 8, kMaxSegments);
        return {recipeKey(shape, {size, double(segments)}), [=] { return makeTeapotStandIn(size, segments); },
                teapotStandInSize(size, segments)};
    }
    if (shape == "obj") {
        const json& value = fields.required("file", "an obj object needs a file, relative to the scene file");
        if (!value.is_string()) fields.fail("file", "expected a string, got " + describe(value));
        const std::filesystem::path file = sceneFilePath(baseDir, value.get<std::string>());
        const std::string path = fields.pathOf("file");
        const ParseContext& context = fields.context();
        // A stand-in shape for when the file is not there (a built-in scene using a shared model).
        // An array of objects is a stand-in group, read by readFallbackGroup instead.
        if (const json* fallback = fields.find("fallback"); fallback && !fallback->is_array()) {
            FieldReader fallbackFields(*fallback, fields.pathOf("fallback"), context);
            const json& shape = fallbackFields.required("shape", std::string("one of: ") + kShapes);
            if (!shape.is_string() || shape.get<std::string>() == "obj")
                fallbackFields.fail("shape", "expected a procedural shape (not obj), got " + describe(shape));
            MeshRecipe recipe = readShape(fallbackFields, shape.get<std::string>(), baseDir);
            fallbackFields.finish("a fallback shape");
            std::error_code missing;
            if (!std::filesystem::exists(file, missing)) return recipe;
        }
        return {"obj " + file.string(), [file, path, &context] {
                    std::error_code error;
                    if (!std::filesystem::exists(file, error)) {
                        context.fail(path, "missing OBJ file '" + file.string() + "'");
                    }
                    try {
                        return loadObj(file);
                    } catch (const SceneError& objError) {
                        context.fail(path, objError.what());
                    }
                }, std::nullopt};
    }
    fields.fail("shape", "unknown shape '" + shape + "' (expected one of: " + kShapes + ")");
}

// A "repeat" block: `count` instances on a grid of columns x rows (x by z) centred on the object,
// each moved by up to +-jitter and scaled by a factor from scaleRange, both from `seed`.
struct Repeat {
    int count = 1;
    int columns = 1;
    int rows = 1;
    glm::vec2 spacing{2.0f};
    glm::vec3 jitter{0.0f};
    glm::vec2 scaleRange{1.0f};
    int seed = 1;
    bool followTerrain = false;   // stand each instance on the last terrain defined before it
    // Seeded random placement and rotation (from a stream of their own, so scenes without them
    // keep their instances): `region` > 0 places instances uniformly in a box of that size centred
    // on the object instead of on the grid; `randomRotate` turns each by up to +-degrees per axis.
    glm::vec3 region{0.0f};
    glm::vec3 randomRotate{0.0f};
};

Repeat readRepeat(const json& node, const std::string& path, const ParseContext& context) {
    FieldReader fields(node, path, context);
    Repeat repeat;
    const json* count = fields.find("count");
    const json* grid = fields.find("grid");
    if (!count && !grid) context.fail(path, "needs \"count\", \"grid\" or both");
    // 0 is allowed: a sweep may start with none of an object (glass-field quads=0).
    if (count) repeat.count = readInteger(*count, fields.pathOf("count"), context, 0, kMaxInstances);
    if (grid) {
        if (!grid->is_array() || grid->size() != 2) {
            fields.fail("grid", "expected an array of 2 numbers (columns, rows), got " + describe(*grid));
        }
        repeat.columns = readInteger(grid->at(0), elementPath(fields.pathOf("grid"), 0), context, 1, kMaxInstances);
        repeat.rows = readInteger(grid->at(1), elementPath(fields.pathOf("grid"), 1), context, 1, kMaxInstances);
        const long long cells = static_cast<long long>(repeat.columns) * repeat.rows;
        // The documented limit is on the grid's cells in every form, with or without a count: a
        // 1,000,000 x 1,000,000 grid holding 10 instances is the same typo as a count of 1e12.
        if (cells > kMaxInstances)
            fields.fail("grid", std::to_string(repeat.columns) + " x " + std::to_string(repeat.rows) + " = " +
                                    std::to_string(cells) + " cells, more than " + std::to_string(kMaxInstances) +
                                    " (the limit of a repeat block)");
        if (!count) {
            repeat.count = static_cast<int>(cells);
        } else if (repeat.count > cells) {
            fields.fail("count", std::to_string(repeat.count) + " instances do not fit a " +
                                     std::to_string(repeat.columns) + " x " + std::to_string(repeat.rows) + " grid");
        }
    } else {
        // No grid given: as square as the count allows.
        repeat.columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(repeat.count)))));
        repeat.rows = (repeat.count + repeat.columns - 1) / repeat.columns;
    }
    repeat.spacing = fields.vec("spacing", repeat.spacing, Range::NonNegative);
    if (const json* jitter = fields.find("jitter")) {
        repeat.jitter = jitter->is_array()
                            ? readVector<3>(*jitter, fields.pathOf("jitter"), context, Range::NonNegative)
                            : glm::vec3(1.0f, 0.0f, 1.0f) *
                                  readFloat(*jitter, fields.pathOf("jitter"), context, Range::NonNegative);
    }
    repeat.scaleRange = fields.vec("scaleRange", repeat.scaleRange, Range::Positive);
    if (repeat.scaleRange.x > repeat.scaleRange.y) fields.fail("scaleRange", "minimum exceeds maximum");
    repeat.seed = fields.integer("seed", repeat.seed, 0, INT_MAX);
    repeat.followTerrain = fields.boolean("followTerrain", false);
    repeat.region = fields.vec("region", repeat.region, Range::NonNegative);
    if (grid && repeat.region != glm::vec3(0.0f)) fields.fail("region", "give either grid or region, not both");
    repeat.randomRotate = fields.vec("randomRotate", repeat.randomRotate, Range::NonNegative) * kRadiansPerDegree;
    fields.finish("a repeat block");
    return repeat;
}

// The state of one scene being built.
struct SceneBuilder {
    ParseContext context;
    std::filesystem::path baseDir;
    Scene scene;
    SceneBudget budget;
    bool checkOnly = false;                       // the first pass: sizes and checks only, no meshes, no objects
    // OBJ meshes read by the checking pass, handed to the building pass (files are read once).
    std::map<std::string, Mesh>* objCache = nullptr;
    std::map<std::string, uint32_t> materialIndex;
    std::map<std::string, uint32_t> meshIndex;   // by MeshRecipe::key
    std::vector<MeshSize> meshSizes;              // by mesh index, also when checkOnly
    struct Terrain {
        glm::vec3 origin;
        float amplitude;
        float wavelength;
    };
    std::optional<Terrain> terrain;               // the last terrain object read, for followTerrain
    // Totals so far, checked against the budget before each allocation.
    uint64_t objects = 0, triangles = 0, storedVertices = 0, storedIndices = 0, textureBytes = 0;

    uint64_t gpuBytes() const {
        return storedVertices * sizeof(Vertex) + storedIndices * sizeof(uint32_t) + objects * kGpuBytesPerObject +
               textureBytes;
    }

    void checkBudget(const std::string& path) const {
        const std::string raise = "; raise it with --budget ";
        if (objects > budget.objects) {
            context.fail(path, "the scene would have " + std::to_string(objects) + " objects, more than the budget of " +
                                   std::to_string(budget.objects) + raise + "objects=N (" + kBudgetHelp + ")");
        }
        if (triangles > budget.triangles) {
            context.fail(path, "the scene would draw " + std::to_string(triangles) +
                                   " triangles per frame, more than the budget of " + std::to_string(budget.triangles) +
                                   raise + "triangles=N (" + kBudgetHelp + ")");
        }
        if (gpuBytes() > budget.gpuBytes) {
            context.fail(path, "the scene's geometry would need about " + formatBytes(gpuBytes()) +
                                   " of GPU memory, more than the budget of " + formatBytes(budget.gpuBytes) + raise +
                                   "gpu-mib=N (" + kBudgetHelp + ")");
        }
        // What the renderer can address, whatever the budget: int32 base vertices, uint32 indices.
        if (storedVertices > uint64_t(INT32_MAX) || storedIndices > uint64_t(UINT32_MAX) || objects > uint64_t(INT32_MAX)) {
            context.fail(path, "the scene's meshes would hold " + std::to_string(storedVertices) + " vertices and " +
                                   std::to_string(storedIndices) + " indices in " + std::to_string(objects) +
                                   " objects: more than the renderer addresses (2^31 vertices, 2^32 indices, 2^31 objects)");
        }
    }

    // The mesh of `recipe`, made once per key; the budget is checked before a procedural mesh is
    // generated (OBJ files are bounded by the file size and checked once read).
    uint32_t meshFor(const MeshRecipe& recipe, const std::string& path) {
        const auto [found, inserted] = meshIndex.try_emplace(recipe.key, static_cast<uint32_t>(meshSizes.size()));
        if (!inserted) return found->second;
        Mesh mesh;
        if (!recipe.size) {
            if (objCache && objCache->count(recipe.key)) {
                mesh = std::move(objCache->at(recipe.key));
                objCache->erase(recipe.key);
            } else {
                mesh = recipe.make();
            }
        }
        const MeshSize size = recipe.size ? *recipe.size : sizeOf(mesh);
        storedVertices += size.vertices;
        storedIndices += size.indices;
        checkBudget(path);
        meshSizes.push_back(size);
        if (!checkOnly) {
            if (recipe.size) mesh = recipe.make();
            scene.meshes.push_back(std::move(mesh));
        } else if (!recipe.size && objCache) {
            objCache->emplace(recipe.key, std::move(mesh));
        }
        return found->second;
    }

    // `count` more instances of `mesh`.
    void addObjects(uint64_t count, uint32_t mesh, const std::string& path) {
        objects += count;
        triangles += count * (meshSizes[mesh].indices / 3);
        checkBudget(path);
    }

    uint32_t materialFor(FieldReader& fields) {
        const json* value = fields.find("material");
        std::string name = "default";
        if (value) {
            if (!value->is_string()) fields.fail("material", "expected a material name, got " + describe(*value));
            name = value->get<std::string>();
        }
        const auto found = materialIndex.find(name);
        if (found != materialIndex.end()) return found->second;
        if (value && name != "default") {
            std::vector<std::string> names;
            for (const auto& entry : materialIndex) names.push_back(entry.first);
            fields.fail("material", "unknown material '" + name + "' (" +
                                        (names.empty() ? "the scene defines none" : "defined: " + joined(names)) + ")");
        }
        // Objects without a material share a plain grey one, added when first needed.
        Material plain;
        plain.name = name;
        materialIndex[name] = static_cast<uint32_t>(scene.materials.size());
        scene.materials.push_back(plain);
        return materialIndex[name];
    }
};

void readParameters(const json* node, const std::map<std::string, double>& overrides, ParseContext& context) {
    if (node) {
        if (!node->is_object()) {
            context.fail("parameters", "expected an object of named numbers, got " + describe(*node));
        }
        for (const auto& item : node->items()) {
            if (!item.value().is_number()) {
                context.fail(childPath("parameters", item.key()), "expected a number, got " + describe(item.value()));
            }
            context.parameters[item.key()] = item.value().get<double>();
        }
    }
    for (const auto& [name, value] : overrides) {
        if (context.parameters.count(name) == 0) {
            context.fail("parameters", "override " + name + "=" + formatNumber(value) +
                                           " names an unknown parameter (" + context.parameterList() + ")");
        }
        if (!std::isfinite(value)) context.fail(childPath("parameters", name), "override is not a finite number");
        context.parameters[name] = value;
    }
}

// A material's texture field (docs/scene-format.md, "Textures"): "file.png", {"file": ...,
// "optional": true} or {"procedural": "rose-window" | "rainbow" | "checker", ...}. Returns the
// index into Scene::textures, or -1 when an optional file cannot be used (with a warning).
int readTexture(const json& value, const std::string& path, float plainAlpha, SceneBuilder& builder) {
    const ParseContext& context = builder.context;
    std::string file;
    bool optional = false;
    std::function<Texture()> make;
    glm::ivec2 size{1};
    if (value.is_string()) {
        file = value.get<std::string>();
    } else {
        FieldReader fields(value, path, context);
        const json* fileValue = fields.find("file");
        const json* procedural = fields.find("procedural");
        if (!fileValue == !procedural) context.fail(path, "give either \"file\" or \"procedural\"");
        if (fileValue) {
            if (!fileValue->is_string()) fields.fail("file", "expected a string, got " + describe(*fileValue));
            file = fileValue->get<std::string>();
            optional = fields.boolean("optional", false);
        } else {
            if (!procedural->is_string()) fields.fail("procedural", "expected a string, got " + describe(*procedural));
            const std::string kind = procedural->get<std::string>();
            const int side = fields.integer("size", kind == "rainbow" ? 64 : 1024, 1, kMaxTextureSize);
            if (kind == "rose-window") {
                const int seed = fields.integer("seed", 1, 0, INT_MAX);
                make = [=] { return makeRoseWindowTexture(side, static_cast<uint32_t>(seed), plainAlpha); };
                size = {side, side};
            } else if (kind == "rainbow") {
                make = [=] { return makeRainbowTexture(side, plainAlpha); };
                size = {side, 1};
            } else if (kind == "checker") {
                const glm::vec4 a = fields.vec("a", glm::vec4(1.0f), Range::NonNegative);
                const glm::vec4 b = fields.vec("b", glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), Range::NonNegative);
                make = [=] { return makeCheckerTexture(side, a, b); };
                size = {side, side};
            } else {
                fields.fail("procedural", "unknown procedural texture '" + kind + "' (expected rose-window, rainbow or checker)");
            }
        }
        fields.finish("a texture");
    }
    Texture texture;
    if (!file.empty() || !make) {
        if (file.empty()) context.fail(path, "empty file name");
        const std::filesystem::path resolved = sceneFilePath(builder.baseDir, file);
        try {
            // The decoded size against what the GPU budget leaves, before the pixels are allocated.
            const uint64_t used = builder.gpuBytes();
            const uint64_t left = used < builder.budget.gpuBytes ? builder.budget.gpuBytes - used : 0;
            texture = loadPngTexture(resolved, plainAlpha, builder.budget.fileBytes, left);
        } catch (const SceneError& error) {
            if (!optional) context.fail(path, error.what());   // the message names the file
            if (!builder.checkOnly)
                logWarning(context.source + ": " + path + ": optional texture not used: " + error.what());
            return -1;
        }
        size = {texture.width, texture.height};
    }
    builder.textureBytes += uint64_t(size.x) * uint64_t(size.y) * 4;
    builder.checkBudget(path);
    if (builder.checkOnly) return 0;
    if (make) texture = make();
    builder.scene.textures.push_back(std::move(texture));
    return static_cast<int>(builder.scene.textures.size() - 1);
}

void readMaterials(const json& node, SceneBuilder& builder) {
    if (!node.is_object()) {
        builder.context.fail("materials", "expected an object of named materials, got " + describe(node));
    }
    for (const auto& item : node.items()) {
        FieldReader fields(item.value(), childPath("materials", item.key()), builder.context);
        Material material;
        material.name = item.key();
        material.baseColor = fields.vec("baseColor", material.baseColor, Range::NonNegative);
        material.alpha = fields.number("alpha", material.alpha, Range::NonNegative);
        if (material.alpha > 1.0f) {
            fields.fail("alpha", "must be between 0 and 1 (got " + formatNumber(material.alpha) + ")");
        }
        material.transmission = fields.vec("transmission", material.transmission, Range::NonNegative);
        material.specular = fields.vec("specular", material.specular, Range::NonNegative);
        material.shininess = fields.number("shininess", material.shininess, Range::Positive);
        if (const json* texture = fields.find("baseColorTexture"))
            material.baseColorTexture = readTexture(*texture, fields.pathOf("baseColorTexture"), 1.0f, builder);
        if (const json* texture = fields.find("transmissionTexture"))
            material.transmissionTexture = readTexture(*texture, fields.pathOf("transmissionTexture"), material.alpha, builder);
        fields.finish("a material");
        builder.materialIndex[material.name] = static_cast<uint32_t>(builder.scene.materials.size());
        builder.scene.materials.push_back(material);
    }
}

void readObject(const json& node, const std::string& path, size_t ordinal, SceneBuilder& builder);

// Checks `node` as an object of a scene without adding it: a builder of its own in check-only mode.
void checkObjectAlone(const json& node, const std::string& path, size_t ordinal, const SceneBuilder& builder) {
    SceneBuilder scratch;
    scratch.context = builder.context;
    scratch.baseDir = builder.baseDir;
    scratch.budget = builder.budget;
    scratch.checkOnly = true;
    scratch.materialIndex = builder.materialIndex;
    scratch.terrain = builder.terrain;
    readObject(node, path, ordinal, scratch);
}

// An obj object whose "fallback" is an array of objects (docs/scene-format.md, "Fallback groups"):
// when its file is missing the group's objects replace it, each read as a scene object of its own;
// when the file is there the group is still checked, so a broken stand-in never waits for the
// machine without the model. Returns false when `node` is not such an object.
bool readFallbackGroup(const json& node, const std::string& path, size_t ordinal, SceneBuilder& builder) {
    if (!node.is_object()) return false;
    const auto shape = node.find("shape"), group = node.find("fallback"), file = node.find("file");
    if (shape == node.end() || *shape != "obj" || group == node.end() || !group->is_array()) return false;
    if (file == node.end() || !file->is_string()) return false;   // readObject names the problem
    const std::string groupPath = path + ".fallback";
    if (group->empty() || group->size() > kMaxFallbackObjects) {
        builder.context.fail(groupPath, "expected 1 to " + std::to_string(kMaxFallbackObjects) +
                                            " objects (or one shape object), got an array of " +
                                            std::to_string(group->size()));
    }
    std::error_code error;
    const bool missing = !std::filesystem::exists(sceneFilePath(builder.baseDir, file->get<std::string>()), error);
    for (size_t i = 0; i < group->size(); ++i) {
        const json& member = (*group)[i];
        const std::string memberPath = elementPath(groupPath, i);
        const auto memberShape = member.is_object() ? member.find("shape") : member.end();
        // No nesting: a group member is procedural, so a stand-in never needs another file.
        if (member.is_object() && memberShape != member.end() && *memberShape == "obj")
            builder.context.fail(memberPath + ".shape", "expected a procedural shape in a fallback group, got 'obj'");
        if (missing) readObject(member, memberPath, i, builder);
        else checkObjectAlone(member, memberPath, i, builder);
    }
    if (missing) {
        // The model's own fields (name, material, transform, repeat) checked as those of a box.
        json standIn = node;
        standIn.erase("file");
        standIn.erase("fallback");
        standIn["shape"] = "box";
        checkObjectAlone(standIn, path, ordinal, builder);
        return true;
    }
    json model = node;
    model.erase("fallback");
    readObject(model, path, ordinal, builder);
    return true;
}

void readObject(const json& node, const std::string& path, size_t ordinal, SceneBuilder& builder) {
    if (readFallbackGroup(node, path, ordinal, builder)) return;
    FieldReader fields(node, path, builder.context);
    const json& shapeValue = fields.required("shape", std::string("one of: ") + kShapes);
    if (!shapeValue.is_string()) fields.fail("shape", "expected a string, got " + describe(shapeValue));
    const std::string shape = shapeValue.get<std::string>();
    const MeshRecipe recipe = readShape(fields, shape, builder.baseDir);

    // Bounded: every instance of a repeat block carries a copy.
    const std::string name = fields.string("name", shape + " " + std::to_string(ordinal), kMaxNameLength);
    const uint32_t material = builder.materialFor(fields);
    const glm::vec3 translate = fields.vec("translate", glm::vec3(0.0f));
    const glm::vec3 rotate = fields.vec("rotate", glm::vec3(0.0f)) * kRadiansPerDegree;
    glm::vec3 scale{1.0f};
    if (const json* value = fields.find("scale")) {
        scale = value->is_array() ? readVector<3>(*value, fields.pathOf("scale"), builder.context, Range::Positive)
                                  : glm::vec3(readFloat(*value, fields.pathOf("scale"), builder.context, Range::Positive));
    }
    const bool castsShadow = fields.boolean("castsShadow", true);
    const bool receivesShadow = fields.boolean("receivesShadow", true);
    const json* repeatNode = fields.find("repeat");
    const Repeat repeat = repeatNode ? readRepeat(*repeatNode, fields.pathOf("repeat"), builder.context) : Repeat{};
    if (repeat.followTerrain && !builder.terrain)
        builder.context.fail(fields.pathOf("repeat") + ".followTerrain", "no terrain object comes before this one");
    fields.finish("a " + shape + " object");
    if (recipe.terrain) builder.terrain = SceneBuilder::Terrain{translate, recipe.terrain->x, recipe.terrain->y};

    SceneObject object;
    object.mesh = builder.meshFor(recipe, path);
    builder.addObjects(static_cast<uint64_t>(repeat.count), object.mesh, repeatNode ? fields.pathOf("repeat") : path);
    const Bounds local = builder.meshSizes[object.mesh].bounds;
    object.material = material;
    object.castsShadow = castsShadow;
    object.receivesShadow = receivesShadow;
    object.isPlane = recipe.isPlane;

    // mt19937 produces the same sequence everywhere; the distributions of <random> do not, so
    // the conversion to [0, 1) is done here to keep scenes identical across standard libraries.
    std::mt19937 random(static_cast<uint32_t>(repeat.seed));
    auto uniform = [&random] { return static_cast<float>(random() >> 8) * (1.0f / 16777216.0f); };
    std::mt19937 placement(static_cast<uint32_t>(repeat.seed) ^ 0x9e3779b9u);
    auto uniformPlacement = [&placement] { return static_cast<float>(placement() >> 8) * (1.0f / 16777216.0f); };
    const bool inRegion = repeat.region != glm::vec3(0.0f);
    // A million instances take a while (each transform is checked): progress, and Ctrl-C.
    std::optional<Progress> progress;
    if (repeatNode) progress.emplace(builder.context.source + ": " + path + ".repeat", uint64_t(repeat.count), "instances");
    for (int i = 0; i < repeat.count; ++i) {
        if (progress) progress->stepOrThrow(uint64_t(i));
        const int column = i % repeat.columns, row = i / repeat.columns;
        const float gridX = static_cast<float>(column) - 0.5f * static_cast<float>(repeat.columns - 1);
        const float gridZ = static_cast<float>(row) - 0.5f * static_cast<float>(repeat.rows - 1);
        glm::vec3 offset{gridX * repeat.spacing.x, 0.0f, gridZ * repeat.spacing.y};
        // Six draws per instance from the placement stream, used or not.
        const glm::vec3 where{uniformPlacement(), uniformPlacement(), uniformPlacement()};
        const glm::vec3 turn{uniformPlacement(), uniformPlacement(), uniformPlacement()};
        if (inRegion) offset = (where - 0.5f) * repeat.region;
        // Four draws per instance whatever is used, so changing one range leaves the others alone.
        const glm::vec3 shake{uniform(), uniform(), uniform()};
        const float scaleChoice = uniform();
        offset += (2.0f * shake - 1.0f) * repeat.jitter;
        if (repeat.followTerrain) {
            // Only the terrain's translation is honoured: rotating or scaling hills is not modelled.
            const SceneBuilder::Terrain& t = *builder.terrain;
            const glm::vec3 at = translate + offset;
            offset.y += t.origin.y + terrainHeight(at.x - t.origin.x, at.z - t.origin.z, t.amplitude, t.wavelength);
        }
        const float instanceScale = glm::mix(repeat.scaleRange.x, repeat.scaleRange.y, scaleChoice);

        object.transform = objectToWorld(translate + offset, rotate + (2.0f * turn - 1.0f) * repeat.randomRotate,
                                         scale * instanceScale);
        if (const std::string problem = transformProblem(object.transform, local); !problem.empty())
            builder.context.fail(repeatNode ? path + " (instance " + std::to_string(i) + ")" : path, problem);
        if (builder.checkOnly) continue;
        object.name = repeatNode ? name + "#" + std::to_string(i) : name;
        if (object.isPlane) object.plane = worldPlane(object.transform);
        builder.scene.objects.push_back(object);
    }
}

// A position in world space, within +-kMaxWorldCoordinate.
glm::vec3 checkedPoint(FieldReader& fields, const std::string& key, glm::vec3 point) {
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(point[axis]) > kMaxWorldCoordinate) {
            fields.fail(key, "coordinate " + formatNumber(point[axis]) + " is beyond +-" + formatNumber(kMaxWorldCoordinate) +
                                 " (the largest coordinate shadowlab handles)");
        }
    }
    return point;
}

glm::vec3 readDirection(FieldReader& fields, const std::string& key, const std::string& why) {
    const glm::vec3 direction = readVector<3>(fields.required(key, why), fields.pathOf(key), fields.context());
    if (const std::string problem = directionProblem(direction); !problem.empty()) fields.fail(key, problem);
    return direction / glm::length(direction);
}

float readDegrees(FieldReader& fields, const std::string& key, float fallbackDegrees, float minimum, float maximum) {
    const float degrees = fields.number(key, fallbackDegrees);
    if (degrees < minimum || degrees > maximum) {
        fields.fail(key, "must be between " + formatNumber(minimum) + " and " + formatNumber(maximum) +
                             " degrees (got " + formatNumber(degrees) + ")");
    }
    return degrees * kRadiansPerDegree;
}

LightInfo readLight(const json& node, const ParseContext& context) {
    FieldReader fields(node, "light", context);
    LightInfo light;
    const std::string type = fields.string("type", "directional");
    const glm::vec3 color = fields.vec("color", glm::vec3(1.0f), Range::NonNegative);
    light.color = color * fields.number("intensity", 1.0f, Range::NonNegative);
    if (type == "directional") {
        light.type = LightType::Directional;
        if (fields.has("elevation") || fields.has("azimuth")) {
            if (fields.has("direction")) {
                fields.fail("direction", "give either direction or elevation/azimuth, not both");
            }
            const float elevation = readDegrees(fields, "elevation", 45.0f, 0.01f, 90.0f);
            const float azimuth = readDegrees(fields, "azimuth", 0.0f, -360.0f, 360.0f);
            // Towards the light is (cos e cos a, sin e, cos e sin a); the light travels the other way.
            light.direction = -glm::vec3(std::cos(elevation) * std::cos(azimuth), std::sin(elevation),
                                         std::cos(elevation) * std::sin(azimuth));
        } else {
            light.direction = readDirection(fields, "direction", "or elevation and azimuth, in degrees");
        }
        light.size = readDegrees(fields, "size", 0.0f, 0.0f, 45.0f);
    } else if (type == "spot" || type == "point") {
        light.type = type == "spot" ? LightType::Spot : LightType::Point;
        light.position = checkedPoint(fields, "position",
                                      readVector<3>(fields.required("position", "a " + type + " light needs a position"),
                                                    fields.pathOf("position"), context));
        light.size = fields.number("size", 0.0f, Range::NonNegative);
        if (const std::string problem = lightSizeProblem(light.type, light.size); !problem.empty()) fields.fail("size", problem);
        if (type == "spot") {
            if (fields.has("target")) {
                if (fields.has("direction")) fields.fail("direction", "give either direction or target, not both");
                const glm::vec3 toTarget = checkedPoint(fields, "target", fields.vec("target", glm::vec3(0.0f))) - light.position;
                if (!(glm::length(toTarget) > 1e-6f)) fields.fail("target", "target is at the light's position");
                light.direction = glm::normalize(toTarget);
            } else {
                light.direction = readDirection(fields, "direction", "or target");
            }
            light.spotOuterAngle = readDegrees(fields, "outerAngle", 30.0f, 0.1f, 89.0f);
            light.spotInnerAngle = readDegrees(fields, "innerAngle", 0.8f * light.spotOuterAngle / kRadiansPerDegree,
                                               0.0f, light.spotOuterAngle / kRadiansPerDegree);
        }
    } else {
        fields.fail("type", "unknown light type '" + type + "' (expected directional, spot or point)");
    }
    fields.finish("a " + type + " light");
    return light;
}

SceneCamera readCamera(const json& node, const ParseContext& context) {
    FieldReader fields(node, "camera", context);
    SceneCamera camera;
    camera.position = checkedPoint(fields, "position", fields.vec("position", camera.position));
    camera.target = checkedPoint(fields, "target", fields.vec("target", camera.target));
    camera.up = fields.vec("up", camera.up);
    camera.fovY = readDegrees(fields, "fovY", 45.0f, 1.0f, 170.0f);
    camera.nearPlane = fields.number("near", camera.nearPlane, Range::Positive);
    camera.farPlane = fields.number("far", camera.farPlane, Range::Positive);
    if (camera.farPlane <= camera.nearPlane) fields.fail("far", "must be greater than near");
    // The check tour steps, sessions, stress cases and every frame of a path get too.
    if (const std::string problem = cameraProblem(camera.position, camera.target); !problem.empty()) fields.fail("target", problem);
    if (const std::string problem = cameraProblem(camera.position, camera.target, glm::dvec3(camera.up)); !problem.empty())
        fields.fail("up", problem);
    fields.finish("the camera");
    return camera;
}

json parseJson(const std::string& text, const std::string& source) {
    json root;
    std::string error;
    if (!parseJsonText(text, source, root, error)) throw SceneError(error);
    return root;
}

// "builtin:cube" -> "cube", "scenes/forest.json" -> "forest".
std::string nameFromSource(const std::string& source) {
    constexpr std::string_view prefix = "builtin:";
    if (source.starts_with(prefix)) return source.substr(prefix.size());
    return std::filesystem::path(source).stem().string();
}

void buildScene(const json& root, SceneBuilder& builder, const std::map<std::string, double>& overrides) {
    const std::string& sourceName = builder.context.source;
    if (!root.is_object()) builder.context.fail("", "a scene is one JSON object, got " + describe(root));
    FieldReader fields(root, "", builder.context);

    Scene& scene = builder.scene;
    scene.source = sourceName;
    scene.name = fields.string("name", nameFromSource(sourceName), kMaxNameLength);
    scene.description = fields.string("description", "");
    readParameters(fields.find("parameters"), overrides, builder.context);
    scene.parameters = builder.context.parameters;
    if (const json* materials = fields.find("materials")) readMaterials(*materials, builder);

    const json& objects = fields.required("objects", "a scene needs at least one object");
    if (!objects.is_array() || objects.empty()) {
        fields.fail("objects", "expected a non-empty array of objects, got " + describe(objects));
    }
    for (size_t i = 0; i < objects.size(); ++i) readObject(objects[i], elementPath("objects", i), i, builder);
    if (builder.objects == 0) fields.fail("objects", "the scene has no object (every repeat count is 0)");

    if (const json* light = fields.find("light")) scene.light = readLight(*light, builder.context);
    if (const json* camera = fields.find("camera")) scene.camera = readCamera(*camera, builder.context);
    if (const json* paths = fields.find("paths")) {
        // Named camera and light paths for `--path NAME` (camera_path.h, docs/stability.md).
        if (!paths->is_object()) fields.fail("paths", "expected an object of named paths, got " + describe(*paths));
        for (const auto& item : paths->items()) {
            CameraPath path;
            std::string error;
            if (!parsePath(item.value(), sourceName + ": " + childPath("paths", item.key()), path, error)) throw SceneError(error);
            path.name = item.key();
            if (const std::string problem = pathSceneProblem(path, scene); !problem.empty()) throw SceneError(problem);
            scene.paths.push_back(std::move(path));
        }
    }
    scene.ambient = fields.vec("ambient", scene.ambient, Range::NonNegative);
    scene.background = fields.vec("background", scene.background, Range::NonNegative);
    fields.finish("a scene");
}

// The text of a built-in scene or a scene file, with its source name and the folder OBJ paths
// are relative to.
struct SceneText {
    std::string text;
    std::string source;
    std::filesystem::path baseDir;
};

SceneText readSceneText(const std::string& nameOrPath) {
    const std::string name = nameFromSource(nameOrPath.starts_with("builtin:") ? nameOrPath : "builtin:" + nameOrPath);
    for (unsigned i = 0; i < kBuiltinSceneCount; ++i) {
        if (kBuiltinScenes[i].first == name)
            return {std::string(kBuiltinScenes[i].second), "builtin:" + name, std::filesystem::current_path()};
    }
    std::error_code ignored;
    if (!std::filesystem::exists(nameOrPath, ignored)) {
        throw SceneError(nameOrPath + ": cannot open scene file (not a built-in scene either; built-in: " +
                         joined(builtinSceneNames()) + ")");
    }
    SceneText scene;
    std::string error;
    if (!readRegularFile(nameOrPath, kMaxJsonFileBytes, scene.text, error, "scene file")) throw SceneError(error);
    scene.source = nameOrPath;
    scene.baseDir = std::filesystem::path(nameOrPath).parent_path();
    if (scene.baseDir.empty()) scene.baseDir = ".";
    return scene;
}

} // namespace

Scene parseScene(const std::string& jsonText, const std::string& sourceName, const std::filesystem::path& baseDir,
                 const std::map<std::string, double>& overrides) {
    const json root = parseJson(jsonText, sourceName);
    // Two passes over the same JSON: the first checks every field and the whole budget without
    // generating a mesh or an object, so a scene over the budget allocates nothing; the second,
    // which cannot fail on anything the first checked, builds it.
    std::map<std::string, Mesh> objMeshes;
    {
        SceneBuilder check;
        check.context.source = sourceName;
        check.baseDir = baseDir;
        check.budget = sceneBudget();
        check.checkOnly = true;
        check.objCache = &objMeshes;
        buildScene(root, check, overrides);
    }
    SceneBuilder builder;
    builder.context.source = sourceName;
    builder.baseDir = baseDir;
    builder.budget = sceneBudget();
    builder.objCache = &objMeshes;
    buildScene(root, builder, overrides);
    builder.scene.computeDerived();
    return std::move(builder.scene);
}

Scene loadScene(const std::string& nameOrPath, const std::map<std::string, double>& overrides) {
    const SceneText scene = readSceneText(nameOrPath);
    return parseScene(scene.text, scene.source, scene.baseDir, overrides);
}

SceneCheck checkSceneText(const std::string& jsonText, const std::string& sourceName, const std::filesystem::path& baseDir,
                          const std::map<std::string, double>& overrides) {
    SceneBuilder builder;
    builder.context.source = sourceName;
    builder.baseDir = baseDir;
    builder.budget = sceneBudget();
    builder.checkOnly = true;
    buildScene(parseJson(jsonText, sourceName), builder, overrides);
    return {builder.scene.name,       builder.scene.light.type, builder.objects,           builder.triangles,
            builder.gpuBytes(),       builder.scene.camera,     builder.scene.light};
}

SceneCheck checkScene(const std::string& nameOrPath, const std::map<std::string, double>& overrides) {
    const SceneText text = readSceneText(nameOrPath);
    return checkSceneText(text.text, text.source, text.baseDir, overrides);
}

const SceneBudget& sceneBudget() { return processBudget(); }
void setSceneBudget(const SceneBudget& budget) { processBudget() = budget; }

uint64_t sceneGeometryBytes(const Scene& scene) {
    uint64_t bytes = scene.objects.size() * kGpuBytesPerObject;
    for (const Mesh& mesh : scene.meshes) bytes += mesh.vertices.size() * sizeof(Vertex) + mesh.indices.size() * sizeof(uint32_t);
    for (const Texture& texture : scene.textures) bytes += texture.rgba.size();
    return bytes;
}

bool parseSceneBudget(const std::string& text, SceneBudget& budget, std::string& error) {
    SceneBudget result = budget;
    std::vector<std::string> items;
    if (!splitList(text, "--budget", items, error)) return false;
    std::set<std::string> given;
    for (const std::string& item : items) {
        const size_t equals = item.find('=');
        const std::string key = item.substr(0, equals);
        // Given twice, the last would win unseen: refused, as JSON files refuse a repeated key.
        if (equals != std::string::npos && !given.insert(key).second) {
            error = "--budget '" + text + "': the key '" + key + "' is given twice";
            return false;
        }
        const std::string value = equals == std::string::npos ? "" : item.substr(equals + 1);
        // Whole numbers, written plainly or as 1e8; at most 1e15 (beyond any machine).
        double number = 0.0;
        const auto parsed = std::from_chars(value.data(), value.data() + value.size(), number);
        const bool valid = equals != std::string::npos && !value.empty() && parsed.ec == std::errc() &&
                           parsed.ptr == value.data() + value.size() && number >= 1 && number <= 1e15 &&
                           number == std::floor(number);
        if (!valid) {
            error = "--budget '" + item + "': expected key=N with N a whole number from 1 to 1e15 "
                    "(keys: objects, triangles, gpu-mib, file-mib)";
            return false;
        }
        const uint64_t n = static_cast<uint64_t>(number);
        if (key == "objects") result.objects = n;
        else if (key == "triangles") result.triangles = n;
        else if (key == "gpu-mib" && n <= (uint64_t(1) << 40)) result.gpuBytes = n << 20;
        else if (key == "file-mib" && n <= (uint64_t(1) << 40)) result.fileBytes = n << 20;
        else {
            error = "--budget '" + item + "': unknown key or value too large (keys: objects, triangles, gpu-mib, "
                    "file-mib; see " + std::string(kBudgetHelp) + ")";
            return false;
        }
    }
    budget = result;
    return true;
}

uint64_t mainTargetBytes(glm::ivec2 size, int msaaSamples) {
    const uint64_t pixels = uint64_t(std::max(size.x, 1)) * uint64_t(std::max(size.y, 1));
    return pixels * (44 + 4 + 44 * uint64_t(std::max(msaaSamples, 0)));
}

std::string renderTargetBudgetProblem(glm::ivec2 size, int msaaSamples, uint64_t geometryBytes) {
    const uint64_t targets = mainTargetBytes(size, msaaSamples);
    const uint64_t budget = sceneBudget().gpuBytes;
    if (targets + geometryBytes <= budget) return "";
    return "--size " + std::to_string(size.x) + "x" + std::to_string(size.y) +
           (msaaSamples > 0 ? " with --msaa " + std::to_string(msaaSamples) : std::string()) + ": the render targets (" +
           formatBytes(targets) + ") and the scene's geometry (" + formatBytes(geometryBytes) +
           ") would need more than the GPU memory budget of " + formatBytes(budget) + "; raise it with --budget gpu-mib=N (" +
           kBudgetHelp + ")";
}

std::string lightSizeProblem(LightType type, double size) {
    if (type == LightType::Directional) {
        if (!(size >= 0.0 && size <= kMaxDirectionalLightSizeDegrees))
            return "a directional light's size is its angular radius in degrees, 0 to 45 (got " + formatNumber(size) + ")";
    } else if (!(size >= 0.0 && size <= kMaxWorldCoordinate)) {
        return "a spot or point light's size is its emitter radius in world units, 0 to " +
               formatNumber(kMaxWorldCoordinate) + " (got " + formatNumber(size) + ")";
    }
    return "";
}

std::string cameraProblem(glm::dvec3 position, glm::dvec3 target, std::optional<glm::dvec3> up) {
    const glm::dvec3 view = target - position;
    const double distance = glm::length(view);
    if (!std::isfinite(distance)) return "the camera's position or target is not finite";
    if (!(distance > kMinCameraDistance))
        return "the target is at the camera position (" + formatNumber(distance) + " apart, at least " +
               formatNumber(kMinCameraDistance) + " needed for a view direction)";
    if (!up) return "";
    const double upLength = glm::length(*up);
    if (!(upLength > 1e-6)) return "the camera's up vector is zero";
    // The sine of the angle between the view and up: the view matrix is built from their cross product.
    if (!(glm::length(glm::cross(view / distance, *up / upLength)) > kMinCameraUpSine))
        return "the camera looks straight along its up vector (the view direction and up are parallel)";
    return "";
}

std::string directionProblem(glm::dvec3 direction) {
    const double length = glm::length(direction);
    if (!std::isfinite(length)) return "the direction is not finite";
    if (!(length > 1e-6)) return "zero-length direction";
    return "";
}

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (unsigned i = 0; i < kBuiltinSceneCount; ++i) names.emplace_back(kBuiltinScenes[i].first);
    std::sort(names.begin(), names.end());
    return names;
}

const char* defaultSceneName() { return "cube"; }

namespace {

// World bounds of every object: the eight corners of its mesh's box moved to world space (loose
// for rotated meshes, but cheap with thousands of instances, and never too small for fitting a
// shadow map). Each mesh is scanned once.
std::vector<Bounds> objectWorldBounds(const Scene& scene) {
    std::vector<Bounds> meshBounds(scene.meshes.size());
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        Bounds local{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};
        for (const Vertex& vertex : scene.meshes[m].vertices) {
            local.min = glm::min(local.min, vertex.position);
            local.max = glm::max(local.max, vertex.position);
        }
        meshBounds[m] = local;
    }
    std::vector<Bounds> out;
    out.reserve(scene.objects.size());
    for (const SceneObject& object : scene.objects) {
        if (object.mesh >= scene.meshes.size() || scene.meshes[object.mesh].vertices.empty()) {
            const glm::vec3 origin{object.transform[3]};
            out.push_back({origin, origin});
            continue;
        }
        const Bounds& local = meshBounds[object.mesh];
        glm::vec3 low{std::numeric_limits<float>::max()}, high{std::numeric_limits<float>::lowest()};
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 point{(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                                  (corner & 4) ? local.max.z : local.min.z};
            const glm::vec3 world{object.transform * glm::vec4(point, 1.0f)};
            low = glm::min(low, world);
            high = glm::max(high, world);
        }
        out.push_back({low, high});
    }
    return out;
}

Bounds setBoundsOf(const Scene& scene, const std::vector<Bounds>& objectBounds, DrawSet set) {
    glm::vec3 low{std::numeric_limits<float>::max()};
    glm::vec3 high{std::numeric_limits<float>::lowest()};
    bool any = false;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        if (!scene.inSet(object, set) || object.mesh >= scene.meshes.size() || scene.meshes[object.mesh].vertices.empty())
            continue;
        low = glm::min(low, objectBounds[i].min);
        high = glm::max(high, objectBounds[i].max);
        any = true;
    }
    if (!any) return {glm::vec3(0.0f), glm::vec3(0.0f)};   // an empty set: a point, not inverted infinities
    return {low, high};
}

} // namespace

void Scene::computeDerived() {
    const std::vector<Bounds> bounds = objectWorldBounds(*this);
    objectInfo.clear();
    objectInfo.reserve(objects.size());
    for (size_t i = 0; i < objects.size(); ++i) {
        const SceneObject& object = objects[i];
        const Material material = object.material < materials.size() ? materials[object.material] : Material{};
        ObjectInfo info;
        info.bounds = bounds[i];
        info.center = 0.5f * (bounds[i].min + bounds[i].max);
        info.flags = (object.castsShadow ? kObjectCastsShadow : 0u) | (object.receivesShadow ? kObjectReceivesShadow : 0u) |
                     (material.translucent() ? kObjectTranslucent : 0u) | (object.isPlane ? kObjectPlane : 0u);
        info.baseColor = material.baseColor;
        info.alpha = material.alpha;
        info.transmission = material.transmission;
        info.material = object.material;
        info.plane = object.plane;
        objectInfo.push_back(info);
    }
    for (size_t set = 0; set < setBounds.size(); ++set) setBounds[set] = setBoundsOf(*this, bounds, DrawSet(set));
}

Bounds Scene::worldBounds(DrawSet set) const {
    if (objectInfo.size() == objects.size() && !objects.empty()) return setBounds[size_t(set)];
    return setBoundsOf(*this, objectWorldBounds(*this), set);
}

size_t Scene::triangleCount() const {
    size_t triangles = 0;
    for (const SceneObject& object : objects) {
        if (object.mesh < meshes.size()) triangles += meshes[object.mesh].indices.size() / 3;
    }
    return triangles;
}

bool Scene::inSet(const SceneObject& object, DrawSet set) const {
    const bool translucent = object.material < materials.size() && materials[object.material].translucent();
    switch (set) {
    case DrawSet::All: return true;
    case DrawSet::Casters: return object.castsShadow;
    case DrawSet::Receivers: return object.receivesShadow;
    case DrawSet::OpaqueCasters: return object.castsShadow && !translucent;
    case DrawSet::TranslucentCasters: return object.castsShadow && translucent;
    case DrawSet::Opaque: return !translucent;
    case DrawSet::Translucent: return translucent;
    }
    return false;
}

} // namespace shadowlab
