// LiSPSM under point lights: one warped map per cube face (kit/warped_faces.h, seed 002 sec. 8.2.4
// / 9.2.3). The faces' bodies against the lookup's face choice (pure maths), the error on
// `point-light` against the Embree reference beside the single focused frustum it replaces and
// shadowmap's cube, and the seams between faces in a closed room lit from its middle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "shadowlab/kit/warped_faces.h"
#include "test_support.h"

using namespace shadowlab;

namespace {

// The lookup's face (shaders/cube_faces.glsl's cubeFaceCoord: x on ties with y or z, then y).
int lispsmFacesMajorAxis(glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    if (a.x >= a.y && a.x >= a.z) return d.x > 0.0f ? 0 : 1;
    if (a.y >= a.z) return d.y > 0.0f ? 2 : 3;
    return d.z > 0.0f ? 4 : 5;
}

// How close a direction is to a seam between two faces: the second largest |component| over the
// largest (1 on the seam, 0 on a face's axis).
float lispsmFacesSeamness(glm::vec3 d) {
    float a[3] = {std::abs(d.x), std::abs(d.y), std::abs(d.z)};
    std::sort(a, a + 3);
    return a[2] > 0.0f ? a[1] / a[2] : 0.0f;
}

// A closed room (10 m cube) lit by a bare lamp in its middle, small blocks around the lamp in the
// seam directions of its cube (edges and corners of the faces), seen from a low corner with a wide
// lens: floor, two walls and the ceiling, their shadows across the faces' seams.
const char* kSeamRoom = R"({"name": "seam-room", "description": "a lamp in a closed room, blocks along its cube's seams",
    "camera": {"position": [-4.2, 1.2, -4.2], "target": [3, 4.5, 3], "fovY": 100, "near": 0.1, "far": 40},
    "light": {"type": "point", "position": [0, 5, 0], "size": 0.05},
    "materials": {"grey": {"baseColor": [0.6, 0.6, 0.6]}},
    "objects": [{"name": "floor", "shape": "box", "size": [10.4, 0.2, 10.4], "translate": [0, -0.1, 0], "material": "grey"},
                {"name": "ceiling", "shape": "box", "size": [10.4, 0.2, 10.4], "translate": [0, 10.1, 0], "material": "grey"},
                {"name": "east", "shape": "box", "size": [0.2, 10, 10], "translate": [5.1, 5, 0], "material": "grey"},
                {"name": "west", "shape": "box", "size": [0.2, 10, 10], "translate": [-5.1, 5, 0], "material": "grey"},
                {"name": "north", "shape": "box", "size": [10, 10, 0.2], "translate": [0, 5, 5.1], "material": "grey"},
                {"name": "south", "shape": "box", "size": [10, 10, 0.2], "translate": [0, 5, -5.1], "material": "grey"},
                {"name": "xz", "shape": "box", "size": [0.3, 1.6, 0.3], "translate": [1.1, 5, 1.1], "material": "grey"},
                {"name": "xy", "shape": "box", "size": [0.3, 0.3, 1.6], "translate": [1.1, 6.1, 0.3], "material": "grey"},
                {"name": "x-y", "shape": "box", "size": [0.3, 0.3, 1.6], "translate": [1.1, 3.9, 0.8], "material": "grey"},
                {"name": "z-y", "shape": "box", "size": [1.6, 0.3, 0.3], "translate": [0.4, 3.9, 1.1], "material": "grey"},
                {"name": "zy", "shape": "box", "size": [1.6, 0.3, 0.3], "translate": [0.6, 6.1, 1.1], "material": "grey"},
                {"name": "corner", "shape": "sphere", "radius": 0.25, "translate": [1.0, 4.0, 1.0], "material": "grey"},
                {"name": "corner-up", "shape": "sphere", "radius": 0.25, "translate": [1.0, 6.0, 1.0], "material": "grey"}]})";

struct LispsmSeamCount {
    size_t seamShadowed = 0;   // seam pixels the reference shadows
    size_t seamFalseLight = 0; // of them, lit by the technique
    size_t seamPixels = 0;
};

LispsmSeamCount lispsmCountSeams(const Evaluation& e, glm::vec3 light, float seamness) {
    LispsmSeamCount count;
    for (size_t i = 0; i < e.mask.size(); ++i) {
        if (!e.mask[i] || e.positions[i].w < 0.5f) continue;
        if (lispsmFacesSeamness(glm::vec3(e.positions[i]) - light) < seamness) continue;
        ++count.seamPixels;
        if (e.reference[i].r > 0.5f) continue;
        ++count.seamShadowed;
        if (e.technique[i].r > 0.5f) ++count.seamFalseLight;
    }
    return count;
}

} // namespace

