// Issue 27: the GPU shadow tracer. The host's BVH on the CPU (boxes, reachability, a traversal of
// its layout against brute force), then the `raytraced` technique under llvmpipe against the
// Embree reference: hard on every built-in scene, coloured casters under the physical model, soft
// converging with N and within the references' noise floors, the temporal blend, the counters.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>

#include "render/bvh.h"
#include "test_support.h"

using namespace shadowlab;
using Mode = ReferenceOptions::Mode;

namespace {

uint32_t bitsOf(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof(u));
    return u;
}

// Pixels where the technique and the reference differ by more than `tolerance` in any channel
// (RGBA16F targets hold a transmittance to about 1e-3), among the compared ones.
struct Difference {
    size_t differing = 0;
    size_t compared = 0;
    double fraction() const { return compared ? double(differing) / double(compared) : 0.0; }
};
Difference differingPixels(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                           const std::vector<uint8_t>& mask, float tolerance = 0.02f) {
    Difference d;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        ++d.compared;
        const glm::vec3 e = glm::abs(technique[i] - reference[i]);
        if (std::max(e.x, std::max(e.y, e.z)) <= tolerance) continue;
        if (++d.differing <= 3)
            std::printf("  pixel %zu: technique (%.4f %.4f %.4f), reference (%.4f %.4f %.4f)\n", i, technique[i].r, technique[i].g,
                        technique[i].b, reference[i].r, reference[i].g, reference[i].b);
    }
    return d;
}

// Brute force: every caster triangle, the same watertight test and crossing factor.
glm::vec3 bruteForce(const bvh::Bvh& tree, glm::vec3 origin, glm::vec3 direction, float tMax) {
    glm::vec3 throughput(1.0f);
    for (size_t i = 0; i < tree.triangleCount; ++i) {
        const bvh::Triangle& tri = tree.triangles[i];
        const float t = bvh::intersectTriangle(origin, direction, tri, tMax);
        if (t < 0.0f) continue;
        throughput *= bvh::crossing(tree, tri, origin + t * direction);
        if (throughput == glm::vec3(0.0f)) return throughput;
    }
    return throughput;
}

} // namespace

