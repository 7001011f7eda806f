// Bad input, class by class (issue 13): each is refused where it is read, with a message naming
// the file or option and the problem, before anything is allocated or measured. No GL needed,
// except for the last test (a sweep refused before its first frame).
//   JSON numbers beyond a double, nesting, non-regular and oversized files;
//   numbers checked as stored in float, transforms and world coordinates;
//   the scene budget (objects, drawn triangles, GPU bytes) and checkScene;
//   OBJ files: mtllib never opened, FIFOs and devices refused, 64-bit indices, polygon size and
//   triangulation, and only pre-scanned lines reaching tinyobjloader, read as it reads them;
//   benchmark specs checked as a whole;
//   issue 31's rules for every reader: duplicate JSON keys, repeated option keys and empty list
//   items, one camera, light-direction and repeat-grid check for every reader, messages that keep
//   their subject (spec files, NUL bytes), and Ctrl-C.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/time.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <random>

#include "bench/bench.h"
#include "groundtruth/groundtruth.h"
#include "plugin/plugin_library.h"
#include "groundtruth/reference_technique.h"
#include "scene/scene.h"
#include "test_support.h"
#include "util/paths.h"
#include "util/progress.h"
#include "util/strings.h"
#include "util/text_file.h"
#include "bench/stress.h"
#include "scene/camera_path.h"
#include "ui/tour.h"

using namespace shadowlab;
namespace fs = std::filesystem;

namespace {

#define EXPECT_MENTIONS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

class TempDir {
public:
    TempDir() {
        path_ = fs::temp_directory_path() / ("shadowlab_robust_" + std::to_string(::getpid()) + "_" +
                                             std::to_string(std::random_device{}()));
        fs::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    const fs::path& path() const { return path_; }
    fs::path write(const std::string& name, const std::string& text) const {
        std::ofstream(path_ / name, std::ios::binary) << text;
        return path_ / name;
    }
    fs::path fifo(const std::string& name) const {
        const fs::path file = path_ / name;
        EXPECT_EQ(::mkfifo(file.c_str(), 0600), 0);
        return file;
    }

private:
    fs::path path_;
};

using test::sceneErrorOf;

std::string parseError(const std::string& json) {
    return sceneErrorOf([&] { parseScene(json, "bad.json", fs::current_path()); });
}

// Sets the process's scene budget for one test.
class ScopedBudget {
public:
    explicit ScopedBudget(const std::string& text) : saved_(sceneBudget()) {
        SceneBudget budget = saved_;
        std::string error;
        EXPECT_TRUE(parseSceneBudget(text, budget, error)) << error;
        setSceneBudget(budget);
    }
    ~ScopedBudget() { setSceneBudget(saved_); }

private:
    SceneBudget saved_;
};

} // namespace

// ---------------------------------------------------------------------------------------------
// JSON and files

TEST(RobustJson, NumberBeyondADoubleIsAnErrorNamingTheFile) {
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "size": [1e400, 1, 1]}]})"), "bad.json: JSON error");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "size": [1e400, 1, 1]}]})"), "1e400");
    TempDir dir;
    const fs::path file = dir.write("huge.json", R"({"objects": [{"shape": "box"}], "ambient": [-1e400, 0, 0]})");
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene(file.string()); }), file.string());
    EXPECT_MENTIONS(sceneErrorOf([&] { checkScene(file.string()); }), "number overflow");
}

TEST(RobustJson, NestingDeeperThanTheLimitIsRefusedWithItsPosition) {
    const std::string deep = R"({"objects": [{"shape": "box"}], "x": )" + std::string(200, '[') + std::string(200, ']') + "}";
    const std::string message = parseError(deep);
    EXPECT_MENTIONS(message, "bad.json:1:");
    EXPECT_MENTIONS(message, "nested deeper than 64");
    // Brackets inside strings do not count.
    EXPECT_NO_THROW(parseScene(R"({"description": ")" + std::string(500, '[') + R"(", "objects": [{"shape": "box"}]})", "ok.json",
                               fs::current_path()));
}

TEST(RobustJson, OnlyRegularFilesOfBoundedSizeAreRead) {
    TempDir dir;
    const fs::path fifo = dir.fifo("scene.json");   // opening it for reading would block forever
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene(fifo.string()); }), "a FIFO, not a regular file");
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene("/dev/zero"); }), "a character device, not a regular file");
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene(dir.path().string()); }), "a folder, not a regular file");
    const fs::path large = dir.write("large.json", std::string(kMaxJsonFileBytes + 1, ' '));
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene(large.string()); }), "larger than 16 MiB");
    std::string text, error;
    EXPECT_FALSE(readRegularFile("/proc/self/maps", 16, text, error));   // size 0 in stat, bounded while read
    EXPECT_MENTIONS(error, "larger than");
}

TEST(RobustJson, WritesToAFullDeviceFail) {
    std::string error;
    EXPECT_FALSE(writeWholeFile("/dev/full", std::string(100000, 'x'), error));
    EXPECT_MENTIONS(error, "/dev/full: write failed");
    Image image{16, 16, 4, std::vector<uint8_t>(16 * 16 * 4, 128)};
    EXPECT_FALSE(writePng("/dev/full", image, error));
    EXPECT_MENTIONS(error, "No space left");
    EXPECT_FALSE(writeBenchResults("/dev/full", {nlohmann::json{{"scene", "cube"}}}, error));
    EXPECT_MENTIONS(error, "/dev/full");
}

// ---------------------------------------------------------------------------------------------
// Numbers as stored

TEST(RobustScene, NumbersAreCheckedAsTheyAreStoredInFloat) {
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "size": [1e300, 1, 1]}]})"),
                    "objects[0].size[0]: too large for single precision");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "sphere", "radius": 1e-300}]})"),
                    "objects[0].radius: too small: 1e-300 is zero");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "scale": 1e-300}]})"), "objects[0].scale: too small");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "translate": [0, -1e300, 0]}]})"),
                    "objects[0].translate[1]: too large");
    EXPECT_MENTIONS(parseError(R"({"light": {"intensity": 1e39}, "objects": [{"shape": "box"}]})"), "light.intensity: too large");
    EXPECT_MENTIONS(parseError(R"({"light": {"direction": [0, -1, 0], "size": 1e300}, "objects": [{"shape": "box"}]})"),
                    "light.size: too large");
    EXPECT_MENTIONS(parseError(R"({"light": {"type": "point", "position": [0, 1e300, 0]}, "objects": [{"shape": "box"}]})"),
                    "light.position[1]: too large");
    // Finite in float but beyond what squares of lengths survive.
    EXPECT_MENTIONS(parseError(R"({"light": {"type": "point", "position": [0, 1e20, 0]}, "objects": [{"shape": "box"}]})"),
                    "light.position: coordinate 1e+20 is beyond");
    EXPECT_MENTIONS(parseError(R"({"light": {"type": "point", "position": [0, 5, 0], "size": 1e20}, "objects": [{"shape": "box"}]})"),
                    "light.size: a spot or point light's size");
    EXPECT_MENTIONS(parseError(R"({"camera": {"position": [1e12, 3, 6]}, "objects": [{"shape": "box"}]})"), "camera.position");
    // A parameter carries the same checks wherever it is used.
    EXPECT_MENTIONS(sceneErrorOf([] {
                        parseScene(R"({"parameters": {"r": 1}, "objects": [{"shape": "sphere", "radius": "$r"}]})", "p.json",
                                   fs::current_path(), {{"r", 1e-300}});
                    }),
                    "objects[0].radius: too small");
}

