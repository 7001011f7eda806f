// Scene module tests (no GL): built-in scenes, procedural meshes (closed, wound outwards, right
// bounds), OBJ loading, the JSON format's conversions and repeat blocks, and the error messages,
// which must name the file, the field and the problem.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "scene/scene.h"
#include "test_support.h"

namespace shadowlab {
namespace {

namespace fs = std::filesystem;

constexpr float kPi = 3.14159265358979f;

// A fresh folder per test, removed afterwards.
class TempDir {
public:
    TempDir() {
        const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
        path_ = fs::temp_directory_path() /
                ("shadowlab_scene_" + std::string(test->name()) + "_" + std::to_string(std::random_device{}()));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }
    fs::path write(const std::string& name, const std::string& text) const {
        const fs::path file = path_ / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

private:
    fs::path path_;
};

using test::sceneErrorOf;

#define EXPECT_MENTIONS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

Scene parse(const std::string& json, const std::map<std::string, double>& overrides = {}) {
    return parseScene(json, "test.json", fs::current_path(), overrides);
}

std::string parseError(const std::string& json, const std::map<std::string, double>& overrides = {}) {
    return sceneErrorOf([&] { parseScene(json, "bad.json", fs::current_path(), overrides); });
}

Bounds boundsOf(const Mesh& mesh) {
    Bounds bounds{glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (const Vertex& vertex : mesh.vertices) {
        bounds.min = glm::min(bounds.min, vertex.position);
        bounds.max = glm::max(bounds.max, vertex.position);
    }
    return bounds;
}

void expectNear(glm::vec3 actual, glm::vec3 expected, float tolerance = 1e-4f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

// Closed and consistently wound: once vertices at the same position are welded (seams are split
// for uv), every directed edge occurs once and its reverse once, i.e. every edge is shared by
// exactly two triangles that agree on orientation. No triangle may be degenerate.
void expectClosed(const Mesh& mesh) {
    std::map<std::array<long, 3>, uint32_t> idOfPosition;
    std::vector<uint32_t> welded(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::vec3 p = mesh.vertices[i].position * 1e4f;
        const std::array<long, 3> key{std::lround(p.x), std::lround(p.y), std::lround(p.z)};
        welded[i] = idOfPosition.try_emplace(key, static_cast<uint32_t>(idOfPosition.size())).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, int> directedEdges;
    ASSERT_EQ(mesh.indices.size() % 3, 0u);
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const uint32_t a = welded[mesh.indices[t]], b = welded[mesh.indices[t + 1]], c = welded[mesh.indices[t + 2]];
        ASSERT_TRUE(a != b && b != c && a != c) << "degenerate triangle " << t / 3;
        ++directedEdges[{a, b}];
        ++directedEdges[{b, c}];
        ++directedEdges[{c, a}];
    }
    for (const auto& [edge, count] : directedEdges) {
        ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second << " used twice in one direction";
        ASSERT_EQ(directedEdges.count({edge.second, edge.first}), 1u)
            << "edge " << edge.first << "-" << edge.second << " is on a boundary";
    }
}

// Counter-clockwise front faces: each triangle's geometric normal agrees with its vertex normals,
// which must be unit length; uv in [0, 1].
void expectWoundLikeNormals(const Mesh& mesh) {
    for (const Vertex& vertex : mesh.vertices) {
        ASSERT_NEAR(glm::length(vertex.normal), 1.0f, 1e-4f);
        ASSERT_TRUE(vertex.uv.x >= 0.0f && vertex.uv.x <= 1.0f && vertex.uv.y >= 0.0f && vertex.uv.y <= 1.0f);
    }
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const Vertex& a = mesh.vertices[mesh.indices[t]];
        const Vertex& b = mesh.vertices[mesh.indices[t + 1]];
        const Vertex& c = mesh.vertices[mesh.indices[t + 2]];
        const glm::vec3 faceNormal = glm::cross(b.position - a.position, c.position - a.position);
        ASSERT_GT(glm::dot(faceNormal, a.normal + b.normal + c.normal), 0.0f) << "triangle " << t / 3;
    }
}

void expectOutwardFrom(const Mesh& mesh, glm::vec3 centre) {
    for (const Vertex& vertex : mesh.vertices) {
        ASSERT_GT(glm::dot(vertex.normal, vertex.position - centre), 0.0f);
    }
}

// ---------------------------------------------------------------------------------------------
// Built-in scenes

TEST(BuiltinScenes, AllParseWithObjectsAndTriangles) {
    const std::vector<std::string> names = builtinSceneNames();
    for (const char* expected : {"cube", "spheres", "pillars", "contact", "overlap"}) {
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    }
    EXPECT_NE(std::find(names.begin(), names.end(), defaultSceneName()), names.end());
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        const Scene scene = loadScene(name);
        EXPECT_EQ(scene.name, name);
        EXPECT_EQ(scene.source, "builtin:" + name);
        EXPECT_FALSE(scene.description.empty());
        EXPECT_FALSE(scene.objects.empty());
        EXPECT_GT(scene.triangleCount(), 0u);
        EXPECT_TRUE(scene.objects.front().castsShadow) << "ground planes are in the shadow map too: acne on them is measured";
        EXPECT_TRUE(scene.objects.front().isPlane || scene.objects.front().name == "terrain") << "the ground comes first";
        for (const SceneObject& object : scene.objects) {
            ASSERT_LT(object.mesh, scene.meshes.size());
            ASSERT_LT(object.material, scene.materials.size());
        }
    }
}

TEST(BuiltinScenes, CubeIsTheSimplestCase) {
    const Scene scene = loadScene("cube");
    ASSERT_EQ(scene.objects.size(), 2u);
    const SceneObject& cube = scene.objects[1];
    const Bounds local = boundsOf(scene.meshes[cube.mesh]);
    expectNear(glm::vec3(cube.transform * glm::vec4(local.min, 1.0f)), {-0.5f, 0.0f, -0.5f});
    expectNear(glm::vec3(cube.transform * glm::vec4(local.max, 1.0f)), {0.5f, 1.0f, 0.5f});
    EXPECT_NEAR(std::asin(-scene.light.direction.y), 45.0f * kPi / 180.0f, 1e-4f);
}

// The point of every built-in scene is the shadows it shows: the shadows (on the ground, y = 0)
// of most casters must land inside the camera's view at 16:9, and the light must reach them.
TEST(BuiltinScenes, ShadowsFallInsideTheCameraView) {
    for (const std::string& name : builtinSceneNames()) {
        SCOPED_TRACE(name);
        const Scene scene = loadScene(name);
        const SceneCamera& camera = scene.camera;
        const glm::mat4 viewProjection =
            glm::perspective(camera.fovY, 16.0f / 9.0f, camera.nearPlane, camera.farPlane) *
            glm::lookAt(camera.position, camera.target, camera.up);
        auto visible = [&](glm::vec3 point) {
            const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0f);
            return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w && std::abs(clip.z) <= clip.w;
        };
        int casters = 0, shadowsSeen = 0;
        for (const SceneObject& object : scene.objects) {
            // The ground (first) receives; other planes (translucent quads, a window) cast.
            if (!object.castsShadow || &object == &scene.objects.front()) continue;
            const Bounds local = boundsOf(scene.meshes[object.mesh]);
            const glm::vec3 centre{object.transform * glm::vec4(0.5f * (local.min + local.max), 1.0f)};
            glm::vec3 towardsGround = scene.light.direction;
            if (scene.light.type != LightType::Directional) towardsGround = glm::normalize(centre - scene.light.position);
            ASSERT_LT(towardsGround.y, 0.0f);
            const glm::vec3 shadow = centre + (-centre.y / towardsGround.y) * towardsGround;
            ++casters;
            if (visible(shadow) && visible(centre)) ++shadowsSeen;
        }
        EXPECT_GT(casters, 0);
        // Scaling scenes (dense, forest) are viewed from inside on purpose: most of them is off screen.
        if (casters > 300) continue;
        EXPECT_GE(shadowsSeen * 5, casters * 4) << shadowsSeen << " of " << casters << " shadows in view";
    }
}

TEST(BuiltinScenes, ParametersCanBeOverridden) {
    const size_t defaultCount = loadScene("spheres").objects.size();
    const Scene more = loadScene("spheres", {{"floating", 40}});
    EXPECT_EQ(more.objects.size(), defaultCount - 16 + 40);
    EXPECT_EQ(more.parameters.at("floating"), 40.0);
}

// ---------------------------------------------------------------------------------------------
// Procedural meshes

TEST(MeshGenerators, BoxIsClosedWithFlatOutwardNormals) {
    const Mesh box = makeBox({1.0f, 2.0f, 3.0f});
    EXPECT_EQ(box.vertices.size(), 24u);
    EXPECT_EQ(box.indices.size(), 36u);
    expectClosed(box);
    expectWoundLikeNormals(box);
    expectOutwardFrom(box, glm::vec3(0.0f));
    const Bounds bounds = boundsOf(box);
    expectNear(bounds.min, {-0.5f, -1.0f, -1.5f});
    expectNear(bounds.max, {0.5f, 1.0f, 1.5f});
    for (const Vertex& vertex : box.vertices) {
        EXPECT_NEAR(std::abs(vertex.normal.x) + std::abs(vertex.normal.y) + std::abs(vertex.normal.z), 1.0f, 1e-6f);
    }
}

TEST(MeshGenerators, SphereIsClosedAndRound) {
    const Mesh sphere = makeSphere(0.75f, 24, 12);
    expectClosed(sphere);
    expectWoundLikeNormals(sphere);
    expectOutwardFrom(sphere, glm::vec3(0.0f));
    for (const Vertex& vertex : sphere.vertices) EXPECT_NEAR(glm::length(vertex.position), 0.75f, 1e-5f);
    const Bounds bounds = boundsOf(sphere);
    expectNear(bounds.min, glm::vec3(-0.75f));
    expectNear(bounds.max, glm::vec3(0.75f));
}

TEST(MeshGenerators, TorusIsClosed) {
    const Mesh torus = makeTorus(1.0f, 0.25f, 32, 12);
    expectClosed(torus);
    expectWoundLikeNormals(torus);
    const Bounds bounds = boundsOf(torus);
    expectNear(bounds.min, {-1.25f, -0.25f, -1.25f});
    expectNear(bounds.max, {1.25f, 0.25f, 1.25f});
    for (const Vertex& vertex : torus.vertices) {
        // Outward from the tube's centre line.
        const glm::vec3 ring = glm::normalize(glm::vec3(vertex.position.x, 0.0f, vertex.position.z));
        EXPECT_GT(glm::dot(vertex.normal, vertex.position - ring), 0.0f);
    }
}

TEST(MeshGenerators, CylinderAndTreeAreClosedAndRestOnTheGround) {
    const Mesh cylinder = makeCylinder(0.5f, 2.0f, 16);
    expectClosed(cylinder);
    expectWoundLikeNormals(cylinder);
    expectOutwardFrom(cylinder, {0.0f, 1.0f, 0.0f});
    Bounds bounds = boundsOf(cylinder);
    expectNear(bounds.min, {-0.5f, 0.0f, -0.5f});
    expectNear(bounds.max, {0.5f, 2.0f, 0.5f});

    const Mesh tree = makeTree(3.0f, 1.0f, 10);
    expectClosed(tree);   // trunk and crown, each closed
    expectWoundLikeNormals(tree);
    bounds = boundsOf(tree);
    EXPECT_NEAR(bounds.min.y, 0.0f, 1e-6f);
    EXPECT_NEAR(bounds.max.y, 3.0f, 1e-6f);
    EXPECT_NEAR(bounds.max.x, 1.0f, 1e-5f);
}

TEST(MeshGenerators, PlaneFacesUp) {
    const Mesh plane = makePlane(4.0f, 2.0f, 3);
    EXPECT_EQ(plane.vertices.size(), 16u);
    EXPECT_EQ(plane.indices.size(), 3u * 2u * 9u);
    expectWoundLikeNormals(plane);
    const Bounds bounds = boundsOf(plane);
    expectNear(bounds.min, {-2.0f, 0.0f, -1.0f});
    expectNear(bounds.max, {2.0f, 0.0f, 1.0f});
    for (const Vertex& vertex : plane.vertices) expectNear(vertex.normal, {0.0f, 1.0f, 0.0f});
}

// ---------------------------------------------------------------------------------------------
// The JSON format

TEST(SceneFormat, PlaneObjectsCarryTheirWorldPlane) {
    const Scene scene = parse(R"({"objects": [
        {"name": "wall", "shape": "plane", "size": [4, 2], "rotate": [90, 0, 0], "translate": [0, 0, -3]},
        {"name": "tilted", "shape": "plane", "rotate": [10, 25, 30], "translate": [1, 2, 3], "scale": [2, 1, 3]}]})");
    ASSERT_EQ(scene.objects.size(), 2u);
    EXPECT_TRUE(scene.objects[0].isPlane);
    expectNear(glm::vec3(scene.objects[0].plane), {0.0f, 0.0f, 1.0f});
    EXPECT_NEAR(scene.objects[0].plane.w, 3.0f, 1e-5f);
    for (const SceneObject& object : scene.objects) {
        SCOPED_TRACE(object.name);
        const glm::vec3 normal{object.plane};
        EXPECT_NEAR(glm::length(normal), 1.0f, 1e-5f);
        const Mesh& mesh = scene.meshes[object.mesh];
        for (const Vertex& vertex : mesh.vertices) {
            const glm::vec3 world{object.transform * glm::vec4(vertex.position, 1.0f)};
            EXPECT_NEAR(glm::dot(normal, world) + object.plane.w, 0.0f, 1e-4f);
        }
        // The plane's normal is the side the mesh faces.
        const glm::vec3 a{object.transform * glm::vec4(mesh.vertices[mesh.indices[0]].position, 1.0f)};
        const glm::vec3 b{object.transform * glm::vec4(mesh.vertices[mesh.indices[1]].position, 1.0f)};
        const glm::vec3 c{object.transform * glm::vec4(mesh.vertices[mesh.indices[2]].position, 1.0f)};
        EXPECT_GT(glm::dot(glm::cross(b - a, c - a), normal), 0.0f);
    }
}

