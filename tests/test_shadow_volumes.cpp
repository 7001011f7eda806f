// Shadow volumes (issue 26): the geometry family's exactness against the ray-traced hard
// reference, on the built-in scenes and on open casters; depth-pass failing and depth-fail
// (and auto) right with the camera inside a shadow; the adjacency the host builds for them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <algorithm>

#include "render/mesh_adjacency.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

struct Disagreement {
    size_t compared = 0;
    size_t wrong = 0;          // technique and reference on opposite sides of 0.5
    size_t outsideBand = 0;    // of those, with no reference edge within one pixel
    size_t terminator = 0;     // of those, on a surface nearly edge-on to the light (N.L < kTerminator)
};
// sin 20 degrees: the bumpy meshes' facets turn up to about 20 degrees from their smooth normals.
constexpr float kTerminator = 0.35f;

// Wrong pixels, and those of them not within one pixel of a change in the reference (the exact
// technique and the reference may disagree on which side of an edge a pixel centre falls).
// Pixels whose shading normal is within 20 degrees of edge-on to the light are counted apart: there a faceted
// mesh under smooth normals shadows itself by its facets in the volumes, while the reference's
// rays, started off the surface along the shading normal, may pass the neighbouring facet (the
// shading terminator; neither image is the smooth surface's).
Disagreement disagreement(const Evaluation& e, const std::vector<glm::vec4>& normals, const LightInfo& light) {
    Disagreement d;
    auto lit = [&](int x, int y) { return e.reference[size_t(y) * size_t(e.width) + size_t(x)].r >= 0.5f; };
    for (int y = 0; y < e.height; ++y)
        for (int x = 0; x < e.width; ++x) {
            const size_t i = size_t(y) * size_t(e.width) + size_t(x);
            if (!e.mask[i]) continue;
            ++d.compared;
            if ((e.technique[i].r >= 0.5f) == lit(x, y)) continue;
            ++d.wrong;
            bool edge = false;
            for (int dy = -1; dy <= 1 && !edge; ++dy)
                for (int dx = -1; dx <= 1 && !edge; ++dx) {
                    const int u = x + dx, v = y + dy;
                    edge = u >= 0 && v >= 0 && u < e.width && v < e.height && lit(u, v) != lit(x, y);
                }
            if (edge) continue;
            const glm::vec3 p(e.positions[i]), n(normals[i]);
            const glm::vec3 toLight = light.type == LightType::Directional ? -light.direction : glm::normalize(light.position - p);
            if (glm::dot(glm::normalize(n), toLight) < kTerminator) ++d.terminator;
            else ++d.outsideBand;
        }
    return d;
}

Disagreement measure(App& app, const std::vector<std::string>& sets) {
    const Evaluation e = test::evaluateTechnique(app, "shadow-volumes", sets, ReferenceOptions::Mode::Hard, 1,
                                                 TranslucencyModel::Opaque);
    return disagreement(e, app.renderer().readTarget(MainTarget::Normal), app.light());
}

} // namespace

class ShadowVolumeScenes : public ::testing::TestWithParam<std::string> {};

// The promise of the family: exact hard shadows. Every compared pixel agrees with the reference
// except in the one-pixel band along its shadow edges, with either counting.
TEST_P(ShadowVolumeScenes, NoWrongPixelOutsideAOnePixelBandAlongEdges) {
    auto app = test::makeHeadlessApp(GetParam(), {240, 160});
    ASSERT_TRUE(app);
    for (const char* counting : {"counting=depth-pass", "counting=depth-fail"}) {
        const Disagreement d = measure(*app, {counting});
        EXPECT_GT(d.compared, 5000u) << counting;
        EXPECT_EQ(d.outsideBand, 0u) << GetParam() << " " << counting << ": " << d.wrong << " wrong of " << d.compared;
        EXPECT_LT(double(d.terminator), 0.01 * double(d.compared)) << counting;
        EXPECT_LT(double(d.wrong), 0.01 * double(d.compared)) << counting;
    }
}