TEST(RobustScene, TransformsMustStayFiniteInvertibleAndInRange) {
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "scale": 1e-20,
                                  "repeat": {"count": 2, "scaleRange": [1e-20, 1e-20]}}]})"),
                    "objects[0] (instance 0): transform is not finite and invertible");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "translate": [2e9, 0, 0]}]})"),
                    "objects[0]: reaches 2e+09 in world space, beyond");
    // Each instance is checked: the grid walks out of range only far from the origin.
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "translate": [9e8, 0, 0],
                                  "repeat": {"grid": [1000, 1], "spacing": [1e6, 1]}}]})"),
                    "in world space, beyond");
}

TEST(RobustScene, NamesAreBoundedSinceEveryInstanceCopiesIt) {
    // A 1 MB name times a million instances would be a terabyte.
    const std::string longName(1 << 20, 'n');
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "name": ")" + longName + R"(", "repeat": {"count": 1000000}}]})"),
                    "objects[0].name: longer than 100 characters (1048576)");
    EXPECT_MENTIONS(parseError(R"({"description": ")" + std::string(5000, 'd') + R"(", "objects": [{"shape": "box"}]})"),
                    "description: longer than 4096 characters");
}

TEST(RobustScene, LightSizesHaveOneRangeForFilesAndOptions) {
    EXPECT_EQ(lightSizeProblem(LightType::Directional, 45.0), "");
    EXPECT_MENTIONS(lightSizeProblem(LightType::Directional, 45.01), "0 to 45");
    EXPECT_MENTIONS(lightSizeProblem(LightType::Directional, -1.0), "0 to 45");
    EXPECT_MENTIONS(lightSizeProblem(LightType::Directional, std::nan("")), "0 to 45");
    EXPECT_MENTIONS(lightSizeProblem(LightType::Directional, INFINITY), "0 to 45");
    EXPECT_EQ(lightSizeProblem(LightType::Spot, 1e9), "");
    EXPECT_NE(lightSizeProblem(LightType::Point, 1e10), "");
    EXPECT_MENTIONS(parseError(R"({"light": {"direction": [0, -1, 0], "size": 46}, "objects": [{"shape": "box"}]})"),
                    "light.size: must be between 0 and 45 degrees");
}

// ---------------------------------------------------------------------------------------------
// The budget

TEST(RobustBudget, ParsesItsOptionStrictly) {
    SceneBudget budget;
    std::string error;
    ASSERT_TRUE(parseSceneBudget("objects=2000000,triangles=1e8,gpu-mib=8192,file-mib=1024", budget, error)) << error;
    EXPECT_EQ(budget.objects, 2000000u);
    EXPECT_EQ(budget.triangles, 100000000u);
    EXPECT_EQ(budget.gpuBytes, uint64_t(8192) << 20);
    EXPECT_EQ(budget.fileBytes, uint64_t(1024) << 20);
    for (const char* bad : {"objects=abc", "objects=0", "objects=1.5", "objects=1e400", "colours=3", "objects", "", "gpu-mib=-1"}) {
        SceneBudget untouched;
        EXPECT_FALSE(parseSceneBudget(bad, untouched, error)) << bad;
        EXPECT_MENTIONS(error, "--budget");
        EXPECT_EQ(untouched.objects, SceneBudget{}.objects) << "unchanged on error";
    }
}

TEST(RobustBudget, TotalsOverEveryBlockAreCheckedBeforeAllocation) {
    // 30 blocks each in range, refused at the second: the issue's 30 x 1,000,000 is in
    // cli_errors.sh; here a budget of 10,000 keeps the test quick under the sanitizers.
    ScopedBudget budget("objects=10000");
    std::string blocks;
    for (int i = 0; i < 30; ++i) blocks += std::string(i ? "," : "") + R"({"shape": "box", "repeat": {"count": 10000}})";
    TempDir dir;
    const fs::path many = dir.write("many.json", R"({"objects": [)" + blocks + "]}");
    std::string message = sceneErrorOf([&] { checkScene(many.string()); });
    EXPECT_MENTIONS(message, "objects[1].repeat: the scene would have 20000 objects, more than the budget of 10000");
    EXPECT_MENTIONS(message, "--budget objects=N");
    EXPECT_EQ(sceneErrorOf([&] { loadScene(many.string()); }), message) << "loadScene refuses it the same way";

    // Three 4096 x 4096 spheres, each in range: the second is over the default triangle budget.
    const fs::path spheres = dir.write("spheres.json", R"({"objects": [
        {"shape": "sphere", "segments": 4096, "rings": 4096},
        {"shape": "sphere", "segments": 4096, "rings": 4095},
        {"shape": "sphere", "segments": 4096, "rings": 4094}]})");
    ScopedBudget defaults("objects=1000000");
    message = sceneErrorOf([&] { checkScene(spheres.string()); });
    EXPECT_MENTIONS(message, "objects[1]: the scene would draw");
    EXPECT_MENTIONS(message, "more than the budget of 50000000");
    // loadScene checks the whole scene before generating anything: the first sphere (a gigabyte,
    // seconds to make) is within the budget but not made, since the second is over it.
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(sceneErrorOf([&] { loadScene(spheres.string()); }), message);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
    ScopedBudget small("gpu-mib=64");
    message = sceneErrorOf([&] { loadScene(spheres.string()); });
    EXPECT_MENTIONS(message, "objects[0]: the scene's geometry would need about");
    EXPECT_MENTIONS(message, "more than the budget of 64.0 MiB");
}

TEST(RobustBudget, RaisedBudgetLetsALargerSceneThrough) {
    const std::string json = R"({"objects": [{"shape": "box", "repeat": {"count": 600}}, {"shape": "box", "repeat": {"count": 600}}]})";
    {
        ScopedBudget budget("objects=1000");
        EXPECT_MENTIONS(parseError(json), "objects[1].repeat: the scene would have 1200 objects");
    }
    ScopedBudget budget("objects=1200");
    EXPECT_EQ(parseScene(json, "ok.json", fs::current_path()).objects.size(), 1200u);
}