TEST(SceneFormat, UnitsAndDefaults) {
    const Scene scene = parse(R"({
        "camera": {"position": [0, 2, 5], "target": [0, 0, 0], "fovY": 60, "near": 0.5, "far": 50},
        "light": {"type": "directional", "direction": [0, -2, 0], "color": [1, 0.5, 0.25], "intensity": 2, "size": 1},
        "objects": [{"shape": "box", "translate": [1, 2, 3], "rotate": [0, 90, 0], "scale": 2}]})");
    EXPECT_NEAR(scene.camera.fovY, 60.0f * kPi / 180.0f, 1e-6f);
    EXPECT_EQ(scene.camera.nearPlane, 0.5f);
    EXPECT_EQ(scene.light.type, LightType::Directional);
    expectNear(scene.light.direction, {0.0f, -1.0f, 0.0f});
    expectNear(scene.light.color, {2.0f, 1.0f, 0.5f});
    EXPECT_NEAR(scene.light.size, kPi / 180.0f, 1e-7f);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].name, "default");
    EXPECT_EQ(scene.name, "test");
    // Scale 2, then 90 degrees about y (+x goes to -z), then translate.
    const glm::vec3 moved{scene.objects[0].transform * glm::vec4(0.5f, 0.0f, 0.0f, 1.0f)};
    expectNear(moved, {1.0f, 2.0f, 2.0f});
}