INSTANTIATE_TEST_SUITE_P(BuiltIn, ShadowVolumeScenes,
                         ::testing::Values("cube", "spheres", "contact", "pillars", "spotlight", "point-light", "dragon-like"),
                         [](const auto& info) {
                             std::string name = info.param;
                             for (char& c : name)
                                 if (c == '-') c = '_';
                             return name;
                         });

// Casters that are not closed: a single-sided quad tilted above the ground (its back to the
// light), a box without its top, and a quad whose one edge is split by a T-junction. Each of
// their triangles bounds its own volume, so they shadow as the reference does.
TEST(ShadowVolumes, OpenCastersMatchTheReference) {
    const auto dir = std::filesystem::temp_directory_path() / ("shadowlab_sv_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream obj(dir / "open.obj");
        // An open box (no top) of 1 x 1 x 1, and beside it a quad of three triangles with a
        // T-junction: the vertex (2.5, 0, 0) splits the lower edge of one triangle only.
        obj << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
               "f 1 2 3\nf 1 3 4\nf 1 5 6\nf 1 6 2\nf 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\nf 4 8 5\nf 4 5 1\n"
               "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\nv 2.5 0 0\n"
               "f 9 13 12\nf 13 10 11\nf 13 11 12\n";
    }
    const test::SceneFile scene("sv_open", R"({
      "name": "open-casters",
      "camera": {"position": [2.0, 4.5, 6.0], "target": [1.0, 0.0, 0.0], "fovY": 50, "near": 0.1, "far": 60},
      "light": {"type": "directional", "direction": [-0.35, -1, -0.45]},
      "materials": {"grey": {"baseColor": [0.7, 0.7, 0.7]}},
      "objects": [
        {"name": "ground", "shape": "plane", "size": [12, 12], "material": "grey"},
        {"name": "quad", "shape": "plane", "size": [1.2, 1.2], "rotate": [160, 20, 0], "translate": [-1.5, 1.2, 0.5], "material": "grey"},
        {"name": "open", "shape": "obj", "file": ")" + (dir / "open.obj").string() + R"(", "translate": [0, 0.3, -0.5], "material": "grey"}
      ]})");
    auto app = test::makeHeadlessApp(scene.path(), {240, 160});
    ASSERT_TRUE(app);
    for (const char* counting : {"counting=depth-pass", "counting=depth-fail"}) {
        const Disagreement d = measure(*app, {counting});
        EXPECT_GT(d.compared, 5000u);
        EXPECT_EQ(d.outsideBand, 0u) << counting << ": " << d.wrong << " wrong of " << d.compared;
    }
    std::filesystem::remove_all(dir);
}

