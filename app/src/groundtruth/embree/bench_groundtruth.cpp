// shadowlab_groundtruth_bench: wall times of the ray-traced reference at 1280x720 (BVH build,
// CPU G-buffer, hard reference, N-sample soft reference) for a cube scene and a spheres scene
// built in code, or for scenes named on the command line (loadScene). Timings are printed, not
// asserted; the targets are 1 s (hard) and 30 s (64-sample soft) on 2 cores.
//
//   shadowlab_groundtruth_bench [--threads N] [--spp N] [--width W --height H] [scene ...]
//
// --adaptive N: the adaptive soft reference instead (a first batch of --first-batch rays, all N
// within --radius pixels of a split batch) timed against the uniform --spp reference (today's 64)
// and the uniform N reference, with the reference's own penumbra error (its floor, estimated per
// pixel; and measured: the MAE between two uniform N references of different seeds / sqrt 2).
//
//   shadowlab_groundtruth_bench --adaptive 1024 [--first-batch 32] [--radius 2] [--quick] [--threads N] [scene ...]
//
// --quick: the uniform --spp and the adaptive reference only (no uniform N, no comparisons).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
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

struct BenchOptions {
    int threads = 0, samples = 64, width = 1280, height = 720, adaptive = 0, firstBatch = 32, radius = 2;
    bool quick = false;
    std::vector<std::string> names;
};

// Returns false (after printing the usage) on an unknown option.
bool parseOptions(int argc, char** argv, BenchOptions& o) {
    for (int i = 1; i < argc; ++i) {
        auto value = [&](const char* flag) {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "%s needs a value\n", flag);
                std::exit(2);
            }
            return std::atoi(argv[++i]);
        };
        if (!std::strcmp(argv[i], "--threads")) o.threads = value("--threads");
        else if (!std::strcmp(argv[i], "--spp")) o.samples = value("--spp");
        else if (!std::strcmp(argv[i], "--width")) o.width = value("--width");
        else if (!std::strcmp(argv[i], "--height")) o.height = value("--height");
        else if (!std::strcmp(argv[i], "--adaptive")) o.adaptive = value("--adaptive");
        else if (!std::strcmp(argv[i], "--first-batch")) o.firstBatch = value("--first-batch");
        else if (!std::strcmp(argv[i], "--radius")) o.radius = value("--radius");
        else if (!std::strcmp(argv[i], "--quick")) o.quick = true;
        else if (argv[i][0] == '-') {
            std::fprintf(stderr,
                         "usage: %s [--threads N] [--spp N] [--width W --height H] [--adaptive N [--first-batch B] "
                         "[--radius R] [--quick]] [scene ...]\n",
                         argv[0]);
            return false;
        } else o.names.emplace_back(argv[i]);
    }
    return true;
}

// The scene camera's view-projection at the bench's image size.
glm::mat4 viewProjectionOf(const SceneCamera& camera, const BenchOptions& o) {
    return glm::perspective(camera.fovY, static_cast<float>(o.width) / static_cast<float>(o.height), camera.nearPlane,
                            camera.farPlane) *
           glm::lookAt(camera.position, camera.target, camera.up);
}