TEST(SceneFormat, LightTypes) {
    Scene scene = parse(R"({"light": {"elevation": 30, "azimuth": 90}, "objects": [{"shape": "box"}]})");
    expectNear(scene.light.direction, {0.0f, -0.5f, -std::sqrt(0.75f)});

    scene = parse(R"({"light": {"type": "spot", "position": [0, 4, 0], "target": [3, 0, 0], "outerAngle": 40,
                                "innerAngle": 30, "size": 0.25}, "objects": [{"shape": "box"}]})");
    EXPECT_EQ(scene.light.type, LightType::Spot);
    expectNear(scene.light.direction, {0.6f, -0.8f, 0.0f});
    EXPECT_NEAR(scene.light.spotOuterAngle, 40.0f * kPi / 180.0f, 1e-6f);
    EXPECT_NEAR(scene.light.spotInnerAngle, 30.0f * kPi / 180.0f, 1e-6f);
    EXPECT_EQ(scene.light.size, 0.25f);

    scene = parse(R"({"light": {"type": "point", "position": [1, 2, 3], "size": 0.1}, "objects": [{"shape": "box"}]})");
    EXPECT_EQ(scene.light.type, LightType::Point);
    expectNear(scene.light.position, {1.0f, 2.0f, 3.0f});
}