// The camera inside a shadow volume (under a wide roof, looking at the shadowed ground): depth-pass
// starts its count off by one and inverts the image, depth-fail is right, and auto sees the near
// plane in the roof's shadow and counts by depth-fail.
TEST(ShadowVolumes, CameraInsideAVolumeBreaksDepthPassOnly) {
    const test::SceneFile scene("sv_inside", R"({
      "name": "inside",
      "camera": {"position": [0.0, 1.2, 0.0], "target": [0.3, 0.0, -3.0], "fovY": 60, "near": 0.05, "far": 60},
      "light": {"type": "directional", "direction": [0.0, -1, -0.2]},
      "materials": {"grey": {"baseColor": [0.7, 0.7, 0.7]}},
      "objects": [
        {"name": "ground", "shape": "plane", "size": [30, 30], "material": "grey", "castsShadow": false},
        {"name": "roof", "shape": "box", "size": [3, 0.2, 3], "translate": [0, 2.5, -0.5], "material": "grey"},
        {"name": "post", "shape": "box", "size": [0.3, 1, 0.3], "translate": [1.5, 0.5, -4], "material": "grey"}
      ]})");
    auto app = test::makeHeadlessApp(scene.path(), {200, 150});
    ASSERT_TRUE(app);
    const Disagreement pass = measure(*app, {"counting=depth-pass"});
    const Disagreement fail = measure(*app, {"counting=depth-fail"});
    const Disagreement chosen = measure(*app, {"counting=auto"});
    EXPECT_GT(double(pass.outsideBand), 0.2 * double(pass.compared)) << "depth-pass should fail here";
    EXPECT_EQ(fail.outsideBand, 0u) << fail.wrong;
    EXPECT_EQ(chosen.outsideBand, 0u) << chosen.wrong;
    std::string error;
    LoadedTechnique* loaded = app->techniques().get("shadow-volumes", error);
    ASSERT_TRUE(loaded) << error;
    EXPECT_EQ(loaded->host().statistics().at("depth-fail"), 1.0);
    // From the default camera of cube, outside every volume, auto keeps depth-pass.
    auto outside = test::makeHeadlessApp("cube", {120, 90});
    measure(*outside, {"counting=auto"});
    EXPECT_EQ(outside->techniques().get("shadow-volumes", error)->host().statistics().at("depth-fail"), 0.0);
}

// The counters reach the statistics a few frames late, without stalling.
TEST(ShadowVolumes, ReportsItsCountersAndDebugImages) {
    auto app = test::makeHeadlessApp("cube", {160, 120});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->applyAssignments({"debug_images=1"}, "shadow-volumes", error)) << error;
    for (int i = 0; i < 6; ++i) ASSERT_TRUE(app->renderFrame("shadow-volumes", error)) << error;
    LoadedTechnique* loaded = app->techniques().get("shadow-volumes", error);
    ASSERT_TRUE(loaded);
    const auto& stats = loaded->host().statistics();
    ASSERT_TRUE(stats.count("volume triangles"));
    EXPECT_GT(stats.at("volume triangles"), 12.0);   // a cube's caps and silhouette sides at least
    EXPECT_GT(stats.at("volume samples passing depth per pixel"), 0.0);
    std::vector<std::string> images;
    for (const auto& image : loaded->host().debugImages()) images.push_back(image.name);
    for (const char* name : {"volume mask", "volume overdraw", "silhouette edges"})
        EXPECT_NE(std::find(images.begin(), images.end(), name), images.end()) << name;
}

// The host's adjacency: a closed box has every edge's neighbour; the same box with its six
// faces' corners repeated (flat normals) welds by position; an open box is open.
TEST(MeshAdjacency, WeldsByPositionAndFindsOpenEdges) {
    Mesh box;
    const glm::vec3 corners[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    for (const auto& face : faces) {   // four vertices a face: as generators write flat-shaded boxes
        const uint32_t base = uint32_t(box.vertices.size());
        for (int k = 0; k < 4; ++k) box.vertices.push_back({corners[face[k]], glm::vec3(0.0f), glm::vec2(0.0f)});
        for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) box.indices.push_back(base + i);
    }
    const MeshAdjacency closed = buildMeshAdjacency(box);
    ASSERT_EQ(closed.indices.size(), box.indices.size() * 2);
    EXPECT_TRUE(closed.closed);
    EXPECT_EQ(closed.openEdges, 0u);
    // Every neighbour is a corner of another face (not the triangle's own opposite corner).
    for (size_t t = 0; t < box.indices.size() / 3; ++t)
        for (int e = 0; e < 3; ++e)
            EXPECT_NE(closed.indices[t * 6 + size_t(e) * 2 + 1], box.indices[t * 3 + size_t((e + 2) % 3)]);
    Mesh open = box;
    open.indices.resize(open.indices.size() - 6);   // no last face
    const MeshAdjacency opened = buildMeshAdjacency(open);
    EXPECT_FALSE(opened.closed);
    EXPECT_EQ(opened.openEdges, 4u);
}
