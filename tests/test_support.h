// Helpers shared by the GL tests: a headless App on OSMesa (the CI backend) and pixel access.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>

#include "app.h"

namespace shadowlab::test {

// A scene file written for one test (in the temporary folder), removed afterwards.
class SceneFile {
public:
    SceneFile(const std::string& name, const std::string& json) {
        path_ = std::filesystem::temp_directory_path() /
                ("shadowlab_" + name + "_" + std::to_string(std::random_device{}()) + ".json");
        std::ofstream(path_, std::ios::binary) << json;
    }
    ~SceneFile() {
        std::error_code ignored;
        std::filesystem::remove(path_, ignored);
    }
    SceneFile(const SceneFile&) = delete;
    SceneFile& operator=(const SceneFile&) = delete;
    std::string path() const { return path_.string(); }

private:
    std::filesystem::path path_;
};

// The message of the SceneError `load` throws ("" and a test failure when it throws none).
template <typename Load>
std::string sceneErrorOf(Load load) {
    try {
        load();
    } catch (const SceneError& error) {
        return error.what();
    }
    ADD_FAILURE() << "no SceneError thrown";
    return "";
}

// Headless App on OSMesa with the given scene; fails the test (and returns nullptr) otherwise.
inline std::unique_ptr<App> makeHeadlessApp(const std::string& scene, glm::ivec2 size = {320, 240},
                                            std::optional<glm::vec3> lightDirection = std::nullopt) {
    auto app = std::make_unique<App>();
    AppOptions options;
    options.scene = scene;
    options.size = size;
    options.backend = BackendKind::OSMesa;
    options.lightDirection = lightDirection;
    std::string error;
    bool badInput = false;
    if (!app->init(options, false, error, badInput)) {
        ADD_FAILURE() << "App init failed: " << error;
        return nullptr;
    }
    return app;
}

// A main target of the last frame. Timed frames write the colour only, so for the others the
// frame's main pass is re-run with the accuracy targets first (App::renderAccuracyTargets).
inline std::vector<glm::vec4> readTarget(App& app, MainTarget which) {
    if (which != MainTarget::Color) {
        std::string error;
        EXPECT_TRUE(app.renderAccuracyTargets(error)) << error;
    }
    return app.renderer().readTarget(which);
}

// Renders `technique` and returns the visibility target (rgb shadow term, a = compared mask).
inline std::vector<glm::vec4> renderVisibility(App& app, const std::string& technique,
                                               const std::vector<std::string>& sets = {}) {
    std::string error;
    EXPECT_TRUE(app.applyAssignments(sets, technique, error)) << error;
    EXPECT_TRUE(app.renderFrame(technique, error)) << error;
    return test::readTarget(app, MainTarget::Visibility);
}

// Analytic shadow of the object named "cube" on the ground (y = 0) under the current directional
// light: a ground point is shadowed iff its ray towards the light hits the box.
// Ray/box slab test in the box's object space.
inline bool rayHitsBox(glm::vec3 origin, glm::vec3 direction, const glm::mat4& boxToWorld, glm::vec3 boxMin, glm::vec3 boxMax) {
    const glm::mat4 worldToBox = glm::inverse(boxToWorld);
    const glm::vec3 o = glm::vec3(worldToBox * glm::vec4(origin, 1.0f));
    const glm::vec3 d = glm::vec3(worldToBox * glm::vec4(direction, 0.0f));
    float tNear = 0.0f, tFar = 1e30f;
    for (int axis = 0; axis < 3; ++axis) {
        if (std::abs(d[axis]) < 1e-12f) {
            if (o[axis] < boxMin[axis] || o[axis] > boxMax[axis]) return false;
            continue;
        }
        float t0 = (boxMin[axis] - o[axis]) / d[axis], t1 = (boxMax[axis] - o[axis]) / d[axis];
        if (t0 > t1) std::swap(t0, t1);
        tNear = std::max(tNear, t0);
        tFar = std::min(tFar, t1);
        if (tNear > tFar) return false;
    }
    return true;
}

struct GroundClassification {
    std::vector<int> analytic;   // per pixel: -1 not ground, 0 lit, 1 in the box's shadow
    glm::ivec2 size;
    // True when a pixel within `band` pixels has the other class (or is not ground).
    bool nearBoundary(int x, int y, int band) const {
        const int centre = analytic[size_t(y) * size_t(size.x) + size_t(x)];
        for (int dy = -band; dy <= band; ++dy)
            for (int dx = -band; dx <= band; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= size.x || ny >= size.y) continue;
                if (analytic[size_t(ny) * size_t(size.x) + size_t(nx)] != centre) return true;
            }
        return false;
    }
};