TEST(SceneFormat, RepeatSharesOneMeshAndIsDeterministic) {
    const std::string json = R"({"parameters": {"count": 7, "r": 0.25}, "objects": [
        {"shape": "plane", "castsShadow": false},
        {"name": "ball", "shape": "sphere", "radius": "$r", "translate": [0, 1, 0],
         "repeat": {"count": "$count", "grid": [4, 2], "spacing": [2, 3], "jitter": [0.3, 0.5, 0.3],
                    "scaleRange": [0.5, 1.5], "seed": 9}}]})";
    const Scene first = parse(json), second = parse(json);
    ASSERT_EQ(first.objects.size(), 8u);
    EXPECT_EQ(first.meshes.size(), 2u);
    EXPECT_EQ(first.objects[1].name, "ball#0");
    EXPECT_EQ(first.triangleCount(), first.meshes[0].indices.size() / 3 + 7 * first.meshes[1].indices.size() / 3);
    for (size_t i = 1; i < first.objects.size(); ++i) {
        EXPECT_EQ(first.objects[i].mesh, first.objects[1].mesh);
        EXPECT_EQ(first.objects[i].transform, second.objects[i].transform);
        const int column = static_cast<int>(i - 1) % 4, row = static_cast<int>(i - 1) / 4;
        const glm::vec3 gridPoint{(column - 1.5f) * 2.0f, 1.0f, (row - 0.5f) * 3.0f};
        const glm::vec3 position{first.objects[i].transform[3]};
        EXPECT_LE(std::abs(position.x - gridPoint.x), 0.3f + 1e-5f);
        EXPECT_LE(std::abs(position.y - gridPoint.y), 0.5f + 1e-5f);
        EXPECT_LE(std::abs(position.z - gridPoint.z), 0.3f + 1e-5f);
        const float scale = glm::length(glm::vec3(first.objects[i].transform[0]));
        EXPECT_TRUE(scale >= 0.5f - 1e-5f && scale <= 1.5f + 1e-5f) << scale;
    }
    EXPECT_NEAR(boundsOf(first.meshes[1]).max.x, 0.25f, 1e-5f);

    const Scene overridden = parse(json, {{"count", 3}});
    EXPECT_EQ(overridden.objects.size(), 4u);
    std::string reseeded = json;
    reseeded.replace(reseeded.find("\"seed\": 9"), 9, "\"seed\": 8");
    EXPECT_NE(parse(reseeded).objects[1].transform, first.objects[1].transform);
}

TEST(SceneFormat, DrawSetsAndBounds) {
    const Scene scene = parse(R"({
        "materials": {"glass": {"baseColor": [0.2, 0.5, 0.9], "alpha": 0.4, "transmission": [0.2, 0.5, 0.9]}},
        "objects": [
            {"name": "ground", "shape": "plane", "size": [20, 20], "castsShadow": false},
            {"name": "box", "shape": "box", "translate": [0, 0.5, 0]},
            {"name": "pane", "shape": "box", "size": [1, 1, 0.1], "translate": [3, 2, 0], "material": "glass",
             "receivesShadow": false}]})");
    const SceneObject &ground = scene.objects[0], &box = scene.objects[1], &pane = scene.objects[2];
    EXPECT_TRUE(scene.inSet(ground, DrawSet::All) && scene.inSet(box, DrawSet::All) && scene.inSet(pane, DrawSet::All));
    EXPECT_FALSE(scene.inSet(ground, DrawSet::Casters));
    EXPECT_TRUE(scene.inSet(ground, DrawSet::Receivers));
    EXPECT_FALSE(scene.inSet(pane, DrawSet::Receivers));
    EXPECT_TRUE(scene.inSet(box, DrawSet::OpaqueCasters));
    EXPECT_FALSE(scene.inSet(box, DrawSet::TranslucentCasters));
    EXPECT_TRUE(scene.inSet(pane, DrawSet::TranslucentCasters));
    EXPECT_FALSE(scene.inSet(pane, DrawSet::OpaqueCasters));

    const Bounds all = scene.worldBounds();
    expectNear(all.min, {-10.0f, 0.0f, -10.0f});
    expectNear(all.max, {10.0f, 2.5f, 10.0f});
    const Bounds casters = scene.worldBounds(DrawSet::Casters);
    expectNear(casters.min, {-0.5f, 0.0f, -0.5f});
    expectNear(casters.max, {3.5f, 2.5f, 0.5f});
    const Bounds translucent = scene.worldBounds(DrawSet::TranslucentCasters);
    expectNear(translucent.min, {2.5f, 1.5f, -0.05f});
}

TEST(SceneFormat, LoadsFilesAndResolvesObjPathsBesideThem) {
    TempDir dir;
    fs::create_directories(dir.path() / "meshes");
    dir.write("meshes/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n");
    const fs::path file = dir.write("scene.json", R"({"objects": [
        {"shape": "obj", "file": "meshes/tri.obj"},
        {"shape": "obj", "file": "meshes/tri.obj", "translate": [2, 0, 0]}]})");
    const Scene scene = loadScene(file.string());
    EXPECT_EQ(scene.name, "scene");
    EXPECT_EQ(scene.source, file.string());
    EXPECT_EQ(scene.meshes.size(), 1u) << "one OBJ file, one mesh";
    EXPECT_EQ(scene.triangleCount(), 2u);
}