// --adaptive N: the adaptive soft reference against uniform sampling (time, refined pixels, error
// floor), scene by scene.
void compareAdaptive(IGroundTruth& groundTruth, std::vector<Scene>& scenes, const BenchOptions& o) {
    const unsigned cores = std::thread::hardware_concurrency();
    std::printf("soft reference %dx%d, %d thread(s) (%u hardware): uniform %d against adaptive %d (first batch %d, "
                "radius %d) and uniform %d\n",
                o.width, o.height, o.threads > 0 ? o.threads : static_cast<int>(cores), cores, o.samples, o.adaptive, o.firstBatch,
                o.radius, o.adaptive);
    for (Scene& scene : scenes) {
        if (scene.light.size <= 0.0f) scene.light.size = scene.light.type == LightType::Directional ? 0.05f : 0.2f;
        groundTruth.setScene(scene);
        const SceneCamera& camera = scene.camera;
        const glm::mat4 viewProjection = viewProjectionOf(camera, o);
        std::vector<glm::vec4> positions, normals;
        groundTruth.tracePrimary(viewProjection, camera.position, o.width, o.height, positions, normals);
        const GBufferView gbuffer{o.width, o.height, positions.data(), normals.data()};
        const std::vector<uint8_t> mask = compareMask(gbuffer, scene.light);

        struct Run {
            const char* name;
            int samples;
            bool adaptive;
            uint32_t seed;
            std::vector<glm::vec3> image;
            ReferenceStats stats;
            double seconds = 0.0, cpuSeconds = 0.0, floor = 0.0;
        };
        Run runs[] = {{"uniform", o.samples, false, 1, {}, {}, 0.0, 0.0, 0.0}, {"adaptive", o.adaptive, true, 1, {}, {}, 0.0, 0.0, 0.0},
                      {"uniform", o.adaptive, false, 1, {}, {}, 0.0, 0.0, 0.0},
                      {"uniform", o.adaptive, false, 2, {}, {}, 0.0, 0.0, 0.0}};
        for (Run& run : runs) {
            if (o.quick && &run - runs >= 2) break;
            ReferenceOptions options;
            options.mode = ReferenceOptions::Mode::Soft;
            options.threads = o.threads;
            options.samplesPerPixel = run.samples;
            options.adaptive = run.adaptive;
            options.firstBatch = o.firstBatch;
            options.refineRadius = o.radius;
            options.seed = run.seed;
            const auto start = std::chrono::steady_clock::now();
            const std::clock_t cpuStart = std::clock();
            groundTruth.trace(gbuffer, scene.light, options, run.image, &run.stats);
            run.seconds = secondsSince(start);
            // CPU time of the whole process (every tracing thread): on a shared machine the
            // wall time also counts other jobs' use of the cores.
            run.cpuSeconds = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
            run.floor = penumbraMean(run.stats.sampleError, run.image, mask, o.width, o.height);
            std::printf("%-12s %-8s %5d rays seed %u: %8.2f s wall, %8.2f s CPU, %6.2f%% of %zu pixels refined, "
                        "%.1f rays per pixel, floor (estimated) %.5f\n",
                        scene.name.c_str(), run.name, run.samples, run.seed, run.seconds, run.cpuSeconds,
                        100.0 * double(run.stats.refinedPixels) / double(std::max<size_t>(run.stats.tracedPixels, 1)),
                        run.stats.tracedPixels, double(run.stats.shadowRays) / double(std::max<size_t>(run.stats.tracedPixels, 1)),
                        run.floor);
            std::fflush(stdout);
        }
        const Run &baseline = runs[0], &fast = runs[1], &uniform = runs[2], &other = runs[3];
        if (o.quick) {
            std::printf("%-12s time: adaptive %d / uniform %d = %.2fx wall, %.2fx CPU\n", scene.name.c_str(), o.adaptive,
                        o.samples, fast.seconds / baseline.seconds, fast.cpuSeconds / baseline.cpuSeconds);
            continue;
        }
        // Differences against the uniform N reference over its penumbra (compareVisibility's
        // maePenumbra with the uniform image as the reference).
        const AccuracyMetrics adaptiveVsUniform = compareVisibility(fast.image, uniform.image, mask, o.width, o.height);
        const AccuracyMetrics seeds = compareVisibility(other.image, uniform.image, mask, o.width, o.height);
        const AccuracyMetrics lowVsHigh = compareVisibility(baseline.image, uniform.image, mask, o.width, o.height);
        size_t differing = 0;
        float largest = 0.0f;
        for (size_t i = 0; i < mask.size(); ++i) {
            const glm::vec3 e = glm::abs(fast.image[i] - uniform.image[i]);
            const float d = std::max(e.x, std::max(e.y, e.z));
            differing += d > 0.0f;
            largest = std::max(largest, d);
        }
        std::printf("%-12s time: adaptive %d / uniform %d = %.2fx wall, %.2fx CPU; uniform %d / uniform %d = %.2fx wall, "
                    "%.2fx CPU\n",
                    scene.name.c_str(), o.adaptive, o.samples, fast.seconds / baseline.seconds,
                    fast.cpuSeconds / baseline.cpuSeconds, o.adaptive, o.samples, uniform.seconds / baseline.seconds,
                    uniform.cpuSeconds / baseline.cpuSeconds);
        std::printf("%-12s penumbra MAE: adaptive vs uniform %d %.5f (%zu pixels differ, largest %.4f); uniform %d seed 2 "
                    "vs seed 1 %.5f (/sqrt 2: measured floor %.5f); uniform %d vs uniform %d %.5f\n",
                    scene.name.c_str(), o.adaptive, adaptiveVsUniform.maePenumbra, differing, largest, o.adaptive,
                    seeds.maePenumbra, seeds.maePenumbra / std::sqrt(2.0), o.samples, o.adaptive, lowVsHigh.maePenumbra);
        std::fflush(stdout);
    }
}

