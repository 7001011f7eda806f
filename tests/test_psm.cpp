// Perspective shadow maps' light space (plugins/psm/psm_space.h, seed 002 ch. 7): eq. 7.1-7.2,
// and for each post-perspective light type (Fig. 7.8) that the map holds the focus body and keeps
// the depth order along every light ray: the point nearer the real light gets the smaller depth,
// also for the inverted light from behind the viewer, where PP reverses the order.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <random>

#include "shadowlab/kit/psm_space.h"
#include "camera.h"
#include "shadowlab/kit/focus.h"

using namespace shadowlab;

namespace {

CameraInfo levelCamera() {
    CameraInfo c{};
    c.position = {0, 2, 0};
    c.view = glm::lookAt(c.position, glm::vec3(0, 2, -10), glm::vec3(0, 1, 0));
    c.nearPlane = 0.5f;
    c.farPlane = 60.0f;
    c.fovY = glm::radians(60.0f);
    c.aspect = 16.0f / 9.0f;
    c.projection = glm::perspective(c.fovY, c.aspect, c.nearPlane, c.farPlane);
    c.viewport = {320, 180};
    c.viewProjection = c.projection * c.view;
    completeCameraInfo(c);
    return c;
}

const Bounds kScene{{-80, 0, -80}, {80, 12, 80}};

LightInfo sun(glm::vec3 travel) {
    LightInfo light;
    light.type = LightType::Directional;
    light.direction = glm::normalize(travel);
    return light;
}

// The map's depth of world point p (NDC z).
float mapDepth(const glm::mat4& m, glm::vec3 p) {
    const glm::vec4 q = m * glm::vec4(p, 1.0f);
    return q.z / q.w;
}

void expectHoldsBodyAndKeepsOrder(const CameraInfo& camera, const LightInfo& light, psm::PostPerspectiveLight expected) {
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    ASSERT_FALSE(body.empty());
    const auto space = psm::psmSpace(camera, light, body.vertices());
    ASSERT_TRUE(space);
    EXPECT_EQ(int(space->lightType), int(expected));
    for (const glm::vec3& v : body.vertices()) {
        const glm::vec4 q = space->viewProjection * glm::vec4(v, 1.0f);
        ASSERT_GT(q.w, 0.0f);
        EXPECT_LE(std::abs(q.x / q.w), 1.0f + 1e-3f);
        EXPECT_LE(std::abs(q.y / q.w), 1.0f + 1e-3f);
        EXPECT_LE(std::abs(q.z / q.w), 1.0f + 1e-3f);
        EXPECT_GE(glm::dot(space->clipPlane, glm::vec4(v, 1.0f)), 0.0f) << "B is in front of the virtual camera";
    }
    // Random points inside B (convex combinations of its vertices) and a point a little towards
    // the light on the same ray: same texel, smaller depth.
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto& vertices = body.vertices();
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        glm::vec3 p(0.0f);
        float total = 0.0f;
        for (int k = 0; k < 4; ++k) {
            const float w = unit(random);
            p += w * vertices[size_t(random() % vertices.size())];
            total += w;
        }
        p /= total;
        const glm::vec3 towardsLight = p - 0.5f * light.direction;
        if (!kit::contains(body, towardsLight, 1e-3f)) continue;
        const glm::vec4 a = space->viewProjection * glm::vec4(p, 1.0f), b = space->viewProjection * glm::vec4(towardsLight, 1.0f);
        EXPECT_NEAR(a.x / a.w, b.x / b.w, 1e-3f) << "one light ray, one texel";
        EXPECT_NEAR(a.y / a.w, b.y / b.w, 1e-3f);
        EXPECT_LT(mapDepth(space->viewProjection, towardsLight), mapDepth(space->viewProjection, p)) << "nearer the light, nearer in the map";
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

} // namespace

// Eq. 7.1 at the planes and Table 7.1 (n = 1, f -> infinity: eq. 7.2), re-derived.
TEST(Psm, PostPerspectiveZ) {
    EXPECT_NEAR(psm::postPerspectiveZ(-1.0, 1.0, 100.0), -1.0, 1e-12);
    EXPECT_NEAR(psm::postPerspectiveZ(-100.0, 1.0, 100.0), 1.0, 1e-12);
    for (const auto& [z, zpp] : {std::pair{-1.0, -1.0}, {-2.0, 0.0}, {-4.0, 0.5}, {-10.0, 0.8}, {-100.0, 0.98}})
        EXPECT_NEAR(psm::postPerspectiveZ(z, 1.0, 1e12), zpp, 1e-9) << z;
}

// A sun ahead of the viewer and above: a point light on the near side of PP (Fig. 7.8, left).
TEST(Psm, LightAheadIsAPostPerspectivePointLight) {
    expectHoldsBodyAndKeepsOrder(levelCamera(), sun({0.3f, -1.0f, 0.8f}), psm::PostPerspectiveLight::Point);
}

// The sun behind the viewer: an inverted point light, whose depth is stored negated.
TEST(Psm, LightFromBehindIsInvertedAndKeepsTheOrder) {
    expectHoldsBodyAndKeepsOrder(levelCamera(), sun({0.3f, -1.0f, -0.8f}), psm::PostPerspectiveLight::InvertedPoint);
}

// Straight above a level camera: the light stays directional in PP (Fig. 7.8, left, first case).
TEST(Psm, LightParallelToTheNearPlaneStaysDirectional) {
    expectHoldsBodyAndKeepsOrder(levelCamera(), sun({0.0f, -1.0f, 0.0f}), psm::PostPerspectiveLight::Directional);
}

// Casters behind the viewer: the virtual camera moves back until B is in front of its near plane.
TEST(Psm, MoveBackPutsTheBodyInFront) {
    const CameraInfo camera = levelCamera();
    const LightInfo light = sun({0.0f, -0.5f, -1.0f});   // from behind and low: B reaches far behind
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    const auto space = psm::psmSpace(camera, light, body.vertices());
    ASSERT_TRUE(space);
    EXPECT_GT(space->moveBack, 1.0f);
    EXPECT_NEAR(space->virtualNear, camera.nearPlane, 1e-3f) << "the nearest point of B sits on the virtual near plane";
}

// Duelling frusta: the sun low in front of the viewer, shining back at it; its post-perspective
// position lies among B's image and one frustum cannot hold B.
TEST(Psm, LightShiningBackAtTheViewerHasNoSingleMap) {
    const CameraInfo camera = levelCamera();
    const LightInfo light = sun({0.0f, -0.15f, 1.0f});
    const kit::ConvexBody body = kit::focusBody(camera, light, kScene, LightSpace{});
    EXPECT_FALSE(psm::psmSpace(camera, light, body.vertices()));
}

// The near plane pushed to the nearest receiver in view: a box 10 units ahead of a camera that sees
// nothing nearer; behind the camera and outside the frustum nothing counts.
TEST(Psm, NearestReceiverDepthIsTheFirstReceiverInView) {
    const CameraInfo camera = levelCamera();
    std::vector<ObjectInfo> objects(3);
    objects[0].bounds = {{-1, 1, -11}, {1, 3, -10}};     // ahead, in view
    objects[1].bounds = {{-1, 1, 3}, {1, 3, 5}};         // behind the camera
    objects[2].bounds = {{40, 1, -6}, {42, 3, -5}};      // far off to the side, outside the frustum
    for (auto& o : objects) o.flags = kObjectReceivesShadow | kObjectCastsShadow;
    EXPECT_NEAR(psm::nearestReceiverDepth(camera, objects.data(), 3), 10.0f, 1e-3f);
    objects[0].flags = kObjectCastsShadow;   // a caster only: nothing receives in view
    EXPECT_NEAR(psm::nearestReceiverDepth(camera, objects.data(), 3), camera.farPlane, 1e-3f);
}

// A plane's bounds are flat (zero height); the frustum clipped by them has no volume, and before
// paddedReceiverBounds the ground never counted as a receiver: the near plane went past it to the
// first box in view or to the far plane (aliasing-plane: every pixel outside psm's map;
// perspective-near: the ground's shadow next to the camera lost, MAE 0.81). The level camera 2
// above flat ground, field of view 60 degrees: the frustum's lower edge meets the ground at
// 2 / tan(30 deg); the pad (1e-5 of the far distance) may only make the depth nearer.
TEST(Psm, NearestReceiverDepthCountsAGroundPlane) {
    const CameraInfo camera = levelCamera();
    std::vector<ObjectInfo> objects(2);
    objects[0].bounds = {{-80, 0, -80}, {80, 0, 80}};   // the ground plane: flat bounds
    objects[0].flags = kObjectReceivesShadow | kObjectCastsShadow | kObjectPlane;
    objects[1].bounds = {{-1, 1, -11}, {1, 3, -10}};     // a box 10 ahead
    objects[1].flags = kObjectReceivesShadow | kObjectCastsShadow;
    const float expected = 2.0f / std::tan(glm::radians(30.0f));
    const float found = psm::nearestReceiverDepth(camera, objects.data(), 2);
    EXPECT_LE(found, expected + 1e-4f);
    EXPECT_GT(found, expected - 0.01f) << "the pad moves it nearer by about 1e-5 far / tan(30 deg)";
    // And the map then holds the visible ground: points of it from there to the far plane land
    // inside the map's clip volume (what the main pass and the texel-footprint measure test).
    const CameraInfo shortened = psm::receiverCamera(camera, found);
    const LightInfo light = sun({0.3f, -1.0f, 0.2f});
    const kit::ConvexBody body = kit::focusBody(shortened, light, kScene, LightSpace{});
    const auto space = psm::psmSpace(shortened, light, body.vertices());
    ASSERT_TRUE(space);
    for (const float z : {3.5f, 5.0f, 10.0f, 30.0f, 59.0f}) {
        const glm::vec4 q = space->viewProjection * glm::vec4(0.0f, 0.0f, -z, 1.0f);
        ASSERT_GT(q.w, 0.0f) << z;
        EXPECT_LE(std::abs(q.x / q.w), 1.0f) << z;
        EXPECT_LE(std::abs(q.y / q.w), 1.0f) << z;
    }
}