TEST(RobustBudget, CheckSceneAgreesWithLoadSceneOnEveryBuiltinScene) {
    for (const std::string& name : builtinSceneNames()) {
        SCOPED_TRACE(name);
        const SceneCheck check = checkScene(name);
        const Scene scene = loadScene(name);
        EXPECT_EQ(check.name, scene.name);
        EXPECT_EQ(check.lightType, scene.light.type);
        EXPECT_EQ(check.objects, scene.objects.size());
        EXPECT_EQ(check.triangles, [&] {
            uint64_t triangles = 0;
            for (const SceneObject& object : scene.objects) triangles += scene.meshes[object.mesh].indices.size() / 3;
            return triangles;
        }());
        EXPECT_EQ(check.gpuBytes, sceneGeometryBytes(scene)) << "the budget's estimate is what is uploaded";
    }
}

TEST(RobustBudget, MeshSizesPredictTheGenerators) {
    auto expectSize = [](const MeshSize& predicted, const Mesh& mesh, const char* what) {
        SCOPED_TRACE(what);
        EXPECT_EQ(predicted.vertices, mesh.vertices.size());
        EXPECT_EQ(predicted.indices, mesh.indices.size());
        const MeshSize actual = sizeOf(mesh);
        for (int axis = 0; axis < 3; ++axis) {   // the predicted box holds the mesh
            EXPECT_LE(predicted.bounds.min[axis], actual.bounds.min[axis] + 1e-5f);
            EXPECT_GE(predicted.bounds.max[axis], actual.bounds.max[axis] - 1e-5f);
        }
    };
    for (int n : {1, 3, 7, 32}) {
        expectSize(planeSize(4, 2, n), makePlane(4, 2, n), "plane");
        expectSize(sphereSize(0.5f, n, n + 1), makeSphere(0.5f, n, n + 1), "sphere");
        expectSize(cylinderSize(0.5f, 2, n), makeCylinder(0.5f, 2, n), "cylinder");
        expectSize(torusSize(1, 0.25f, n, n + 2), makeTorus(1, 0.25f, n, n + 2), "torus");
        expectSize(treeSize(2, 0.6f, n), makeTree(2, 0.6f, n), "tree");
        expectSize(bumpySphereSize(0.5f, 0.3f, n + 2), makeBumpySphere(0.5f, 0.3f, 6, n + 2), "bumpy");
        expectSize(terrainSize(50, 30, n, 3), makeTerrain(50, 30, n, 3, 20), "terrain");
    }
    expectSize(boxSize({1, 2, 3}), makeBox({1, 2, 3}), "box");
}

// ---------------------------------------------------------------------------------------------
// OBJ files

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3\n";

