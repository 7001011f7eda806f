// Whether the camera's near plane may lie in a shadow: what decides a shadow-volume technique's
// counting (depth-pass is wrong when the eye is inside a volume; Everitt and Kilgard 2002) and
// anything else that must know whether the view starts in shadow. Conservative: true may be a
// false alarm, false is certain.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <shadowlab/technique.h>

namespace shadowlab::kit {

// Conservative: does the near-plane rectangle, swept towards the light, touch any caster's box?
// A sphere around the rectangle swept along the ray to the light against each box grown by its
// radius (slab test). True means depth-pass may be wrong.
inline bool nearPlaneMayBeInShadow(const FrameContext& frame, const ObjectInfo* objects, uint32_t count) {
    const glm::vec3* c = frame.camera.frustumCorners;
    const glm::vec3 centre = 0.25f * (c[0] + c[1] + c[2] + c[3]);
    float radius = 0.0f;
    for (int i = 0; i < 4; ++i) radius = std::max(radius, glm::length(c[i] - centre));
    const bool directional = frame.light.type == LightType::Directional;
    const glm::vec3 toLight = directional ? -frame.light.direction : frame.light.position - centre;
    const float reach = directional ? 1e30f : 1.0f;   // along toLight
    for (uint32_t i = 0; i < count; ++i) {
        if (!objects[i].castsShadow()) continue;
        const glm::vec3 lo = objects[i].bounds.min - radius, hi = objects[i].bounds.max + radius;
        float t0 = 0.0f, t1 = reach;
        for (int axis = 0; axis < 3 && t0 <= t1; ++axis) {
            if (std::abs(toLight[axis]) < 1e-12f) {
                if (centre[axis] < lo[axis] || centre[axis] > hi[axis]) t0 = 1.0f, t1 = 0.0f;
                continue;
            }
            float a = (lo[axis] - centre[axis]) / toLight[axis], b = (hi[axis] - centre[axis]) / toLight[axis];
            if (a > b) std::swap(a, b);
            t0 = std::max(t0, a);
            t1 = std::min(t1, b);
        }
        if (t0 <= t1) return true;
    }
    return false;
}

} // namespace shadowlab::kit
