// The fuzzing harness's entry points (see fuzz_inputs.h).
#include "fuzz_inputs.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "bench/bench_spec.h"
#include "bench/stress.h"
#include "scene/camera_path.h"
#include "scene/scene.h"
#include "ui/tour.h"
#include "util/text_file.h"

namespace shadowlab::fuzz {
namespace {

[[noreturn]] void broken(const std::string& what) {
    std::fprintf(stderr, "fuzz: broken promise: %s\n", what.c_str());
    std::abort();
}

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

void checkMesh(const Mesh& mesh, const char* what) {
    if (mesh.indices.size() % 3 != 0) broken(std::string(what) + ": index count not a multiple of 3");
    for (uint32_t index : mesh.indices)
        if (index >= mesh.vertices.size()) broken(std::string(what) + ": index out of range");
    for (const Vertex& v : mesh.vertices) {
        if (!finite(v.position)) broken(std::string(what) + ": non-finite position");
        if (!finite(v.normal) || std::abs(glm::length(v.normal) - 1.0f) > 1e-3f) broken(std::string(what) + ": bad normal");
    }
}

// Techniques with one parameter of every type, named like real ones so specs from assets/bench
// (the seed corpus) get far.
const std::vector<TechniqueInfo>& techniques() {
    static const std::vector<TechniqueInfo> list = [] {
        std::vector<TechniqueInfo> out(3);
        out[0].id = "shadowmap";
        out[0].category = "hard";
        out[0].params = {{"resolution", "", ParamType::Int, 256, 8192, 2048, "", "", {}},
                         {"constant_bias", "", ParamType::Float, 0, 20, 2, "", "", {}},
                         {"hardware_filter", "", ParamType::Bool, 0, 1, 0, "", "", {}},
                         {"depth_format", "", ParamType::Enum, 0, 2, 2, "", "", {"16", "24", "32F"}}};
        out[1].id = "pcf";
        out[1].category = "filtered";
        out[1].params = {{"resolution", "", ParamType::Int, 256, 8192, 2048, "", "", {}},
                         {"kernel", "", ParamType::Int, 1, 15, 5, "", "", {}}};
        out[2].id = "reference";
        out[2].category = "reference";
        return out;
    }();
    return list;
}

} // namespace

void useFuzzBudget() {
    SceneBudget budget;
    budget.objects = 20000;
    budget.triangles = 2'000'000;
    budget.gpuBytes = uint64_t(256) << 20;
    budget.fileBytes = uint64_t(16) << 20;
    setSceneBudget(budget);
}

bool fuzzScene(const uint8_t* data, size_t size, const std::filesystem::path& objDir) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string parseError, checkError;
    Scene scene;
    SceneCheck check;
    try {
        scene = parseScene(text, "fuzz.json", objDir);
    } catch (const SceneError& e) {
        parseError = e.what();
    }
    try {
        check = checkSceneText(text, "fuzz.json", objDir);
    } catch (const SceneError& e) {
        checkError = e.what();
    }
    if (parseError != checkError) broken("parseScene and checkScene disagree: '" + parseError + "' vs '" + checkError + "'");
    if (!parseError.empty()) {
        if (parseError.rfind("fuzz.json", 0) != 0) broken("the error does not name the file: " + parseError);
        return false;
    }
    uint64_t triangles = 0;
    for (const SceneObject& object : scene.objects) {
        if (object.mesh >= scene.meshes.size() || object.material >= scene.materials.size()) broken("object refers nowhere");
        for (int c = 0; c < 4; ++c)
            if (!finite(glm::vec3(object.transform[c])) || !std::isfinite(object.transform[c][3])) broken("non-finite transform");
        triangles += scene.meshes[object.mesh].indices.size() / 3;
    }
    for (const Mesh& mesh : scene.meshes) checkMesh(mesh, "scene mesh");
    if (check.objects != scene.objects.size() || check.triangles != triangles || check.gpuBytes != sceneGeometryBytes(scene))
        broken("checkScene's counts differ from the parsed scene's");
    if (scene.objects.size() > sceneBudget().objects || triangles > sceneBudget().triangles ||
        sceneGeometryBytes(scene) > sceneBudget().gpuBytes)
        broken("a scene over the budget was accepted");
    if (!finite(scene.light.position) || !finite(scene.light.direction) || !std::isfinite(scene.light.size))
        broken("non-finite light");
    return true;
}