TEST(RayTracedBvh, BoxesEncloseTheirContentAndEveryTriangleIsInOneLeaf) {
    for (const char* name : {"dragon-like", "forest-002", "glass-field"}) {
        const Scene scene = loadScene(name);
        const bvh::Bvh tree = bvh::build(scene);
        ASSERT_GT(tree.triangleCount, 0u) << name;
        EXPECT_LE(tree.depth, 60) << name;
        std::vector<int> seen(tree.triangleCount, 0);
        std::vector<uint32_t> stack{0};
        size_t nodes = 0;
        while (!stack.empty()) {
            const bvh::Node& node = tree.nodes[stack.back()];
            stack.pop_back();
            ++nodes;
            const glm::vec3 lo(node.lo), hi(node.hi);
            const uint32_t first = bitsOf(node.lo.w), count = bitsOf(node.hi.w);
            if (count > 0) {
                for (uint32_t t = first; t < first + count; ++t) {
                    ASSERT_LT(t, tree.triangleCount);
                    ++seen[t];
                    for (const glm::vec4& v : {tree.triangles[t].v0, tree.triangles[t].v1, tree.triangles[t].v2})
                        ASSERT_TRUE(glm::all(glm::lessThanEqual(lo, glm::vec3(v))) && glm::all(glm::lessThanEqual(glm::vec3(v), hi)))
                            << name << ": leaf box encloses its triangles";
                }
                continue;
            }
            ASSERT_LT(first + 1, tree.nodes.size());
            for (uint32_t child : {first, first + 1}) {
                const bvh::Node& c = tree.nodes[child];
                EXPECT_TRUE(glm::all(glm::lessThanEqual(lo, glm::vec3(c.lo))) && glm::all(glm::lessThanEqual(glm::vec3(c.hi), hi)))
                    << name << ": node box encloses its children";
                stack.push_back(child);
            }
        }
        EXPECT_EQ(nodes, tree.nodes.size()) << name << ": every node reachable from the root";
        for (size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << name << ": triangle " << t;
        std::printf("bvh %s: %zu triangles, %zu nodes, depth %d, %.1f MiB, built in %.1f ms\n", name, tree.triangleCount,
                    tree.nodes.size(), tree.depth, double(tree.bytes()) / 1048576.0, tree.buildSeconds * 1000.0);
    }
}

TEST(RayTracedBvh, TraversalAgreesWithBruteForceOnRandomRays) {
    for (const char* name : {"dragon-like", "layered-quads"}) {
        const Scene scene = loadScene(name);
        const bvh::Bvh tree = bvh::build(scene);
        const Bounds bounds = scene.worldBounds(DrawSet::Casters);
        std::mt19937 random(27);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        int blocked = 0, coloured = 0;
        uint64_t visits = 0;
        constexpr int kRays = 3000;
        for (int r = 0; r < kRays; ++r) {
            // From a point in the (enlarged) bounds towards another: rays through the geometry.
            auto point = [&] {
                const glm::vec3 u(unit(random), unit(random), unit(random));
                return glm::mix(bounds.min, bounds.max, u * 1.2f - 0.1f);
            };
            const glm::vec3 origin = point(), target = point();
            const float length = glm::length(target - origin);
            if (length < 1e-3f) continue;
            const glm::vec3 direction = (target - origin) / length;
            const float tMax = (r % 2) ? length : 1e30f;
            bvh::TraceCounters counters;
            const glm::vec3 fast = bvh::transmittance(tree, origin, direction, tMax, 0.0f, &counters);
            const glm::vec3 slow = bruteForce(tree, origin, direction, tMax);
            ASSERT_NEAR(fast.r, slow.r, 1e-5f) << name << " ray " << r;
            ASSERT_NEAR(fast.g, slow.g, 1e-5f) << name << " ray " << r;
            ASSERT_NEAR(fast.b, slow.b, 1e-5f) << name << " ray " << r;
            blocked += slow == glm::vec3(0.0f);
            coloured += slow != glm::vec3(0.0f) && slow != glm::vec3(1.0f);
            visits += counters.nodes + counters.triangles;
        }
        std::printf("bvh %s: %d of %d rays blocked, %d coloured, %.1f visits and tests per ray (brute force %zu)\n", name,
                    blocked, kRays, coloured, double(visits) / kRays, tree.triangleCount);
        EXPECT_GT(blocked + coloured, kRays / 10) << name << ": the rays meet geometry";
        if (tree.triangleCount > 1000) {
            EXPECT_LT(double(visits) / kRays, 0.01 * double(tree.triangleCount)) << name << ": the tree prunes";
        }
    }
}

TEST(RayTraced, HardMatchesTheEmbreeReferenceOnEveryBuiltInScene) {
    for (const std::string& name : builtinSceneNames()) {
        auto app = test::makeHeadlessApp(name, {160, 120});
        ASSERT_TRUE(app) << name;
        const Evaluation e = test::evaluateTechnique(*app, "raytraced", {"rays=1"}, Mode::Hard, 1, TranslucencyModel::Physical);
        const Difference d = differingPixels(e.technique, e.reference, e.mask);
        Difference layers;
        for (const TranslucentLayerEvaluation& layer : e.translucentLayers) {
            const Difference l = differingPixels(layer.technique, layer.reference, layer.mask);
            layers.differing += l.differing;
            layers.compared += l.compared;
        }
        std::printf("raytraced hard on %-15s: %zu of %zu pixels differ (%.4f%%), MAE %.2e; translucent layers %zu of %zu\n",
                    name.c_str(), d.differing, d.compared, 100.0 * d.fraction(), e.metrics.mae, layers.differing,
                    layers.compared);
        EXPECT_GT(d.compared, 1000u) << name;
        // 0.01% of the compared pixels, rounded up to a whole pixel at this size (ties at edges).
        EXPECT_LE(d.differing, std::max<size_t>(1, d.compared / 10000)) << name;
        EXPECT_LE(layers.differing, std::max<size_t>(1, layers.compared / 10000)) << name << ": translucent receivers";
    }
}

TEST(RayTraced, ColouredAndTexturedCastersFollowThePhysicalModel) {
    for (const char* name : {"layered-quads", "rose-window"}) {
        auto app = test::makeHeadlessApp(name, {200, 150});
        ASSERT_TRUE(app);
        const AccuracyMetrics physical = test::measureAccuracy(*app, "raytraced", {}, Mode::Hard, 1, TranslucencyModel::Physical);
        const AccuracyMetrics opaque = test::measureAccuracy(*app, "raytraced", {}, Mode::Hard, 1, TranslucencyModel::Opaque);
        std::printf("raytraced on %s: physical MAE %.5f (r %.5f g %.5f b %.5f), against the opaque model %.4f\n", name,
                    physical.mae, physical.maePerChannel.r, physical.maePerChannel.g, physical.maePerChannel.b, opaque.mae);
        EXPECT_LT(physical.maePerChannel.r, 2e-3) << name;
        EXPECT_LT(physical.maePerChannel.g, 2e-3) << name;
        EXPECT_LT(physical.maePerChannel.b, 2e-3) << name;
        EXPECT_GT(opaque.mae, 20.0 * physical.mae + 0.01) << name << ": the light through the casters is there";
    }
}

// contact (a sphere light over casters touching the ground): penumbrae from sharp to wide.
TEST(RayTraced, SoftConvergesWithRaysAndMatchesTheReferenceAtEqualRayCount) {
    auto app = test::makeHeadlessApp("contact", {240, 180});
    ASSERT_TRUE(app);
    double previous = 1.0;
    for (int rays : {4, 16, 64}) {
        const std::string set = "rays=" + std::to_string(rays);
        const Evaluation converged = test::evaluateTechnique(*app, "raytraced", {set}, Mode::Soft, 256, TranslucencyModel::Physical);
        ReferenceOptions options;
        options.mode = Mode::Soft;
        options.samplesPerPixel = rays;
        options.model = TranslucencyModel::Physical;
        options.adaptive = false;
        Evaluation equal;
        std::string error;
        ASSERT_TRUE(app->evaluate(options, equal, error)) << error;
        std::printf("raytraced soft on contact, N = %2d: penumbra MAE %.4f against 256 rays (floor %.4f); %.4f against "
                    "Embree at %d rays (its floor %.4f)\n",
                    rays, converged.metrics.maePenumbra, converged.referenceFloor, equal.metrics.maePenumbra, rays,
                    equal.referenceFloor);
        EXPECT_LT(converged.metrics.maePenumbra, 0.7 * previous) << "converges as N grows";
        previous = converged.metrics.maePenumbra;
        // Two independent estimates with the same sampling: their difference is within the sum of
        // their noise floors (the GPU's equals the reference's at equal N).
        EXPECT_LT(equal.metrics.maePenumbra, 2.0 * equal.referenceFloor) << "N = " << rays;
        EXPECT_LT(equal.metrics.falseLightRate + equal.metrics.falseShadowRate, 0.01);
    }
}

TEST(RayTraced, TemporalBlendLowersTheNoiseOfAStillView) {
    auto app = test::makeHeadlessApp("contact", {240, 180});
    ASSERT_TRUE(app);
    const Evaluation single = test::evaluateTechnique(*app, "raytraced", {"rays=4", "temporal=0"}, Mode::Soft, 256,
                                                      TranslucencyModel::Physical);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"rays=4", "temporal=0.9"}, "raytraced", error)) << error;
    for (int frame = 0; frame < 24; ++frame) ASSERT_TRUE(app->renderFrame("raytraced", error)) << error;
    ReferenceOptions options;
    options.mode = Mode::Soft;
    options.samplesPerPixel = 256;
    options.model = TranslucencyModel::Physical;
    Evaluation blended;
    ASSERT_TRUE(app->evaluate(options, blended, error)) << error;
    std::printf("raytraced soft N = 4 on contact: penumbra MAE %.4f one frame, %.4f blended (weight 0.9, 24 frames)\n",
                single.metrics.maePenumbra, blended.metrics.maePenumbra);
    EXPECT_LT(blended.metrics.maePenumbra, 0.6 * single.metrics.maePenumbra);
    EXPECT_LT(blended.metrics.noiseEnergy, 0.6 * single.metrics.noiseEnergy);
}