TEST(RobustObj, MaterialLibrariesAreNeverOpened) {
    TempDir dir;
    dir.fifo("blocking.mtl");
    const fs::path obj = dir.write("m.obj", "mtllib /dev/zero\nmtllib blocking.mtl\nusemtl x\n" + std::string(kTriangle));
    const auto start = std::chrono::steady_clock::now();
    const Mesh mesh = loadObj(obj);
    EXPECT_EQ(mesh.indices.size(), 3u);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

TEST(RobustObj, OnlyRegularFilesUpToTheBudgetAreRead) {
    TempDir dir;
    const fs::path fifo = dir.fifo("pipe.obj");
    EXPECT_MENTIONS(sceneErrorOf([&] { loadObj(fifo); }), "a FIFO, not a regular file");
    EXPECT_MENTIONS(sceneErrorOf([&] { loadObj("/dev/zero"); }), "a character device, not a regular file");
    const fs::path obj = dir.write("t.obj", kTriangle);
    EXPECT_MENTIONS(sceneErrorOf([&] { loadObj(obj, 10); }), "--budget file-mib");
    // Through a scene: named with the scene's field.
    const fs::path scene = dir.write("s.json", R"({"objects": [{"shape": "obj", "file": "pipe.obj"}]})");
    const std::string message = sceneErrorOf([&] { loadScene(scene.string()); });
    EXPECT_MENTIONS(message, "s.json: objects[0].file: ");
    EXPECT_MENTIONS(message, "a FIFO");
}

TEST(RobustObj, IndicesAreCheckedInSixtyFourBits) {
    std::string message = sceneErrorOf([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967297\n", "wrap.obj"); });
    EXPECT_MENTIONS(message, "wrap.obj:4: face refers to vertex 4294967297");
    EXPECT_MENTIONS(message, "out of range");
    message = sceneErrorOf([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999999\n", "big.obj"); });
    EXPECT_MENTIONS(message, "big.obj:4:");
    EXPECT_MENTIONS(message, "out of range");
    message = sceneErrorOf([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/4294967298 2 3\n", "uv.obj"); });
    EXPECT_MENTIONS(message, "texture coordinate");
    message = sceneErrorOf([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4294967296\n", "neg.obj"); });
    EXPECT_MENTIONS(message, "out of range");
    message = sceneErrorOf([] { parseObj("v 1e400 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj"); });
    EXPECT_MENTIONS(message, "nan.obj:1: OBJ parse error: '1e400' is not a finite number");
    message = sceneErrorOf([] { parseObj("v 0 0 0\nv 1 0 0\nf 1 2\n", "two.obj"); });
    EXPECT_MENTIONS(message, "two.obj:3: OBJ parse error: a face needs at least 3 corners");
}

TEST(RobustObj, TheBudgetIsCheckedWhileReading) {
    std::string text = "v 0 0 0\nv 1 0 0\nv 0 0 -1\n";
    for (int i = 0; i < 20; ++i) text += "f 1 2 3\n";
    SceneBudget budget;
    budget.triangles = 10;
    std::string message = sceneErrorOf([&] { parseObj(text, "many.obj", budget); });
    EXPECT_MENTIONS(message, "many.obj:14: more than 10 triangles, the scene budget; raise it with --budget triangles=N");
    budget = SceneBudget{};
    budget.gpuBytes = 100;
    message = sceneErrorOf([&] { parseObj(text, "big.obj", budget); });
    EXPECT_MENTIONS(message, "big.obj: 3 vertices and 20 triangles need more than the GPU memory budget");
    EXPECT_EQ(parseObj(text, "fine.obj").indices.size(), 60u);
}

TEST(RobustObj, AHundredThousandCornerPolygonIsRefusedAtOnce) {
    std::string text;
    for (int i = 0; i < 100000; ++i) text += "v " + std::to_string(std::cos(i * 1e-4)) + " 0 " + std::to_string(std::sin(i * 1e-4)) + "\n";
    text += "f";
    for (int i = 1; i <= 100000; ++i) text += " " + std::to_string(i);
    text += "\n";
    const auto start = std::chrono::steady_clock::now();
    const std::string message = sceneErrorOf([&] { parseObj(text, "huge.obj"); });
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_MENTIONS(message, "huge.obj:100001: a face with more than 255 corners");
}

// Signed area of the mesh's triangles projected on y = 0 (seen from +y), and of the polygon.
double projectedArea(const Mesh& mesh) {
    double area = 0.0;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.vertices[mesh.indices[t]].position), b(mesh.vertices[mesh.indices[t + 1]].position),
            c(mesh.vertices[mesh.indices[t + 2]].position);
        area += 0.5 * ((c.x - a.x) * (b.z - a.z) - (b.x - a.x) * (c.z - a.z));
    }
    return area;
}

TEST(RobustObj, ConcaveAndConvexPolygonsAreTriangulatedExactly) {
    // A comb: a bottom bar and 63 teeth, 253 corners, deeply concave, counter-clockwise in
    // (x, -z), i.e. seen from +y: the bottom edge left to right, then the teeth right to left.
    std::vector<glm::dvec2> outline;   // (x, -z)
    const int teeth = 63;
    outline.push_back({0.0, -1.0});
    outline.push_back({2.0 * teeth, -1.0});
    for (int i = teeth - 1; i >= 0; --i) {
        outline.push_back({2.0 * i + 1.0, 0.0});
        outline.push_back({2.0 * i + 1.0, 10.0});
        outline.push_back({2.0 * i + 0.0, 10.0});
        outline.push_back({2.0 * i + 0.0, 0.0});
    }
    outline.pop_back();   // the first tooth's foot would lie on the closing edge
    ASSERT_LE(outline.size(), 255u);
    double polygonArea = 0.0;
    std::string text;
    for (size_t i = 0; i < outline.size(); ++i) {
        const glm::dvec2 a = outline[i], b = outline[(i + 1) % outline.size()];
        polygonArea += 0.5 * (a.x * b.y - b.x * a.y);
        text += "v " + std::to_string(a.x) + " 0 " + std::to_string(-a.y) + "\n";
    }
    ASSERT_GT(polygonArea, 0.0);
    text += "f";
    for (size_t i = 1; i <= outline.size(); ++i) text += " " + std::to_string(i);
    text += "\n";
    const Mesh comb = parseObj(text, "comb.obj");
    EXPECT_EQ(comb.indices.size(), 3 * (outline.size() - 2)) << "n - 2 triangles";
    EXPECT_NEAR(projectedArea(comb), polygonArea, 1e-6 * polygonArea) << "no overlap, no gap, one winding";
    for (const Vertex& v : comb.vertices) EXPECT_GT(v.normal.y, 0.99f) << "faces +y like the polygon";

    // A convex 255-gon: a fan.
    text.clear();
    for (int i = 0; i < 255; ++i)
        text += "v " + std::to_string(std::cos(6.283185307 * i / 255)) + " 0 " + std::to_string(-std::sin(6.283185307 * i / 255)) + "\n";
    text += "f";
    for (int i = 1; i <= 255; ++i) text += " " + std::to_string(i);
    const Mesh disc = parseObj(text + "\n", "disc.obj");
    EXPECT_EQ(disc.indices.size(), 3u * 253u);
    EXPECT_NEAR(projectedArea(disc), 0.5 * 255 * std::sin(6.283185307 / 255), 1e-4);
}

// tinyobjloader parses OBJ files, after the pre-scan: what it would act on but the mesh does not
// need never reaches it. Unblanked, `l 0 1`, `p 0` and `vw 0 -1 1` would make it fail the file,
// a `t` line allocates 3 x 8192 values and `vw 0 1e30 1` casts 1e30 to int.
TEST(RobustObj, OnlyTheCheckedLinesReachTinyobjloader) {
    std::string text = "mtllib /dev/zero\no one\ng two\nusemtl x\ns 1\nl 0 1\np 0\nvw 0 -1 1\nvw 0 1e30 1\ncstype bspline\n";
    for (int i = 0; i < 100; ++i) text += "t crease 8192/8192/8192\n";
    text += std::string(kTriangle) + "g three\nf 1 3 2\n";
    const Mesh mesh = parseObj(text, "ext.obj");
    EXPECT_EQ(mesh.indices.size(), 6u) << "both faces, the groups merged";
}

TEST(RobustObj, LinesEndWhereTinyobjloaderEndsThem) {
    EXPECT_EQ(parseObj("v 0 0 0\rv 1 0 0\rv 0 0 -1\rf 1 2 3\r", "cr.obj").indices.size(), 3u);
    EXPECT_EQ(parseObj("v 0 0 0\r\nv 1 0 0\r\nv 0 0 -1\r\nf 1 2 3", "crlf.obj").indices.size(), 3u);
    EXPECT_MENTIONS(sceneErrorOf([] { parseObj("v 0 0 0\rv 1 0 0\r\nv 0 0 -1\r\rf 1 2 4\n", "cr.obj"); }),
                    "cr.obj:5: face refers to vertex 4 but the file has 3 (index out of range)");
    // A NUL ends tinyobjloader's line: refused where it would cut a number or a corner short.
    EXPECT_MENTIONS(sceneErrorOf([] { parseObj(std::string("v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3") + '\0' + " 4\n", "nul.obj"); }),
                    "nul.obj:4: OBJ parse error:");
}

TEST(RobustObj, CornersAndNumbersAreReadAsTinyobjloaderReadsThem) {
    const std::string points = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvt 0 0\nvn 0 1 0\n";
    auto error = [&](const std::string& line) { return sceneErrorOf([&] { parseObj(points + line + "\n", "c.obj"); }); };
    EXPECT_EQ(parseObj(points + "f 1/1/1 2//1 3/-1/-1\n", "c.obj").indices.size(), 3u);
    // tinyobjloader refuses an empty index after '/', and atoi reads 3x as 3 and +3 as 3.
    EXPECT_MENTIONS(error("f 1/ 2 3"), "c.obj:6: OBJ parse error: corner '1/' has no texture coordinate index after '/'");
    EXPECT_MENTIONS(error("f 1// 2 3"), "c.obj:6: OBJ parse error: corner '1//' has no normal index after '/'");
    EXPECT_MENTIONS(error("f 1/1/ 2 3"), "has no normal index");
    EXPECT_MENTIONS(error("f 1/1/1/1 2 3"), "'1/1' is not a normal index");
    EXPECT_MENTIONS(error("f 1 2 3x"), "c.obj:6: OBJ parse error: '3x' is not a vertex index");
    EXPECT_MENTIONS(error("f 1 2 +3"), "'+3' is not a vertex index");
    EXPECT_MENTIONS(error("f 1 2 -4"), "face refers to vertex -4 but only 3 come before it");
    // Its number reader: 0e999 is nan, a 70-digit fraction loses its digits, +-1 and 1.5abc are read
    // as 0 and 1.5, an exponent beyond 2^31 overflows an int (also in a vertex colour).
    EXPECT_MENTIONS(error("v 0e999 0 0"), "c.obj:6: OBJ parse error: '0e999' has an exponent beyond +-400");
    EXPECT_MENTIONS(error("v 0." + std::string(70, '0') + "1e71 0 0"), "characters");
    EXPECT_MENTIONS(error("v +-1 0 0"), "c.obj:6: OBJ parse error: '+-1' is not a finite number");
    EXPECT_MENTIONS(error("v 1.5abc 0 0"), "'1.5abc' is not a finite number");
    EXPECT_MENTIONS(error("v 0 0 0 1 1 0e2147483649"), "c.obj:6: OBJ parse error: '0e2147483649' has an exponent");
    EXPECT_MENTIONS(error("vt 0 1e39"), "'1e39' is not a finite number");
    EXPECT_MENTIONS(error("vn 0 1"), "c.obj:6: OBJ parse error: a normal needs 3 numbers");
    // Accepted: a leading '+', '.5' and '5.', w, colours, a comment after the numbers.
    const Mesh mesh = parseObj("v +1 0 0 1\nv .5 0 5. 1 0 0\nv 0 0 -1 # tip\nf 1 2 3\n", "ok.obj");
    ASSERT_EQ(mesh.vertices.size(), 3u);
    EXPECT_EQ(mesh.vertices[0].position, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(mesh.vertices[1].position, glm::vec3(0.5f, 0.0f, 5.0f));
}

TEST(RobustObj, ConcaveQuadsAreSplitInside) {
    // Seen from +y: (0,0), (0.5,0.1), (1,0), (0.5,10), the second corner reflex. The shorter diagonal
    // (tinyobjloader's choice) runs outside; ours from the reflex corner.
    const Mesh dart = parseObj("v 0 0 0\nv 0.5 0 -0.1\nv 1 0 0\nv 0.5 0 -10\nf 1 2 3 4\n", "dart.obj");
    ASSERT_EQ(dart.indices.size(), 6u);
    for (size_t t = 0; t < 6; t += 3) {
        const glm::vec3 a = dart.vertices[dart.indices[t]].position, b = dart.vertices[dart.indices[t + 1]].position,
                        c = dart.vertices[dart.indices[t + 2]].position;
        EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f) << "triangle " << t / 3 << " wound like the quad";
    }
    EXPECT_NEAR(projectedArea(dart), 4.95, 1e-5);
}

// ---------------------------------------------------------------------------------------------
// Benchmark specs, checked as a whole against the real plugins' descriptors

namespace {

const std::vector<TechniqueInfo>& realTechniques() {
    static const std::vector<TechniqueInfo> techniques = [] {
        PluginScan scan = scanPlugins(pluginDir());
        scan.techniques.push_back(copyDescriptor(referenceDescriptor(), {}));
        return scan.techniques;
    }();
    return techniques;
}

std::string specError(BenchSpec spec, std::optional<double> lightSize = std::nullopt) {
    std::string error;
    if (checkBenchSpec(spec, realTechniques(), error, lightSize)) {
        ADD_FAILURE() << "the spec was accepted";
        return "";
    }
    return error;
}

BenchSpec commandLineSpec(const std::vector<std::string>& sweeps) {
    BenchSpec spec;
    spec.fromCommandLine = true;
    for (const auto& sweep : sweeps) {
        std::string error;
        EXPECT_TRUE(addSweep(spec, sweep, error)) << error;
    }
    return spec;
}

} // namespace

TEST(RobustBench, EveryValueIsCheckedBeforeTheRunNamingTheOption) {
    ASSERT_GE(realTechniques().size(), 10u) << "the plugins are built";
    std::string error;
    EXPECT_TRUE(checkBenchSpec(commandLineSpec({"resolution=256,512", "light.size=0.5,2"}), realTechniques(), error)) << error;

    EXPECT_MENTIONS(specError(commandLineSpec({"light.size=abc"})), "--sweep light.size=...: 'abc' is not a number");
    // Named after the first technique with the parameter (by category, then id: csm among the hard ones).
    EXPECT_MENTIONS(specError(commandLineSpec({"resolution=256,abc"})), "--sweep resolution=...: csm: parameter 'resolution': 'abc' is not a number");
    EXPECT_MENTIONS(specError(commandLineSpec({"resolution=100000"})), "out of range");
    EXPECT_MENTIONS(specError(commandLineSpec({"scene.floating=4,lots"})), "'lots' is not a number");
    EXPECT_MENTIONS(specError(commandLineSpec({"light.size=50"})), "'50' on scene 'cube': a directional light's size");
    EXPECT_MENTIONS(specError(commandLineSpec({}), 1000.0), "--light-size on scene 'cube'");
    EXPECT_MENTIONS(specError(commandLineSpec({"light.size=nan"})), "'nan' is not a number");
    EXPECT_MENTIONS(specError(commandLineSpec({"resolutoin=256"})), "'resolutoin' is no parameter");

    BenchSpec spec = commandLineSpec({});
    spec.reference = "sofft";
    EXPECT_MENTIONS(specError(spec), "--reference 'sofft': expected hard, soft, both or auto");
    spec.reference = "bogus";
    EXPECT_MENTIONS(specError(spec), "--reference 'bogus'");
    spec = commandLineSpec({});
    spec.referenceSamples = 0;
    EXPECT_MENTIONS(specError(spec), "--samples 0: expected 1 to 4096");
    spec = commandLineSpec({});
    spec.scenes = {"cube", "contact", "no-such-scene"};
    EXPECT_MENTIONS(specError(spec), "--scenes 'no-such-scene': no-such-scene: cannot open scene file");
    spec = commandLineSpec({});
    spec.techniques = {"shadowmap", "shadowmapp"};
    EXPECT_MENTIONS(specError(spec), "--techniques: no technique 'shadowmapp'");
    spec = commandLineSpec({});
    spec.base = {"light.size=3"};
    EXPECT_MENTIONS(specError(spec), "--set light.size=3: 'light.size' is not a technique parameter");
    spec = commandLineSpec({});
    spec.base = {"kernel=abc"};
    EXPECT_MENTIONS(specError(spec), "--set kernel=abc");
    spec = commandLineSpec({"scene.count=5000000"});
    spec.scenes = {"dense"};
    EXPECT_MENTIONS(specError(spec), "--scenes 'dense': builtin:dense: objects[1].repeat.count: must be between 0 and 1000000");

    glm::ivec2 size;
    for (const char* bad : {"64x64junk", "64x", "x64", "64*64", "8x8", "64x99999", " 64x64", "+64x64"}) {
        EXPECT_FALSE(parseSize(bad, size, error)) << bad;
        EXPECT_MENTIONS(error, "WIDTHxHEIGHT");
    }
    EXPECT_TRUE(parseSize("64X48", size, error));
    EXPECT_EQ(size, glm::ivec2(64, 48));

    // --reference-adaptive on | off
    bool adaptive = false;
    EXPECT_TRUE(parseOnOff("on", adaptive, error, "--reference-adaptive"));
    EXPECT_TRUE(adaptive);
    EXPECT_TRUE(parseOnOff("off", adaptive, error, "--reference-adaptive"));
    EXPECT_FALSE(adaptive);
    for (const char* bad : {"maybe", "", "On ", "yes"}) {
        EXPECT_FALSE(parseOnOff(bad, adaptive, error, "--reference-adaptive")) << bad;
        EXPECT_MENTIONS(error, "--reference-adaptive '" + std::string(bad) + "': expected on or off");
    }
    EXPECT_TRUE(BenchSpec{}.referenceAdaptive) << "the soft reference is adaptive by default";
    EXPECT_EQ(BenchSpec{}.referenceSamples, 1024);
}

TEST(RobustBench, TheShippedSpecsPassTheCheck) {
    // Every spec shipped in assets/bench, so a new one is checked on its first build.
    size_t checked = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(SHADOWLAB_SOURCE_DIR) / "assets" / "bench")) {
        if (entry.path().extension() != ".json") continue;
        SCOPED_TRACE(entry.path().filename().string());
        ++checked;
        std::vector<BenchSpec> specs;
        std::string error;
        ASSERT_TRUE(loadBenchSpecs(entry.path(), specs, error)) << error;
        for (const BenchSpec& spec : specs) EXPECT_TRUE(checkBenchSpec(spec, realTechniques(), error)) << error;
    }
    EXPECT_GE(checked, 8u);
}

TEST(RobustBench, DepthFloorResolutionsAreChecked) {
    // The issue's case: an uncaught std::stoi (exit 134) once the depth floor reached "abc".
    BenchSpec spec = commandLineSpec({"resolution=256,abc"});
    spec.techniques = {"shadowmap"};
    spec.depthFloor = true;
    EXPECT_MENTIONS(specError(spec), "'abc' is not a number");
}

TEST(RobustBench, JsonSpecsAreStrictAboutTypesAndRanges) {
    std::string error;
    BenchSpec spec;
    for (const char* bad : {R"({"frames": 1e300})", R"({"frames": 3.5})", R"({"frames": 0})", R"({"warmup": -1})",
                            R"({"referenceSamples": 0})", R"({"accuracy": "yes"})", R"({"scenes": []})", R"({"scenes": "cube"})",
                            R"({"sizes": ["64x64junk"]})", R"({"sweep": {"resolution": [[512]]}})", R"({"base": {"kernel": {}}})",
                            R"({"reference": 3})", R"({"referenceAdaptive": "on"})", R"({"referenceAdaptive": 1})",
                            R"({"stableWithin": 0})", R"({"stableWithin": 0.9})", R"({"stableWithin": "1%"})",
                            R"({"minFrames": 5})", R"({"minFrames": 12.5})"}) {
        EXPECT_FALSE(parseBenchSpec(nlohmann::json::parse(bad), spec, error)) << bad;
    }
    TempDir dir;
    const fs::path file = dir.write("spec.json", R"([{"frames": 2}, {"sweep": {"resolution": [1e400]}}])");
    std::vector<BenchSpec> specs;
    EXPECT_FALSE(loadBenchSpecs(file, specs, error));
    EXPECT_MENTIONS(error, file.string() + ": JSON error: number overflow");
    EXPECT_FALSE(loadBenchSpecs(dir.fifo("spec.fifo"), specs, error));
    EXPECT_MENTIONS(error, "a FIFO");
}

TEST(RobustBench, ASweepWithABadValueLateInItMeasuresNothing) {
    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    BenchSpec spec;
    spec.techniques = {"none", "shadowmap"};
    spec.scenes = {"cube", "contact", "no-such-scene"};
    spec.sizes = {{64, 48}};
    spec.frames = 1;
    spec.warmupFrames = 0;
    std::vector<nlohmann::json> rows;
    int measured = 0;
    std::string error;
    EXPECT_FALSE(runBench(*app, spec, rows, error, [&](const nlohmann::json&) { ++measured; }));
    EXPECT_MENTIONS(error, "no-such-scene");
    EXPECT_EQ(measured, 0) << "refused before the first row";
    EXPECT_TRUE(rows.empty());
}

// ---------------------------------------------------------------------------------------------
// The reference refuses non-finite light input itself (whoever calls it)

TEST(RobustReference, NonFiniteLightIsRefusedWithAMessage) {
    std::string error;
    GroundTruthPtr groundTruth = loadGroundTruth(error);
    ASSERT_TRUE(groundTruth) << error;
    groundTruth->setScene(loadScene("cube"));
    const glm::vec4 position(0.0f, 0.0f, 0.0f, 1.0f), normal(0.0f, 1.0f, 0.0f, 0.0f);
    const GBufferView gbuffer{1, 1, &position, &normal};
    std::vector<glm::vec3> visibility;
    ReferenceOptions soft;
    soft.mode = ReferenceOptions::Mode::Soft;
    auto refusal = [&](LightInfo light) {
        try {
            groundTruth->trace(gbuffer, light, soft, visibility);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    LightInfo light;
    light.size = INFINITY;
    EXPECT_MENTIONS(refusal(light), "the light's size");
    light = LightInfo{};
    light.type = LightType::Point;
    light.position = glm::vec3(0.0f, INFINITY, 0.0f);
    EXPECT_MENTIONS(refusal(light), "the light's position is not finite");
    light = LightInfo{};
    light.direction = glm::vec3(NAN);
    EXPECT_MENTIONS(refusal(light), "direction is not a finite non-zero vector");
    EXPECT_EQ(refusal(LightInfo{}), "accepted");
}

// ---------------------------------------------------------------------------------------------
// Issue 31: one rule for every reader of the same structure

TEST(RobustRules, DuplicateJsonKeysAreRefusedNamingTheKeyAndWhere) {
    nlohmann::json json;
    std::string error;
    EXPECT_FALSE(parseJsonText(R"({"a": 1, "b": 2, "a": 3})", "top.json", json, error));
    EXPECT_MENTIONS(error, "top.json: duplicate key \"a\" in the top-level object");
    EXPECT_FALSE(parseJsonText(R"({"steps": [{"x": 1}, {"x": 1, "p": {"k": 1, "k": 2}}]})", "deep.json", json, error));
    EXPECT_MENTIONS(error, "deep.json: duplicate key \"k\" in \"/steps/1/p\"");
    EXPECT_FALSE(parseJsonText(R"({"a/b": {"~": [[], {"z": 0, "z": 0}]}})", "escaped.json", json, error));
    EXPECT_MENTIONS(error, "duplicate key \"z\" in \"/a~1b/~0/1\"");   // RFC 6901 escapes
    // The same key in different objects, and a key that is also a value, are fine.
    EXPECT_TRUE(parseJsonText(R"({"a": {"a": "a"}, "b": [{"a": 1}, {"a": 2}], "c": "a"})", "fine.json", json, error)) << error;
    EXPECT_EQ(json["b"][1]["a"], 2);
    // A key of 10,000 bytes is named, not copied whole into the message.
    const std::string longKey(10000, 'k');
    EXPECT_FALSE(parseJsonText("{\"" + longKey + "\": 1, \"" + longKey + "\": 2}", "long.json", json, error));
    EXPECT_LT(error.size(), 400u) << error;
}

TEST(RobustRules, EveryJsonReaderRefusesADuplicateKey) {
    TempDir dir;
    std::string error;
    // Scene files.
    EXPECT_MENTIONS(sceneErrorOf([&] { loadScene(dir.write("s.json", R"({"objects": [{"shape": "box", "shape": "sphere"}]})").string()); }),
                    "s.json: duplicate key \"shape\" in \"/objects/0\"");
    // Benchmark specs.
    std::vector<BenchSpec> specs;
    EXPECT_FALSE(loadBenchSpecs(dir.write("b.json", R"({"techniques": ["shadowmap"], "sweep": {"resolution": [512], "resolution": [1024]}})"),
                                specs, error));
    EXPECT_MENTIONS(error, "b.json: duplicate key \"resolution\" in \"/sweep\"");
    // Tours and sessions.
    Tour tour;
    EXPECT_FALSE(loadTour(dir.write("t.json", R"({"title": "t", "title": "u", "steps": []})").string(), realTechniques(), tour, error));
    EXPECT_MENTIONS(error, "t.json: duplicate key \"title\" in the top-level object");
    TourStep step;
    EXPECT_FALSE(loadSession(dir.write("x.json", R"({"title": "s", "scene": "cube", "technique": "shadowmap", "caption": "c",
                                                     "light": {"size": 1, "size": 2}})"),
                             realTechniques(), step, error));
    EXPECT_MENTIONS(error, "x.json: duplicate key \"size\" in \"/light\"");
    // Camera paths and stress cases files.
    CameraPath path;
    EXPECT_FALSE(loadPathFile(dir.write("p.json", R"({"keyframes": [{"time": 0}], "frames": 2, "frames": 3})").string(), path, error));
    EXPECT_MENTIONS(error, "p.json: duplicate key \"frames\"");
    StressSuite suite;
    EXPECT_FALSE(loadStressSuite(dir.write("c.json", R"({"cases": [], "cases": []})"), suite, error));
    EXPECT_MENTIONS(error, "c.json: duplicate key \"cases\"");
}

TEST(RobustRules, RepeatedOptionKeysAndEmptyListItemsAreRefused) {
    SceneBudget budget;
    std::string error;
    EXPECT_FALSE(parseSceneBudget("objects=10,objects=20", budget, error));
    EXPECT_MENTIONS(error, "--budget 'objects=10,objects=20': the key 'objects' is given twice");
    for (const char* text : {"objects=10,,triangles=5", ",objects=10", "objects=10,", ""}) {
        EXPECT_FALSE(parseSceneBudget(text, budget, error)) << text;
        EXPECT_MENTIONS(error, "of the list is empty");
    }
    BenchSpec spec;
    EXPECT_FALSE(addSweep(spec, "resolution=512,,1024", error));
    EXPECT_MENTIONS(error, "--sweep resolution=... '512,,1024': item 2 of the list is empty");
    EXPECT_FALSE(addSweep(spec, "resolution=512,", error));
    EXPECT_MENTIONS(error, "item 2 of the list is empty");
    EXPECT_TRUE(addSweep(spec, "resolution=512,1024", error)) << error;
    EXPECT_FALSE(addSweep(spec, "resolution=2048", error));
    EXPECT_MENTIONS(error, "--sweep resolution=...: the key is swept twice");
    EXPECT_EQ(spec.sweeps["resolution"], (std::vector<std::string>{"512", "1024"})) << "the first list kept";
    std::vector<std::string> items;
    EXPECT_TRUE(splitList("a,b,c", "--x", items, error));
    EXPECT_EQ(items, (std::vector<std::string>{"a", "b", "c"}));
    // An empty technique list in a spec file would mean "all": refused.
    EXPECT_FALSE(parseBenchSpec(nlohmann::json::parse(R"({"techniques": []})"), spec, error));
    EXPECT_MENTIONS(error, "techniques: expected a non-empty array");
}

TEST(RobustRules, ASpecFilesContentErrorsNameTheFile) {
    TempDir dir;
    std::vector<BenchSpec> specs;
    std::string error;
    ASSERT_TRUE(loadBenchSpecs(dir.write("one.json", R"({"techniques": ["nosuch"]})"), specs, error)) << error;
    EXPECT_FALSE(checkBenchSpec(specs[0], realTechniques(), error));
    EXPECT_MENTIONS(error, (dir.path() / "one.json").string() + ": techniques: no technique 'nosuch'");
    specs.clear();
    EXPECT_FALSE(loadBenchSpecs(dir.write("two.json", R"([{"techniques": ["shadowmap"]}, {"sizes": ["99999x1"]}])"), specs, error));
    EXPECT_MENTIONS(error, "two.json: spec 1: sizes:");
    specs.clear();
    ASSERT_TRUE(loadBenchSpecs(dir.write("three.json", R"([{"techniques": ["shadowmap"]},
        {"techniques": ["shadowmap"], "scenes": ["nowhere"]}])"),
                               specs, error))
        << error;
    EXPECT_TRUE(checkBenchSpec(specs[0], realTechniques(), error)) << error;
    EXPECT_FALSE(checkBenchSpec(specs[1], realTechniques(), error));
    EXPECT_MENTIONS(error, "three.json: spec 1: scenes 'nowhere'");
    // From the command line, the option is named, with no file.
    EXPECT_MENTIONS(specError(commandLineSpec({"resolutoin=256"})), "--sweep resolutoin=...");
}

TEST(RobustRules, OneCameraCheckForScenesToursSessionsAndPaths) {
    // The same camera, 5e-5 apart: refused by every reader alike (it used to pass a scene file).
    EXPECT_MENTIONS(parseError(R"({"camera": {"position": [1, 1, 1], "target": [1, 1, 1.00005]}, "objects": [{"shape": "box"}]})"),
                    "bad.json: camera.target: the target is at the camera position");
    std::string error;
    TourStep step;
    nlohmann::json session = {{"title", "s"}, {"scene", "cube"}, {"technique", "shadowmap"}, {"caption", "c"},
                              {"camera", {{"position", {1, 1, 1}}, {"target", {1, 1, 1.00005}}}}};
    EXPECT_FALSE(parseTourStep(session, "s.json", {}, step, error));
    EXPECT_MENTIONS(error, "s.json.camera: the target is at the camera position");
    CameraPath path;
    EXPECT_FALSE(parsePath(nlohmann::json::parse(R"({"keyframes": [{"time": 0, "camera": {"position": [1, 1, 1], "target": [1, 1, 1.00005]}}]})"),
                           "p.json", path, error));
    EXPECT_MENTIONS(error, "p.json: keyframes[0].camera: the target is at the camera position");
    // Looking straight down the scene's up vector: refused in a scene, a step and a path's frames.
    EXPECT_MENTIONS(parseError(R"({"camera": {"position": [0, 9, 0], "target": [0, 0, 0]}, "objects": [{"shape": "box"}]})"),
                    "camera.up: the camera looks straight along its up vector");
    session["camera"] = {{"position", {0, 9, 0}}, {"target", {0, 0, 0}}};
    ASSERT_TRUE(parseTourStep(session, "s.json", {}, step, error)) << error;   // the scene's up is known only to the check
    EXPECT_FALSE(checkTourStep(step, "s.json", realTechniques(), error));
    EXPECT_MENTIONS(error, "s.json (\"s\"): camera: the camera looks straight along its up vector");
    ASSERT_TRUE(parsePath(nlohmann::json::parse(R"({"keyframes": [{"time": 0, "camera": {"position": [0, 9, 0], "target": [0, 0, 0]}},
                                                                  {"time": 1, "camera": {"position": [4, 9, 0]}}], "frames": 5})"),
                          "p.json", path, error))
        << error;
    const Scene cube = loadScene("cube");
    EXPECT_MENTIONS(pathSceneProblem(path, cube), "p.json: frame 0 (time 0): the camera looks straight along its up vector");
    // Between keyframes: the eye passes through the target at the middle frame.
    ASSERT_TRUE(parsePath(nlohmann::json::parse(R"({"keyframes": [{"time": 0, "camera": {"position": [-2, 0, 0], "target": [0, 0, 0]}},
                                                                  {"time": 1, "camera": {"position": [2, 0, 0], "target": [0, 0, 0]}}], "frames": 5})"),
                          "p.json", path, error))
        << error;
    EXPECT_MENTIONS(pathSceneProblem(path, cube), "p.json: frame 2 (time 0.5): the target is at the camera position");
    path.frames = 4;   // frames at 0, 1/3, 2/3, 1: never on the target
    EXPECT_EQ(pathSceneProblem(path, cube), "");
}

TEST(RobustRules, OneLightDirectionCheckForScenesToursAndPaths) {
    EXPECT_MENTIONS(parseError(R"({"light": {"direction": [0, 0, 0]}, "objects": [{"shape": "box"}]})"),
                    "light.direction: zero-length direction");
    std::string error;
    TourStep step;
    EXPECT_FALSE(parseTourStep({{"title", "s"}, {"scene", "cube"}, {"technique", "shadowmap"}, {"caption", "c"},
                                {"light", {{"direction", {0, 0, 0}}}}},
                               "s.json", {}, step, error));
    EXPECT_MENTIONS(error, "s.json.light.direction: zero-length direction");
    CameraPath path;
    EXPECT_FALSE(parsePath(nlohmann::json::parse(R"({"keyframes": [{"time": 0, "light": {"direction": [0, 0, 0]}}]})"), "p.json", path, error));
    EXPECT_MENTIONS(error, "p.json: keyframes[0].light.direction: zero-length direction");
    // Opposite directions interpolate through zero: the frame between them is refused.
    ASSERT_TRUE(parsePath(nlohmann::json::parse(R"({"keyframes": [{"time": 0, "light": {"direction": [1, -1, 0]}},
                                                                  {"time": 1, "light": {"direction": [-1, 1, 0]}}], "frames": 3})"),
                          "p.json", path, error))
        << error;
    EXPECT_MENTIONS(pathSceneProblem(path, loadScene("cube")), "p.json: frame 1 (time 0.5): the light's direction passes through zero");
}