// ---------------------------------------------------------------------------------------------
// OBJ files

constexpr const char* kTetrahedron =
    "# outward-facing tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

TEST(ObjLoader, GeneratesOutwardUnitNormalsWhenTheFileHasNone) {
    TempDir dir;
    const Mesh mesh = loadObj(dir.write("tetra.obj", kTetrahedron));
    EXPECT_EQ(mesh.indices.size(), 12u);
    EXPECT_EQ(mesh.vertices.size(), 4u);
    expectClosed(mesh);
    expectOutwardFrom(mesh, glm::vec3(0.25f));
    for (const Vertex& vertex : mesh.vertices) EXPECT_NEAR(glm::length(vertex.normal), 1.0f, 1e-5f);
}

TEST(ObjLoader, UsesFileNormalsTriangulatesQuadsAndMergesShapes) {
    const std::string cube =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "vn 0 0 -1\nvn 0 0 1\nvn -1 0 0\nvn 1 0 0\nvn 0 -1 0\nvn 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "o front_and_back\nf 1/1/1 4/4/1 3/3/1 2/2/1\nf 5/1/2 6/2/2 7/3/2 8/4/2\n"
        "o sides\nf 1/1/3 5/2/3 8/3/3 4/4/3\nf 2/1/4 3/2/4 7/3/4 6/4/4\nf 1/1/5 2/2/5 6/3/5 5/4/5\nf 4/1/6 8/2/6 7/3/6 3/4/6\n";
    TempDir dir;
    const Mesh withNormals = loadObj(dir.write("cube.obj", cube));
    EXPECT_EQ(withNormals.indices.size(), 36u);
    EXPECT_EQ(withNormals.vertices.size(), 24u);
    expectClosed(withNormals);
    expectWoundLikeNormals(withNormals);
    expectOutwardFrom(withNormals, glm::vec3(0.0f));
    for (const Vertex& vertex : withNormals.vertices) {
        EXPECT_NEAR(std::abs(vertex.normal.x) + std::abs(vertex.normal.y) + std::abs(vertex.normal.z), 1.0f, 1e-6f);
    }

    // The same cube without normals: smooth ones, generated, still unit and outward.
    const std::string noNormals =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "f 1/1 4/4 3/3 2/2\nf 5/1 6/2 7/3 8/4\nf 1/1 5/2 8/3 4/4\nf 2/1 3/2 7/3 6/4\nf 1/1 2/2 6/3 5/4\nf 4/1 8/2 7/3 3/4\n";
    const Mesh smooth = loadObj(dir.write("cube_smooth.obj", noNormals));
    EXPECT_EQ(smooth.indices.size(), 36u);
    expectClosed(smooth);
    expectOutwardFrom(smooth, glm::vec3(0.0f));
    for (const Vertex& vertex : smooth.vertices) {
        EXPECT_NEAR(glm::length(vertex.normal), 1.0f, 1e-5f);
        // Shared corners share a normal despite their different uv: the corner's diagonal.
        EXPECT_GT(glm::dot(vertex.normal, glm::normalize(vertex.position)), 0.9f);
    }
}

TEST(ObjLoader, MissingMaterialLibraryIsNotFatal) {
    TempDir dir;
    const Mesh mesh = loadObj(dir.write("lonely.obj", std::string("mtllib nowhere.mtl\nusemtl shiny\n") + kTetrahedron));
    EXPECT_EQ(mesh.indices.size(), 12u);
}

