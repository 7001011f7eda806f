// shadowlab_groundtruth_bench: wall times of the ray-traced reference at 1280x720 (BVH build,
// CPU G-buffer, hard reference, N-sample soft reference) for a cube scene and a spheres scene
// built in code, or for scenes named on the command line (loadScene). Timings are printed, not
// asserted; the targets are 1 s (hard) and 30 s (64-sample soft) on 2 cores.
//
//   shadowlab_groundtruth_bench [--threads N] [--spp N] [--width W --height H] [scene ...]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <thread>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "groundtruth/groundtruth.h"
#include "groundtruth/metrics.h"
#include "scene/scene.h"

using namespace shadowlab;

namespace {

Scene groundScene(const char* name) {
    Scene scene;
    scene.name = name;
    scene.source = std::string("bench:") + name;
    scene.materials = {Material{}};
    scene.meshes.push_back(makePlane(20.0f, 20.0f, 1));
    SceneObject ground;
    ground.name = "ground";
    ground.isPlane = true;
    scene.objects.push_back(ground);
    scene.light.type = LightType::Directional;
    scene.light.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
    scene.light.size = 0.05f; // radians, about three times the sun's
    scene.camera.position = glm::vec3(4.0f, 4.0f, 6.0f);
    scene.camera.target = glm::vec3(0.0f, 0.5f, 0.0f);
    return scene;
}

void addObject(Scene& scene, std::string name, uint32_t mesh, glm::vec3 position) {
    SceneObject object;
    object.name = std::move(name);
    object.mesh = mesh;
    object.transform = glm::translate(glm::mat4(1.0f), position);
    scene.objects.push_back(object);
}

Scene cubeScene() {
    Scene scene = groundScene("cube");
    scene.meshes.push_back(makeBox(glm::vec3(1.0f)));
    addObject(scene, "box", 1, {0.0f, 0.5f, 0.0f});
    return scene;
}

// 25 small spheres sharing one mesh (instanced in the BVH) and one large sphere of its own.
Scene spheresScene() {
    Scene scene = groundScene("spheres");
    scene.meshes.push_back(makeSphere(0.35f, 64, 32));
    scene.meshes.push_back(makeSphere(1.0f, 96, 48));
    for (int i = 0; i < 25; ++i)
        addObject(scene, "sphere" + std::to_string(i), 1,
                  {-2.4f + 1.2f * static_cast<float>(i % 5), 0.35f, -2.4f + 1.2f * static_cast<float>(i / 5)});
    addObject(scene, "big", 2, {0.0f, 1.6f, 0.0f});
    return scene;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv) {
    int threads = 0, samples = 64, width = 1280, height = 720;
    std::vector<std::string> names;
    for (int i = 1; i < argc; ++i) {
        auto value = [&](const char* flag) {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", flag);
                std::exit(2);
            }
            return std::atoi(argv[++i]);
        };
        if (!std::strcmp(argv[i], "--threads")) threads = value("--threads");
        else if (!std::strcmp(argv[i], "--spp")) samples = value("--spp");
        else if (!std::strcmp(argv[i], "--width")) width = value("--width");
        else if (!std::strcmp(argv[i], "--height")) height = value("--height");
        else if (argv[i][0] == '-') {
            std::fprintf(stderr, "usage: %s [--threads N] [--spp N] [--width W --height H] [scene ...]\n", argv[0]);
            return 2;
        } else names.emplace_back(argv[i]);
    }

    std::string error;
    GroundTruthPtr groundTruth = loadGroundTruth(error);
    if (!groundTruth) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }

    std::vector<Scene> scenes;
    try {
        if (names.empty()) {
            scenes.push_back(cubeScene());
            scenes.push_back(spheresScene());
        }
        for (const std::string& name : names) scenes.push_back(loadScene(name));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }

    const unsigned cores = std::thread::hardware_concurrency();
    std::printf("ground truth %dx%d, %d thread(s) (%u hardware), soft: %d samples per pixel\n", width, height,
                threads > 0 ? threads : static_cast<int>(cores), cores, samples);
    std::printf("%-10s %10s %8s %10s %10s %10s %9s\n", "scene", "triangles", "bvh s", "primary s", "hard s", "soft s",
                "compared");
    for (Scene& scene : scenes) {
        size_t triangles = 0;
        for (const SceneObject& object : scene.objects) triangles += scene.meshes[object.mesh].indices.size() / 3;
        if (scene.light.size <= 0.0f) // give the soft run an emitter to sample
            scene.light.size = scene.light.type == LightType::Directional ? 0.05f : 0.2f;

        auto start = std::chrono::steady_clock::now();
        groundTruth->setScene(scene);
        const double bvh = secondsSince(start);

        const SceneCamera& camera = scene.camera;
        const glm::mat4 viewProjection =
            glm::perspective(camera.fovY, static_cast<float>(width) / static_cast<float>(height), camera.nearPlane,
                             camera.farPlane) *
            glm::lookAt(camera.position, camera.target, camera.up);
        std::vector<glm::vec4> positions, normals;
        start = std::chrono::steady_clock::now();
        groundTruth->tracePrimary(viewProjection, camera.position, width, height, positions, normals);
        const double primary = secondsSince(start);
        const GBufferView gbuffer{width, height, positions.data(), normals.data()};

        ReferenceOptions options;
        options.threads = threads;
        std::vector<glm::vec3> hard, soft;
        start = std::chrono::steady_clock::now();
        groundTruth->trace(gbuffer, scene.light, options, hard);
        const double hardSeconds = secondsSince(start);

        options.mode = ReferenceOptions::Mode::Soft;
        options.samplesPerPixel = samples;
        start = std::chrono::steady_clock::now();
        groundTruth->trace(gbuffer, scene.light, options, soft);
        const double softSeconds = secondsSince(start);

        const std::vector<uint8_t> mask = compareMask(gbuffer, scene.light);
        const AccuracyMetrics hardVsSoft = compareVisibility(hard, soft, mask, width, height);
        std::printf("%-10s %10zu %8.3f %10.3f %10.3f %10.3f %8.1f%%\n", scene.name.c_str(), triangles, bvh, primary,
                    hardSeconds, softSeconds, 100.0 * hardVsSoft.comparedFraction);
        std::printf("           hard vs soft reference: %s\n", metricsToJson(hardVsSoft).c_str());
    }
    return 0;
}