TEST(RayTraced, CountersReportRaysNodeVisitsAndTheBvh) {
    auto app = test::makeHeadlessApp("dragon-like", {160, 120});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"rays=4", "counters=true"}, "raytraced", error)) << error;
    for (int frame = 0; frame < 6; ++frame) ASSERT_TRUE(app->renderFrame("raytraced", error)) << error;
    const auto& stats = app->techniques().get("raytraced", error)->host().statistics();
    for (const char* key : {"rays per pixel", "node visits per pixel", "triangle tests per pixel", "Mrays per s", "bvh build ms",
                            "bvh MiB"})
        ASSERT_TRUE(stats.count(key)) << key;
    std::printf("raytraced on dragon-like, N = 4: %.2f rays, %.1f node visits, %.1f triangle tests per pixel, %.2f Mrays/s; "
                "bvh %.2f MiB in %.1f ms\n",
                stats.at("rays per pixel"), stats.at("node visits per pixel"), stats.at("triangle tests per pixel"),
                stats.at("Mrays per s"), stats.at("bvh MiB"), stats.at("bvh build ms"));
    EXPECT_GT(stats.at("rays per pixel"), 1.0);
    EXPECT_LE(stats.at("rays per pixel"), 4.0);
    EXPECT_GT(stats.at("node visits per pixel"), stats.at("rays per pixel"));
    EXPECT_GT(stats.at("triangle tests per pixel"), 0.0);
    EXPECT_GT(stats.at("bvh MiB"), 0.0);
}