TEST(ObjLoader, ErrorsNameTheFileAndLine) {
    TempDir dir;
    std::string message = sceneErrorOf([&] { loadObj(dir.path() / "absent.obj"); });
    EXPECT_MENTIONS(message, "absent.obj");
    EXPECT_MENTIONS(message, "cannot open");

    message = sceneErrorOf([&] { loadObj(dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")); });
    EXPECT_MENTIONS(message, "zero.obj:4");
    EXPECT_MENTIONS(message, "parse error");

    message = sceneErrorOf([&] { loadObj(dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n# end\n")); });
    EXPECT_MENTIONS(message, "range.obj:5");
    EXPECT_MENTIONS(message, "out of range");

    message = sceneErrorOf([&] { loadObj(dir.write("relative.obj", "v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n")); });
    EXPECT_MENTIONS(message, "relative.obj:3");
    EXPECT_MENTIONS(message, "out of range");

    message = sceneErrorOf([&] { loadObj(dir.write("points.obj", "v 0 0 0\nv 1 0 0\n")); });
    EXPECT_MENTIONS(message, "points.obj");
    EXPECT_MENTIONS(message, "no faces");
}

TEST(ObjLoader, StanfordBunnyFromSharedAssets) {
    const fs::path bunny = fs::path(SHADOWLAB_SHARED_ASSETS_DIR) / "bunny.obj";
    if (!fs::exists(bunny)) GTEST_SKIP() << bunny << " is not there";
    const Mesh mesh = loadObj(bunny);
    EXPECT_EQ(mesh.indices.size() / 3, 3674u);
    for (const Vertex& vertex : mesh.vertices) ASSERT_NEAR(glm::length(vertex.normal), 1.0f, 1e-4f);
}

// ---------------------------------------------------------------------------------------------
// Error messages: file, field path, problem

TEST(SceneErrors, JsonSyntaxErrorGivesLineAndColumn) {
    const std::string message = parseError("{\n  \"name\": \"x\",\n  \"objects\": [\n    {\"shape\": \"box\",}\n  ]\n}\n");
    EXPECT_MENTIONS(message, "bad.json:4:");
    EXPECT_MENTIONS(message, "syntax error");
}

TEST(SceneErrors, UnknownShape) {
    const std::string message = parseError(R"({"objects": [{"shape": "box"}, {"shape": "cone"}]})");
    EXPECT_MENTIONS(message, "bad.json: objects[1].shape: ");
    EXPECT_MENTIONS(message, "unknown shape 'cone'");
    EXPECT_MENTIONS(message, "sphere");
}

TEST(SceneErrors, UnknownFieldIsReportedWithTheLikelyName) {
    std::string message = parseError(R"({"camera": {"postion": [1, 2, 3]}, "objects": [{"shape": "box"}]})");
    EXPECT_MENTIONS(message, "bad.json: camera.postion: ");
    EXPECT_MENTIONS(message, "unknown field");
    EXPECT_MENTIONS(message, "did you mean 'position'");

    message = parseError(R"({"lihgt": {}, "objects": [{"shape": "box"}]})");
    EXPECT_MENTIONS(message, "lihgt: unknown field (did you mean 'light'?)");

    // A field of another shape: no likely name, so the fields a box has are listed.
    message = parseError(R"({"objects": [{"shape": "box", "radius": 2}]})");
    EXPECT_MENTIONS(message, "objects[0].radius: unknown field");
    EXPECT_MENTIONS(message, "size");
}

TEST(SceneErrors, WrongArrayLengthAndTypes) {
    std::string message = parseError(R"({"objects": [{"shape": "box", "size": [1, 1]}]})");
    EXPECT_MENTIONS(message, "bad.json: objects[0].size: ");
    EXPECT_MENTIONS(message, "array of 3 numbers");

    message = parseError(R"({"objects": [{"shape": "box", "translate": [0, "up", 0]}]})");
    EXPECT_MENTIONS(message, "objects[0].translate[1]: expected a number");

    message = parseError(R"({"objects": [{"shape": "box", "castsShadow": "yes"}]})");
    EXPECT_MENTIONS(message, "objects[0].castsShadow: expected true or false");

    message = parseError(R"({"objects": {"shape": "box"}})");
    EXPECT_MENTIONS(message, "objects: expected a non-empty array");
}

TEST(SceneErrors, RangesAndGeometry) {
    std::string message = parseError(R"({"objects": [{"shape": "sphere", "radius": -1}]})");
    EXPECT_MENTIONS(message, "objects[0].radius: must be positive");

    message = parseError(R"({"objects": [{"shape": "box", "size": [1, -2, 1]}]})");
    EXPECT_MENTIONS(message, "objects[0].size[1]: must be positive");

    message = parseError(R"({"light": {"direction": [0, 0, 0]}, "objects": [{"shape": "box"}]})");
    EXPECT_MENTIONS(message, "bad.json: light.direction: zero-length");

    message = parseError(R"({"objects": [{"shape": "box", "repeat": {"count": 10, "grid": [3, 3]}}]})");
    EXPECT_MENTIONS(message, "objects[0].repeat.count: 10 instances do not fit a 3 x 3 grid");

    message = parseError(R"({"materials": {"glass": {"alpha": 1.5}}, "objects": [{"shape": "box"}]})");
    EXPECT_MENTIONS(message, "materials.glass.alpha: must be between 0 and 1");

    message = parseError(R"({"light": {"type": "area", "position": [0, 1, 0]}, "objects": [{"shape": "box"}]})");
    EXPECT_MENTIONS(message, "light.type: unknown light type 'area'");
}

TEST(SceneErrors, UnknownMaterial) {
    const std::string message = parseError(R"({"materials": {"blue": {}}, "objects": [{"shape": "box", "material": "red"}]})");
    EXPECT_MENTIONS(message, "bad.json: objects[0].material: ");
    EXPECT_MENTIONS(message, "unknown material 'red'");
    EXPECT_MENTIONS(message, "blue");
}

TEST(SceneErrors, MissingObjFileResolvedBesideTheScene) {
    TempDir dir;
    const fs::path file = dir.write("scene.json", R"({"objects": [{"shape": "obj", "file": "bunny_missing.obj"}]})");
    const std::string message = sceneErrorOf([&] { loadScene(file.string()); });
    EXPECT_MENTIONS(message, file.string() + ": objects[0].file: ");
    EXPECT_MENTIONS(message, "missing OBJ file");
    EXPECT_MENTIONS(message, (dir.path() / "bunny_missing.obj").string());
}

TEST(SceneErrors, ObjErrorsKeepTheSceneAndTheObjLine) {
    TempDir dir;
    dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    const fs::path file = dir.write("scene.json", R"({"objects": [{"shape": "obj", "file": "broken.obj"}]})");
    const std::string message = sceneErrorOf([&] { loadScene(file.string()); });
    EXPECT_MENTIONS(message, "scene.json: objects[0].file: ");
    EXPECT_MENTIONS(message, "broken.obj:3");
}

TEST(SceneErrors, Parameters) {
    const std::string json = R"({"parameters": {"count": 4}, "objects": [{"shape": "box", "repeat": {"count": "$count"}}]})";
    std::string message = parseError(json, {{"cnt", 5}});
    EXPECT_MENTIONS(message, "bad.json: parameters: ");
    EXPECT_MENTIONS(message, "unknown parameter");
    EXPECT_MENTIONS(message, "cnt");
    EXPECT_MENTIONS(message, "count");

    message = parseError(R"({"objects": [{"shape": "sphere", "radius": "$big"}]})");
    EXPECT_MENTIONS(message, "objects[0].radius: unknown parameter '$big'");

    message = parseError(json, {{"count", 2.5}});
    EXPECT_MENTIONS(message, "objects[0].repeat.count: expected a whole number");
}

TEST(SceneErrors, UnknownSceneNamesTheBuiltins) {
    const std::string message = sceneErrorOf([] { loadScene("/nonexistent/forest.json"); });
    EXPECT_MENTIONS(message, "/nonexistent/forest.json: cannot open scene file");
    EXPECT_MENTIONS(message, "built-in: ");
    EXPECT_MENTIONS(message, "cube");
}

TEST(Terrain, MeshFollowsTheHeightFunctionAndInstancesStandOnIt) {
    const Scene scene = parse(R"({
        "objects": [
          {"name": "hills", "shape": "terrain", "size": [40, 40], "subdivisions": 40, "amplitude": 3, "wavelength": 20,
           "translate": [0, 1, 0]},
          {"name": "post", "shape": "box", "size": [0.2, 1, 0.2], "translate": [0, 0.5, 0],
           "repeat": {"grid": [5, 5], "spacing": [4, 4], "jitter": 0.7, "followTerrain": true}}]})");
    const Mesh& hills = scene.meshes[scene.objects[0].mesh];
    EXPECT_FALSE(scene.objects[0].isPlane) << "planar receivers are planes only";
    float highest = -1e30f, lowest = 1e30f;
    for (const Vertex& v : hills.vertices) {
        EXPECT_NEAR(v.position.y, terrainHeight(v.position.x, v.position.z, 3.0f, 20.0f), 1e-5f);
        EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
        EXPECT_GT(v.normal.y, 0.0f);
        highest = std::max(highest, v.position.y);
        lowest = std::min(lowest, v.position.y);
    }
    EXPECT_GT(highest - lowest, 2.0f) << "hills, not a plane";
    ASSERT_EQ(scene.objects.size(), 26u);
    for (size_t i = 1; i < scene.objects.size(); ++i) {
        const glm::vec3 base = glm::vec3(scene.objects[i].transform * glm::vec4(0.0f, -0.5f, 0.0f, 1.0f));
        // The post's base (0.5 below its centre) rests on the terrain, lifted 1 with it.
        EXPECT_NEAR(base.y, 1.0f + terrainHeight(base.x, base.z, 3.0f, 20.0f), 1e-4f) << scene.objects[i].name;
    }
}

TEST(Terrain, FollowTerrainNeedsATerrainBeforeIt) {
    const std::string message = parseError(R"({"objects": [
        {"shape": "box", "repeat": {"count": 3, "followTerrain": true}},
        {"shape": "terrain"}]})");
    EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
    EXPECT_NE(message.find("objects[0].repeat.followTerrain"), std::string::npos) << message;
    EXPECT_NE(message.find("no terrain"), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------------------
// Textures (docs/scene-format.md, "Textures")

// A 2 x 1 RGBA PNG: texel 0 red glass of alpha 0.4, texel 1 opaque black.
fs::path writeTwoTexelPng(const TempDir& dir, const std::string& name, int channels = 4) {
    Image image{2, 1, channels, {}};
    if (channels == 4) image.pixels = {255, 0, 0, 102, 0, 0, 0, 255};
    else image.pixels = {255, 0, 0, 0, 0, 0};
    std::string error;
    EXPECT_TRUE(writePng(dir.path() / name, image, error)) << error;
    return dir.path() / name;
}

std::string texturedScene(const std::string& texture) {
    return R"({"materials": {"glass": {"alpha": 0.5, "transmissionTexture": )" + texture +
           R"(}}, "objects": [{"shape": "plane"}, {"shape": "plane", "size": [2, 2], "translate": [0, 1, 0], "material": "glass"}]})";
}

TEST(SceneTextures, PngFileReplacesAlphaAndTransmission) {
    TempDir dir;
    writeTwoTexelPng(dir, "two.png");
    const Scene scene = parseScene(texturedScene(R"("two.png")"), "t.json", dir.path());
    ASSERT_EQ(scene.textures.size(), 1u);
    const Material& glass = scene.materials[scene.objects[1].material];
    EXPECT_EQ(glass.transmissionTexture, 0);
    EXPECT_TRUE(glass.translucent());
    EXPECT_EQ(scene.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 102, 0, 0, 0, 255}));
    // Bilinear with repeat: texel centres at u = 0.25 and 0.75, their mean at 0.5 and at 0 (wrapped).
    const glm::vec4 red(1.0f, 0.0f, 0.0f, 0.4f), black(0.0f, 0.0f, 0.0f, 1.0f);
    for (auto [u, expected] : {std::pair{0.25f, red}, {0.75f, black}, {0.5f, 0.5f * (red + black)}, {0.0f, 0.5f * (red + black)}})
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(sampleTexture(scene.textures[0], {u, 0.5f})[c], expected[c], 1e-6f) << u;
    EXPECT_EQ(sceneGeometryBytes(scene) - sceneGeometryBytes([&] { Scene s = scene; s.textures.clear(); return s; }()), 8u)
        << "textures count in the GPU budget";
}

TEST(SceneTextures, PlainImageBlackIsOpaqueElseTheMaterialAlpha) {
    TempDir dir;
    writeTwoTexelPng(dir, "rgb.png", 3);
    const Scene scene = parseScene(texturedScene(R"("rgb.png")"), "t.json", dir.path());
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_EQ(scene.textures[0].rgba, (std::vector<uint8_t>{255, 0, 0, 128, 0, 0, 0, 255})) << "alpha 0.5 glass, black opaque";
}

TEST(SceneTextures, BadFilesNameTheFileUnlessOptional) {
    TempDir dir;
    dir.write("fake.png", "this is not a png");
    EXPECT_MENTIONS(sceneErrorOf([&] { parseScene(texturedScene(R"("fake.png")"), "t.json", dir.path()); }),
                    "t.json: materials.glass.transmissionTexture: " + (dir.path() / "fake.png").string() + ": not a readable PNG");
    EXPECT_MENTIONS(sceneErrorOf([&] { parseScene(texturedScene(R"("missing.png")"), "t.json", dir.path()); }),
                    (dir.path() / "missing.png").string() + ": cannot open texture");
    EXPECT_MENTIONS(sceneErrorOf([&] { parseScene(texturedScene(R"({"file": "x.png", "procedural": "rainbow"})"), "t.json", dir.path()); }),
                    "give either \"file\" or \"procedural\"");
    EXPECT_MENTIONS(sceneErrorOf([&] { parseScene(texturedScene(R"({"procedural": "marble"})"), "t.json", dir.path()); }),
                    "unknown procedural texture 'marble'");
    EXPECT_MENTIONS(sceneErrorOf([&] { parseScene(texturedScene(R"({"file": "fake.png", "optinal": true})"), "t.json", dir.path()); }),
                    "did you mean 'optional'");
    // Optional: the scene loads without it, and the material keeps its plain alpha.
    const Scene scene = parseScene(texturedScene(R"({"file": "fake.png", "optional": true})"), "t.json", dir.path());
    EXPECT_TRUE(scene.textures.empty());
    EXPECT_EQ(scene.materials[scene.objects[1].material].transmissionTexture, -1);
    EXPECT_FLOAT_EQ(scene.materials[scene.objects[1].material].alpha, 0.5f);
}

TEST(SceneTextures, RoseWindowHasOpaqueTraceryAndManyColouredCells) {
    const Texture rose = makeRoseWindowTexture(256, 1, 0.85f);
    size_t opaque = 0, glass = 0;
    std::set<uint32_t> colours;
    for (size_t i = 0; i < rose.rgba.size(); i += 4) {
        const uint8_t* t = &rose.rgba[i];
        if (t[3] == 255) {
            EXPECT_EQ(t[0] | t[1] | t[2], 0) << "opaque texels are black";
            ++opaque;
        } else {
            EXPECT_EQ(t[3], 217);
            ++glass;
            colours.insert(uint32_t(t[0]) << 16 | uint32_t(t[1]) << 8 | t[2]);
        }
    }
    EXPECT_GT(glass, opaque / 2) << "mostly glass inside the circle";
    EXPECT_GT(opaque, rose.rgba.size() / 4 / 5) << "tracery and the corners outside the circle";
    EXPECT_GE(colours.size(), 8u) << "many colours of glass";
}

TEST(SceneRepeat, RegionAndRandomRotationAreSeeded) {
    const std::string json = R"({"objects": [{"shape": "plane"}, {"shape": "box", "translate": [1, 2, 3],
        "repeat": {"count": 50, "region": [4, 2, 6], "randomRotate": [180, 90, 0], "seed": 7}}]})";
    const Scene a = parse(json), b = parse(json);
    ASSERT_EQ(a.objects.size(), 51u);
    bool turned = false;
    for (size_t i = 1; i < a.objects.size(); ++i) {
        EXPECT_EQ(a.objects[i].transform, b.objects[i].transform) << "same seed, same scene";
        const glm::vec3 at(a.objects[i].transform[3]);
        EXPECT_LE(std::abs(at.x - 1.0f), 2.0f);
        EXPECT_LE(std::abs(at.y - 2.0f), 1.0f);
        EXPECT_LE(std::abs(at.z - 3.0f), 3.0f);
        turned = turned || std::abs(a.objects[i].transform[0][0] - 1.0f) > 1e-3f;
    }
    EXPECT_TRUE(turned);
    EXPECT_NE(parse(R"({"objects": [{"shape": "plane"}, {"shape": "box", "repeat": {"count": 50, "region": [4, 2, 6], "seed": 8}}]})")
                  .objects[1].transform,
              a.objects[1].transform);
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "repeat": {"grid": [2, 2], "region": [1, 1, 1]}}]})"),
                    "give either grid or region");
    EXPECT_EQ(parse(R"({"objects": [{"shape": "plane"}, {"shape": "box", "repeat": {"count": 0}}]})").objects.size(), 1u);
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "repeat": {"count": 0}}]})"), "no object");
}

TEST(BuiltinScenes, Seed001ScenesHaveTheirTranslucentCasters) {
    for (const char* name : {"layered-quads", "rose-window", "teapot-glass", "glass-field"}) {
        SCOPED_TRACE(name);
        const Scene scene = loadScene(name);
        size_t translucent = 0;
        for (const SceneObject& object : scene.objects)
            translucent += object.castsShadow && scene.materials[object.material].translucent();
        EXPECT_GE(translucent, name == std::string("rose-window") ? 1u : 3u);
    }
    EXPECT_EQ(loadScene("glass-field", {{"quads", 0}}).objects.size(), 1001u);
    EXPECT_EQ(loadScene("glass-field", {{"quads", 2000}}).objects.size(), 3001u);
    // The teapot: the shared model when it is there, the stand-in otherwise (never an error).
    const Scene teapot = loadScene("teapot-glass");
    EXPECT_GT(teapot.meshes[teapot.objects[1].mesh].indices.size() / 3, 1000u);
}

} // namespace
} // namespace shadowlab