inline GroundClassification classifyGround(App& app) {
    const Scene& scene = app.scene();
    const SceneObject* cube = nullptr;
    for (const auto& object : scene.objects)
        if (object.name == "cube") cube = &object;
    EXPECT_TRUE(cube) << "the cube scene has an object named 'cube'";
    glm::vec3 boxMin(1e30f), boxMax(-1e30f);
    for (const Vertex& v : scene.meshes[cube->mesh].vertices) {
        boxMin = glm::min(boxMin, v.position);
        boxMax = glm::max(boxMax, v.position);
    }
    const glm::vec3 toLight = -glm::normalize(app.light().direction);
    const auto positions = test::readTarget(app, MainTarget::Position);
    const auto normals = test::readTarget(app, MainTarget::Normal);
    GroundClassification out{std::vector<int>(positions.size(), -1), app.renderer().size()};
    for (size_t i = 0; i < positions.size(); ++i) {
        const bool ground = positions[i].w > 0.5f && std::abs(positions[i].y) < 1e-3f && normals[i].y > 0.99f;
        if (!ground) continue;
        out.analytic[i] = rayHitsBox(glm::vec3(positions[i]), toLight, cube->transform, boxMin, boxMax) ? 1 : 0;
    }
    return out;
}

// `visibility` (a frame of `cube`) against the cube's analytic shadow on the ground, pixels within
// 3 of its edge left out: at least 95% of those inside it dark, 99% of those outside lit.
inline void expectAnalyticCubeShadow(App& app, const std::vector<glm::vec4>& visibility) {
    const GroundClassification ground = classifyGround(app);
    int inside = 0, insideDark = 0, outside = 0, outsideLit = 0;
    for (int y = 0; y < ground.size.y; ++y)
        for (int x = 0; x < ground.size.x; ++x) {
            const size_t i = size_t(y) * size_t(ground.size.x) + size_t(x);
            if (ground.analytic[i] < 0 || ground.nearBoundary(x, y, 3)) continue;
            if (ground.analytic[i] == 1) {
                ++inside;
                insideDark += visibility[i].r < 0.5f;
            } else {
                ++outside;
                outsideLit += visibility[i].r > 0.5f;
            }
        }
    ASSERT_GT(inside, 50);
    EXPECT_GE(insideDark, inside * 95 / 100) << "shadowed inside the cube's analytic shadow";
    EXPECT_GE(outsideLit, outside * 99 / 100) << "lit well outside it";
}


// One frame of `technique` (after `sets`) evaluated against the reference of the given mode:
// the technique's shadow term per pixel as App::evaluate reads it (Evaluation::technique), the
// reference and the accuracy. Tests that compare two techniques' shadow terms use this rather
// than the visibility target.
inline Evaluation evaluateTechnique(App& app, const std::string& technique, const std::vector<std::string>& sets,
                                    ReferenceOptions::Mode mode, int samples = 32,
                                    TranslucencyModel model = TranslucencyModel::Opaque, const EvaluationParts& parts = {}) {
    std::string error;
    EXPECT_TRUE(app.applyAssignments(sets, technique, error)) << error;
    for (int frame = 0; frame < 2; ++frame) EXPECT_TRUE(app.renderFrame(technique, error)) << error;
    ReferenceOptions options;
    options.mode = mode;
    options.samplesPerPixel = samples;
    options.model = model;
    Evaluation evaluation;
    EXPECT_TRUE(app.evaluate(options, evaluation, error, parts)) << error;
    return evaluation;
}

// Only the technique's shadow term per pixel, as evaluateTechnique reads it, for tests that
// compare two techniques' terms: the metrics' optional parts (texel footprint, contact band) are
// left out, which were most of such a test's time (issue 31).
inline std::vector<glm::vec3> shadowTerm(App& app, const std::string& technique, const std::vector<std::string>& sets) {
    return evaluateTechnique(app, technique, sets, ReferenceOptions::Mode::Hard, 1, TranslucencyModel::Opaque,
                             EvaluationParts{false, false, false})
        .technique;
}

// Accuracy of `technique` (after `sets`) against the reference of the given mode, on one frame.
inline AccuracyMetrics measureAccuracy(App& app, const std::string& technique, const std::vector<std::string>& sets,
                                       ReferenceOptions::Mode mode, int samples = 32,
                                       TranslucencyModel model = TranslucencyModel::Opaque) {
    return evaluateTechnique(app, technique, sets, mode, samples, model).metrics;
}

} // namespace shadowlab::test