// Every point the camera sees lies in the body B_f of the face the lookup picks for it, and so does
// its segment to the light within the scene (all its casters): the map pass's faces and the lookup's major axis
// agree at the seams. The faces' bodies lie in their padded frusta.
TEST(LispsmFaces, LookupFaceHoldsEveryVisiblePointAndItsCasters) {
    auto app = test::makeHeadlessApp("point-light", {320, 240});
    ASSERT_TRUE(app);
    std::string error;
    ASSERT_TRUE(app->renderFrame("lispsm", error)) << error;
    const CameraInfo camera = app->lastFrame().camera;
    const LightInfo light = app->lastFrame().light;
    const Bounds scene = app->renderer().bounds(DrawSet::All);
    const auto faces = kit::cubeFaceFocus(camera, light, scene);
    int drawn = 0;
    for (const auto& f : faces) drawn += f.body.empty() ? 0 : 1;
    EXPECT_GE(drawn, 4) << "the view from above sees the floor all round the lamp";
    EXPECT_TRUE(faces[2].body.empty()) << "nothing visible above the lamp (+y)";
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int inView = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::vec3 p = scene.min + (scene.max - scene.min) * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec4 clip = camera.viewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 0.0f) || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w || std::abs(clip.z) > clip.w) continue;
        ++inView;
        const auto& f = faces[size_t(lispsmFacesMajorAxis(p - light.position))];
        ASSERT_FALSE(f.body.empty()) << "face " << f.face << " not drawn for a visible point";
        EXPECT_TRUE(kit::contains(f.body, p, 1e-3f)) << "face " << f.face;
        // A caster on the way to the light, where there can be any (in the scene's bounds: the lamp is above them).
        for (const float along : {0.25f, 0.5f, 0.75f}) {
            const glm::vec3 q = glm::mix(light.position, p, along);
            if (glm::all(glm::greaterThanEqual(q, scene.min)) && glm::all(glm::lessThanEqual(q, scene.max))) {
                EXPECT_TRUE(kit::contains(f.body, q, 1e-3f)) << "face " << f.face << " at " << along;
            }
        }
    }
    EXPECT_GT(inView, 1000);
}

// Seed 002 sec. 8.2.4 on `point-light`: the per-face warps against the single focused frustum the
// technique used before (measured with it on llvmpipe at 320 x 240: MAE 0.0037, near third 0.0038,
// mid 0.0023; false shadow 0.11%, false light 0.27%) and shadowmap's cube (2048 faces).
TEST(LispsmFaces, PointLightBelowTheSingleFrustumItReplaces) {
    auto app = test::makeHeadlessApp("point-light", {320, 240});
    ASSERT_TRUE(app);
    const Evaluation faces = test::evaluateTechnique(*app, "lispsm", {}, ReferenceOptions::Mode::Hard);
    const Evaluation cube = test::evaluateTechnique(*app, "shadowmap", {}, ReferenceOptions::Mode::Hard);
    const AccuracyMetrics& m = faces.metrics;
    std::printf("point-light hard MAE all / near / mid / far (false shadow, false light): lispsm faces %.5f / %.5f %.5f %.5f "
                "(%.4f, %.4f), shadowmap cube %.5f / %.5f %.5f %.5f; old single frustum 0.0037 / 0.0038 0.0023 -\n",
                m.mae, m.maeByViewDepth[0], m.maeByViewDepth[1], m.maeByViewDepth[2], m.falseShadowRate, m.falseLightRate,
                cube.metrics.mae, cube.metrics.maeByViewDepth[0], cube.metrics.maeByViewDepth[1],
                cube.metrics.maeByViewDepth[2]);
    constexpr double kOldSingleFrustumMae = 0.0037;
    EXPECT_LT(m.mae, 0.6 * kOldSingleFrustumMae);
    EXPECT_LT(m.maeByViewDepth[0], 0.0025);
    EXPECT_LT(m.falseLightRate, 0.001);
    EXPECT_LT(m.falseShadowRate, 0.002);
    EXPECT_GT(m.comparedFraction, 0.5);
    // The host is told the faces drawn (footprint, debug views): those that see the floor and walls.
    std::string error;
    LoadedTechnique* loaded = app->techniques().get("lispsm", error);
    ASSERT_TRUE(loaded) << error;
    (void)test::evaluateTechnique(*app, "lispsm", {}, ReferenceOptions::Mode::Hard, 1);
    const size_t reported = loaded->host().shadowMaps().size();
    EXPECT_GE(reported, 4u);
    EXPECT_LE(reported, 5u) << "+y sees nothing visible";
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

// The faces' seams: blocks along the lamp's cube edges and corners shadow the walls, floor and
// ceiling across the seams; near the seam directions (second largest component of (P - light) at
// least 0.9 of the largest) the shadows must be there (no crack of light) and not doubled. Also
// with the two-layer midpoint bias and linear depth, which keep per face.
TEST(LispsmFaces, NoCracksAtTheFaceSeams) {
    const test::SceneFile room("seam_room", kSeamRoom);
    auto app = test::makeHeadlessApp(room.path(), {320, 240});
    ASSERT_TRUE(app);
    const glm::vec3 light = app->light().position;
    ASSERT_EQ(app->light().type, LightType::Point);
    for (const std::vector<std::string>& sets : {std::vector<std::string>{}, {"bias_method=midpoint"}, {"depth=linear"}}) {
        SCOPED_TRACE(testing::PrintToString(sets));
        const Evaluation e = test::evaluateTechnique(*app, "lispsm", sets, ReferenceOptions::Mode::Hard);
        const LispsmSeamCount seams = lispsmCountSeams(e, light, 0.9f);
        const double crack = double(seams.seamFalseLight) / double(std::max<size_t>(seams.seamShadowed, 1));
        std::printf("seam room lispsm %s: MAE %.5f (false shadow %.4f, false light %.4f); seam pixels %zu, shadowed %zu, "
                    "lit there %.4f\n",
                    testing::PrintToString(sets).c_str(), e.metrics.mae, e.metrics.falseShadowRate, e.metrics.falseLightRate,
                    seams.seamPixels, seams.seamShadowed, crack);
        ASSERT_GT(seams.seamShadowed, 300u) << "the blocks must shadow the seams in view";
        // Measured on llvmpipe: none lit there, false light 0.00%, false shadow 0.01-0.02%; with the face
        // picked 15% off the major axis towards y (a seam rule the map pass does not share) 1.9% of
        // them lit and 0.05% false light in all.
        EXPECT_LT(crack, 0.005);
        EXPECT_LT(e.metrics.falseLightRate, 0.0002);
        EXPECT_LT(e.metrics.falseShadowRate, 0.002);
    }
}