TEST(RobustRules, ARepeatGridIsHeldToTheCellLimitInEveryForm) {
    // Grid alone, grid with a count, and a count alone: the same limit of 1,000,000 cells.
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "repeat": {"grid": [1001, 1000]}}]})"),
                    "objects[0].repeat.grid: 1001 x 1000 = 1001000 cells, more than 1000000");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "repeat": {"count": 2, "grid": [1000000, 1000000]}}]})"),
                    "objects[0].repeat.grid: 1000000 x 1000000 = 1000000000000 cells, more than 1000000");
    EXPECT_MENTIONS(parseError(R"({"objects": [{"shape": "box", "repeat": {"count": 1000001}}]})"), "objects[0].repeat.count");
    EXPECT_MENTIONS(sceneErrorOf([] {
                        checkSceneText(R"({"objects": [{"shape": "box", "repeat": {"count": 2, "grid": [1000000, 1000000]}}]})",
                                       "check.json", fs::current_path());
                    }),
                    "check.json: objects[0].repeat.grid");
    EXPECT_NO_THROW(parseScene(R"({"objects": [{"shape": "box", "repeat": {"count": 3, "grid": [1000, 1000]}}]})", "ok.json",
                               fs::current_path()));
}

TEST(RobustRules, MessagesKeepTheirSubjectPastANulByte) {
    // what() is a C string: the NUL is shown as \x00 and what follows it is kept.
    const std::string obj = std::string("v 0 0 0\nv 1 0 0\nv 0 0 -1\nf 1 2 3x") + '\0' + "tail\n";
    const std::string message = sceneErrorOf([&] { parseObj(obj, "nul.obj"); });
    EXPECT_MENTIONS(message, "nul.obj:4:");
    EXPECT_MENTIONS(message, "3x\\x00tail");
    EXPECT_MENTIONS(parseError(std::string(R"({"objects": [{"shape": "box"}], "na\u0000me": 1})")), "na\\x00me: unknown field");
    EXPECT_EQ(printable(std::string("a\0b\x1b[31mc\n", 10)), "a\\x00b\\x1b[31mc\\x0a");
    EXPECT_EQ(printable(std::string("line\n\tnext"), true), "line\n\tnext");
    EXPECT_EQ(quoteForMessage(std::string(100, 'k'), 10), "\"kkkkkkkkkk...\"");
}