bool fuzzObj(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const Mesh mesh = parseObj(text, "fuzz.obj");
        if (mesh.indices.empty()) broken("an OBJ without triangles was accepted");
        checkMesh(mesh, "OBJ mesh");
        return true;
    } catch (const SceneError& e) {
        const std::string message = e.what();
        if (message.rfind("fuzz.obj", 0) != 0) broken("the error does not name the file: " + message);
        // The pre-scan passed something tinyobjloader read otherwise: the pre-scan must be tightened.
        if (message.find("differently from the pre-scan") != std::string::npos) broken(message);
        return false;
    }
}

bool fuzzBenchSpec(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string error;
    nlohmann::json json;
    if (!parseJsonText(text, "fuzz-spec.json", json, error)) {
        if (error.empty()) broken("a JSON error without a message");
        // Not JSON: the lines as command-line values.
        std::istringstream lines(text);
        BenchSpec spec;
        spec.fromCommandLine = true;
        for (std::string line; std::getline(lines, line);) {
            glm::ivec2 size2;
            SceneBudget budget;
            if (!addSweep(spec, line, error) && error.empty()) broken("addSweep failed without a message");
            if (!parseSize(line, size2, error) && error.empty()) broken("parseSize failed without a message");
            if (parseSize(line, size2, error) && (size2.x < kMinRenderSize || size2.y > kMaxRenderSize)) broken("size out of range");
            if (!parseSceneBudget(line, budget, error) && error.empty()) broken("parseSceneBudget failed without a message");
            if (const auto number = parseNumberText(line); number && !std::isfinite(*number)) broken("a non-finite number");
        }
        bool accepted = !spec.sweeps.empty();
        if (!checkBenchSpec(spec, techniques(), error)) {
            if (error.empty()) broken("checkBenchSpec failed without a message");
            accepted = false;
        }
        return accepted;
    }
    if (!json.is_array()) json = nlohmann::json::array({json});
    bool accepted = !json.empty();
    for (const auto& item : json) {
        BenchSpec spec;
        if (!parseBenchSpec(item, spec, error)) {
            if (error.empty()) broken("parseBenchSpec failed without a message");
            accepted = false;
            continue;
        }
        if (!checkBenchSpec(spec, techniques(), error)) {
            if (error.empty()) broken("checkBenchSpec failed without a message");
            accepted = false;
        }
    }
    return accepted;
}

bool fuzzTour(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string error;
    nlohmann::json json;
    if (!parseJsonText(text, "fuzz-tour.json", json, error)) {
        if (error.rfind("fuzz-tour.json", 0) != 0) broken("a JSON error that does not name the file: " + error);
        return false;
    }
    Tour tour;
    bool accepted = false;
    if (json.is_object() && !json.contains("steps") && json.contains("caption")) {
        // A session file: one step.
        TourStep step;
        accepted = parseTourStep(json, "fuzz-tour.json", {}, step, error) && checkTourStep(step, "fuzz-tour.json", techniques(), error);
        if (accepted) tour.steps.push_back(step);
    } else {
        accepted = parseTour(json, "fuzz-tour.json", {}, tour, error) && checkTour(tour, techniques(), error);
    }
    if (!accepted) {
        if (error.rfind("fuzz-tour.json", 0) != 0) broken("the error does not name the file: " + error);
        return false;
    }
    for (const TourStep& step : tour.steps) {
        bool known = false;
        for (const auto& t : techniques()) known |= t.id == step.technique;
        if (!known) broken("an unknown technique was accepted: " + step.technique);
        if (step.caption.empty() || step.caption.size() > kMaxCaptionBytes) broken("a caption out of bounds was accepted");
        TourStep again;
        const nlohmann::json written = tourStepJson(step);
        if (!parseTourStep(written, "again", {}, again, error)) broken("a written step does not read back: " + error);
        if (tourStepJson(again) != written) broken("a written step reads back differently: " + written.dump());
    }
    return true;
}