// The default run: BVH build, primary rays, hard and soft reference times per scene.
void timeReferences(IGroundTruth& groundTruth, std::vector<Scene>& scenes, const BenchOptions& o) {
    const unsigned cores = std::thread::hardware_concurrency();
    std::printf("ground truth %dx%d, %d thread(s) (%u hardware), soft: %d samples per pixel\n", o.width, o.height,
                o.threads > 0 ? o.threads : static_cast<int>(cores), cores, o.samples);
    std::printf("%-10s %10s %8s %10s %10s %10s %9s\n", "scene", "triangles", "bvh s", "primary s", "hard s", "soft s",
                "compared");
    for (Scene& scene : scenes) {
        size_t triangles = 0;
        for (const SceneObject& object : scene.objects) triangles += scene.meshes[object.mesh].indices.size() / 3;
        if (scene.light.size <= 0.0f) // give the soft run an emitter to sample
            scene.light.size = scene.light.type == LightType::Directional ? 0.05f : 0.2f;

        auto start = std::chrono::steady_clock::now();
        groundTruth.setScene(scene);
        const double bvh = secondsSince(start);

        const SceneCamera& camera = scene.camera;
        const glm::mat4 viewProjection = viewProjectionOf(camera, o);
        std::vector<glm::vec4> positions, normals;
        start = std::chrono::steady_clock::now();
        groundTruth.tracePrimary(viewProjection, camera.position, o.width, o.height, positions, normals);
        const double primary = secondsSince(start);
        const GBufferView gbuffer{o.width, o.height, positions.data(), normals.data()};

        ReferenceOptions options;
        options.threads = o.threads;
        std::vector<glm::vec3> hard, soft;
        start = std::chrono::steady_clock::now();
        groundTruth.trace(gbuffer, scene.light, options, hard);
        const double hardSeconds = secondsSince(start);

        options.mode = ReferenceOptions::Mode::Soft;
        options.samplesPerPixel = o.samples;
        start = std::chrono::steady_clock::now();
        groundTruth.trace(gbuffer, scene.light, options, soft);
        const double softSeconds = secondsSince(start);

        const std::vector<uint8_t> mask = compareMask(gbuffer, scene.light);
        const AccuracyMetrics hardVsSoft = compareVisibility(hard, soft, mask, o.width, o.height);
        std::printf("%-10s %10zu %8.3f %10.3f %10.3f %10.3f %8.1f%%\n", scene.name.c_str(), triangles, bvh, primary,
                    hardSeconds, softSeconds, 100.0 * hardVsSoft.comparedFraction);
        std::printf("           hard vs soft reference: %s\n", metricsToJson(hardVsSoft).c_str());
    }
}

} // namespace

int main(int argc, char** argv) {
    BenchOptions o;
    if (!parseOptions(argc, argv, o)) return 2;
    std::string error;
    GroundTruthPtr groundTruth = loadGroundTruth(error);
    if (!groundTruth) {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
    }

    std::vector<Scene> scenes;
    try {
        if (o.names.empty()) {
            scenes.push_back(cubeScene());
            scenes.push_back(spheresScene());
        }
        for (const std::string& name : o.names) scenes.push_back(loadScene(name));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }

    if (o.adaptive > 0) compareAdaptive(*groundTruth, scenes, o);
    else timeReferences(*groundTruth, scenes, o);
    return 0;
}