// Ctrl-C (util/progress.h): the flag stops generation (nothing partial to keep) and a sweep at its
// next frame, with the rows measured before it kept.
TEST(RobustRules, AnInterruptStopsGenerationAndKeepsTheRowsMeasured) {
    requestInterrupt();
    EXPECT_THROW(makeSphere(1.0f, 64, 64), Interrupted);
    EXPECT_THROW(loadScene("spheres"), Interrupted);
    Progress progress("test", 10, "steps");
    EXPECT_FALSE(progress.step(1));
    clearInterrupt();
    EXPECT_TRUE(progress.step(2));
    EXPECT_EQ(makeSphere(1.0f, 64, 64).indices.size(), size_t(64) * 63 * 2 * 3) << "generates again once cleared";

    auto app = test::makeHeadlessApp("cube", {64, 48});
    ASSERT_TRUE(app);
    BenchSpec spec;
    spec.techniques = {"shadowmap"};
    spec.sizes = {{64, 48}};
    spec.frames = 3;
    spec.warmupFrames = 0;
    std::string error;
    ASSERT_TRUE(addSweep(spec, "resolution=256,512,1024,2048", error)) << error;
    std::vector<nlohmann::json> rows;
    int delivered = 0;
    // Ctrl-C while the second row is measured (raised as the first is delivered).
    EXPECT_FALSE(runBench(*app, spec, rows, error, [&](const nlohmann::json&) {
        if (++delivered == 1) requestInterrupt();
    }));
    const bool wasInterrupted = interrupted();
    clearInterrupt();
    EXPECT_TRUE(wasInterrupted);
    EXPECT_MENTIONS(error, "interrupted (Ctrl-C)");
    EXPECT_EQ(delivered, 1);
    ASSERT_EQ(rows.size(), 1u) << "the row in progress is dropped, the one before kept";
    EXPECT_EQ(rows[0]["param.resolution"], "256");
    rows.clear();
    EXPECT_TRUE(runBench(*app, spec, rows, error)) << error;
    EXPECT_EQ(rows.size(), 4u) << "the app draws again once the flag is cleared";
}