bool fuzzSession(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string error;
    TourStep step;
    if (!parseSessionText(text, "fuzz-session.json", {}, techniques(), step, error)) {
        if (error.rfind("fuzz-session.json", 0) != 0) broken("the error does not name the file: " + error);
        return false;
    }
    bool known = false;
    for (const auto& t : techniques()) known |= t.id == step.technique;
    if (!known) broken("an unknown technique was accepted: " + step.technique);
    if (step.caption.empty() || step.caption.size() > kMaxCaptionBytes) broken("a caption out of bounds was accepted");
    if (step.camera && !cameraProblem(step.camera->position, step.camera->target).empty())
        broken("a degenerate camera was accepted: " + cameraProblem(step.camera->position, step.camera->target));
    if (step.light.direction && !directionProblem(*step.light.direction).empty()) broken("a zero light direction was accepted");
    // What F5 writes reads back as the same step, through the same reader.
    const std::string written = tourStepJson(step).dump(2);
    TourStep again;
    if (!parseSessionText(written, "again.json", {}, techniques(), again, error)) broken("a saved session does not read back: " + error);
    if (tourStepJson(again).dump(2) != written) broken("a saved session reads back differently: " + written);
    return true;
}

bool fuzzPath(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::string error;
    nlohmann::json json;
    if (!parseJsonText(text, "fuzz-path.json", json, error)) {
        if (error.empty()) broken("a JSON error without a message");
        return false;
    }
    bool accepted = false;
    CameraPath path;
    if (parsePath(json, "fuzz-path.json", path, error)) {
        if (path.frames < 1 || path.frames > 100000) broken("a path with a frame count out of range");
        // What a scene checks before drawing a path (every frame, from its camera and light; a
        // spot light takes every form of light keyframe): a path it accepts samples to finite
        // values (the first, the last and a few frames between).
        LightInfo spot;
        spot.type = LightType::Spot;
        const std::string problem = pathProblem(path, "fuzz", SceneCamera{}, spot);
        if (!problem.empty() && problem.rfind("fuzz-path.json", 0) != 0) broken("the path's problem does not name it: " + problem);
        accepted = problem.empty();
        for (int frame : {0, path.frames / 3, path.frames / 2, path.frames - 1}) {
            if (!problem.empty()) break;
            const PathState state = samplePath(path, path.frameTime(frame));
            for (const auto& v : {state.cameraPosition, state.cameraTarget, state.cameraOrbit, state.lightDirection, state.lightPosition})
                if (v && !finite(*v)) broken("a path samples to a non-finite value");
            if (state.lightSize && !std::isfinite(*state.lightSize)) broken("a path samples to a non-finite light size");
        }
    } else if (error.rfind("fuzz-path.json", 0) != 0) {
        broken("the error does not name the file: " + error);
    }
    StressSuite suite;
    if (parseStressSuite(json, "fuzz-cases.json", suite, error)) {
        accepted = true;
        if (suite.cases.empty()) broken("a stress suite without cases was accepted");
    } else if (error.rfind("fuzz-cases.json", 0) != 0) {
        broken("the error does not name the file: " + error);
    }
    return accepted;
}

bool fuzzTexture(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        // 64 MiB of decoded texels at most, so inputs at the budget stay fast.
        const Texture texture = decodePngTexture(bytes, "fuzz.png", 0.5f, uint64_t(64) << 20);
        if (texture.width < 1 || texture.height < 1 || texture.width > kMaxTextureSize || texture.height > kMaxTextureSize)
            broken("a texture of a size out of range was accepted");
        if (texture.rgba.size() != size_t(texture.width) * size_t(texture.height) * 4) broken("texels and size disagree");
        return true;
    } catch (const SceneError& e) {
        if (std::string(e.what()).rfind("fuzz.png: ", 0) != 0) broken(std::string("the error does not name the file: ") + e.what());
        return false;
    }
}

} // namespace shadowlab::fuzz