// --reference-device gpu: the same rays through the GPU tracer, checked against Embree on every
// built-in scene (hard, the physical and the opaque model) before it is trusted.
TEST(RayTracedReference, GpuHardReferenceMatchesEmbreeOnEveryBuiltInScene) {
    for (const std::string& name : builtinSceneNames()) {
        auto app = test::makeHeadlessApp(name, {160, 120});
        ASSERT_TRUE(app) << name;
        app->setTranslucentLayers(0);
        std::string error;
        ASSERT_TRUE(app->renderFrame("shadowmap", error)) << error;
        Difference total;
        for (TranslucencyModel model : {TranslucencyModel::Physical, TranslucencyModel::Opaque}) {
            ReferenceOptions options;
            options.mode = Mode::Hard;
            options.model = model;
            Evaluation cpu, gpu;
            app->setReferenceDevice(ReferenceDevice::Cpu);
            ASSERT_TRUE(app->evaluate(options, cpu, error)) << error;
            app->setReferenceDevice(ReferenceDevice::Gpu);
            ASSERT_TRUE(app->evaluate(options, gpu, error)) << error;
            const Difference d = differingPixels(gpu.reference, cpu.reference, cpu.mask);
            total.differing += d.differing;
            total.compared += d.compared;
            EXPECT_LE(d.differing, std::max<size_t>(1, d.compared / 10000)) << name << " model " << int(model);
        }
        std::printf("gpu hard reference on %-15s: %zu of %zu pixels differ from Embree\n", name.c_str(), total.differing,
                    total.compared);
    }
}

TEST(RayTracedReference, GpuSoftReferenceAgreesWithEmbreeWithinTheirFloors) {
    auto app = test::makeHeadlessApp("contact", {240, 180});
    ASSERT_TRUE(app);
    app->setTranslucentLayers(0);
    std::string error;
    ASSERT_TRUE(app->renderFrame("pcss", error)) << error;
    ReferenceOptions options;
    options.mode = Mode::Soft;
    options.samplesPerPixel = 64;
    options.adaptive = false;
    Evaluation cpu, gpu;
    app->setReferenceDevice(ReferenceDevice::Cpu);
    ASSERT_TRUE(app->evaluate(options, cpu, error)) << error;
    app->setReferenceDevice(ReferenceDevice::Gpu);
    ASSERT_TRUE(app->evaluate(options, gpu, error)) << error;
    const AccuracyMetrics between = compareVisibility(gpu.reference, cpu.reference, cpu.mask, cpu.width, cpu.height);
    std::printf("gpu soft reference (64 rays) on contact: penumbra MAE %.4f from Embree's; floors %.4f (gpu) %.4f (Embree)\n",
                between.maePenumbra, gpu.referenceFloor, cpu.referenceFloor);
    EXPECT_GT(gpu.referenceFloor, 0.5 * cpu.referenceFloor) << "the same error estimate";
    EXPECT_LT(gpu.referenceFloor, 2.0 * cpu.referenceFloor);
    EXPECT_LT(between.maePenumbra, gpu.referenceFloor + cpu.referenceFloor);
    // The techniques' scores barely move with the device.
    EXPECT_NEAR(gpu.metrics.maePenumbra, cpu.metrics.maePenumbra, 0.25 * cpu.metrics.maePenumbra + 0.002);
}

// pass = fragment: shadowTerm() traces itself, no camera pre-pass (the flag condition), the same image.
TEST(RayTraced, FragmentPassTracesTheSameImageWithoutThePrepass) {
    auto app = test::makeHeadlessApp("glass-field", {160, 120});
    ASSERT_TRUE(app);
    const Evaluation e =
        test::evaluateTechnique(*app, "raytraced", {"pass=fragment"}, Mode::Hard, 1, TranslucencyModel::Physical);
    std::string error;
    EXPECT_EQ(app->techniques().get("raytraced", error)->host().frameFlags() & kTechniqueNeedsCameraPrepass, 0u)
        << "no pre-pass asked for";
    const Difference d = differingPixels(e.technique, e.reference, e.mask);
    std::printf("raytraced pass = fragment on glass-field: %zu of %zu pixels differ\n", d.differing, d.compared);
    EXPECT_GT(d.compared, 1000u);
    EXPECT_LE(d.differing, std::max<size_t>(1, d.compared / 10000));
}
