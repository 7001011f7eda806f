// Light-space fitting (see light_space.h). Depth range is fitted to the box too, so the full
// precision of the shadow map's depth covers the objects that matter.
#include "render/light_space.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace shadowlab {
namespace {

glm::vec3 upFor(glm::vec3 forward) {
    return std::abs(forward.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
}

} // namespace

void boxCorners(const Bounds& b, glm::vec3 corners[8]) {
    for (int i = 0; i < 8; ++i)
        corners[i] = {i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z};
}

LightSpace fitLightSpaceToPoints(const LightInfo& light, const glm::vec3* points, size_t count, const Bounds* casters) {
    Bounds box{glm::vec3(1e30f), glm::vec3(-1e30f)};
    for (size_t i = 0; i < count; ++i) {
        box.min = glm::min(box.min, points[i]);
        box.max = glm::max(box.max, points[i]);
    }
    if (count == 0) box = {glm::vec3(-1.0f), glm::vec3(1.0f)};
    const glm::vec3 center = 0.5f * (box.min + box.max);
    const float radius = std::max(0.5f * glm::length(box.max - box.min), 1e-3f);
    glm::vec3 casterCorners[8];
    if (casters) boxCorners(*casters, casterCorners);
    LightSpace ls{};

    if (light.type == LightType::Directional) {
        const glm::vec3 dir = glm::normalize(light.direction);
        const glm::vec3 eye = center - dir * (2.0f * radius);
        ls.view = glm::lookAt(eye, center, upFor(dir));
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (size_t i = 0; i < count; ++i) {
            const glm::vec3 v = glm::vec3(ls.view * glm::vec4(points[i], 1.0f));
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        // Casters between the light and the region cast into it: reach back to the nearest.
        if (casters)
            for (const auto& c : casterCorners) hi.z = std::max(hi.z, (ls.view * glm::vec4(c, 1.0f)).z);
        // View space looks down -z: near = -hi.z, far = -lo.z, with a small margin.
        const float margin = 0.01f * radius;
        ls.nearPlane = -hi.z - margin;
        ls.farPlane = -lo.z + margin;
        ls.projection = glm::ortho(lo.x, hi.x, lo.y, hi.y, ls.nearPlane, ls.farPlane);
        ls.perspective = false;
        ls.worldSizeAtUnitDepth = {hi.x - lo.x, hi.y - lo.y};
    } else {
        const glm::vec3 eye = light.position;
        const glm::vec3 forward = light.type == LightType::Spot ? glm::normalize(light.direction)
                                                                : glm::normalize(center - eye);
        ls.view = glm::lookAt(eye, eye + forward, upFor(forward));
        float nearest = 1e30f, farthest = 0.0f, maxTan = 0.0f;
        for (size_t i = 0; i < count; ++i) {
            const glm::vec3 v = glm::vec3(ls.view * glm::vec4(points[i], 1.0f));
            const float depth = -v.z;
            farthest = std::max(farthest, depth);
            nearest = std::min(nearest, depth);
            if (depth > 1e-4f) maxTan = std::max({maxTan, std::abs(v.x) / depth, std::abs(v.y) / depth});
        }
        if (casters)
            for (const auto& c : casterCorners) nearest = std::min(nearest, -(ls.view * glm::vec4(c, 1.0f)).z);
        float halfFov;
        if (light.type == LightType::Spot) {
            halfFov = std::min(light.spotOuterAngle * 1.02f, glm::radians(85.0f));
        } else {
            halfFov = std::clamp(std::atan(maxTan > 0 ? maxTan : 1.0f) * 1.02f, glm::radians(5.0f), glm::radians(80.0f));
        }
        // A near plane too close wastes depth precision; boxes reaching behind the light clamp.
        ls.farPlane = std::max(farthest * 1.01f, 1e-2f);
        ls.nearPlane = std::clamp(nearest * 0.99f, ls.farPlane * 1e-3f, ls.farPlane * 0.99f);
        ls.projection = glm::perspective(2.0f * halfFov, 1.0f, ls.nearPlane, ls.farPlane);
        ls.perspective = true;
        ls.worldSizeAtUnitDepth = glm::vec2(2.0f * std::tan(halfFov));
    }
    ls.viewProjection = ls.projection * ls.view;
    return ls;
}

LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds, const Bounds* casters) {
    glm::vec3 corners[8];
    boxCorners(bounds, corners);
    return fitLightSpaceToPoints(light, corners, 8, casters);
}

void frustumSliceCorners(const CameraInfo& camera, float nearDistance, float farDistance, glm::vec3 corners[8]) {
    // Corner i of the near plane lies at view depth camera.nearPlane on the ray from the eye
    // through it; the same ray reaches depth d at eye + (corner - eye) d / near.
    const float n = std::max(camera.nearPlane, 1e-6f);
    for (int i = 0; i < 4; ++i) {
        const glm::vec3 ray = (camera.frustumCorners[i] - camera.position) / n;
        corners[i] = camera.position + ray * nearDistance;
        corners[i + 4] = camera.position + ray * farDistance;
    }
}

} // namespace shadowlab
