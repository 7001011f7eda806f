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

LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds) {
    glm::vec3 corners[8];
    boxCorners(bounds, corners);
    const glm::vec3 center = 0.5f * (bounds.min + bounds.max);
    const float radius = std::max(0.5f * glm::length(bounds.max - bounds.min), 1e-3f);
    LightSpace ls{};

    if (light.type == LightType::Directional) {
        const glm::vec3 dir = glm::normalize(light.direction);
        const glm::vec3 eye = center - dir * (2.0f * radius);
        ls.view = glm::lookAt(eye, center, upFor(dir));
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const auto& c : corners) {
            const glm::vec3 v = glm::vec3(ls.view * glm::vec4(c, 1.0f));
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
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
        for (const auto& c : corners) {
            const glm::vec3 v = glm::vec3(ls.view * glm::vec4(c, 1.0f));
            const float depth = -v.z;
            farthest = std::max(farthest, depth);
            nearest = std::min(nearest, depth);
            if (depth > 1e-4f) maxTan = std::max({maxTan, std::abs(v.x) / depth, std::abs(v.y) / depth});
        }
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

} // namespace shadowlab
