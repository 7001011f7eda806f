// Light space of the filterable shadow maps (vsm, esm, evsm, msm), without GL so that tests can
// reproduce the mapping (tests/test_moment_shadows.cpp).
//
// The map covers the same area as the host's default light space (so texel density compares with
// plain shadow mapping at the same resolution), but the stored depth is linear along the light's
// axis and spans the casters (plus some room behind them), not the whole scene:
// d = (distance along the axis - near) / (far - near). See shaders/moment_shadows.glsl.
#pragma once

#include <shadowlab/technique.h>

#include <algorithm>

namespace shadowlab::kit {

struct MomentLightSpace {
    LightSpace light;        // view-projection used for rasterising and for the lookup
    glm::vec4 depthPlane;    // linear depth: d = dot(depthPlane, vec4(world, 1)), [0, 1] over the casters
};

// Distance range along the light's axis of a box's corners.
inline glm::vec2 axisRange(glm::vec4 axis, const Bounds& box) {
    glm::vec2 range{1e30f, -1e30f};
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner{i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                               i & 4 ? box.max.z : box.min.z};
        const float distance = glm::dot(axis, glm::vec4(corner, 1.0f));
        range = {std::min(range.x, distance), std::max(range.y, distance)};
    }
    return range;
}

// `light` is the host's fit around everything; `casters` and `all` are scene bounds.
inline MomentLightSpace fitMomentLightSpace(const LightSpace& light, const Bounds& casters, const Bounds& all) {
    // View space looks down -z, so the distance along the axis is -(view * p).z: an affine
    // function of p whose coefficients are minus the third row of the view matrix.
    const glm::vec4 axis = -glm::vec4(light.view[0][2], light.view[1][2], light.view[2][2], light.view[3][2]);
    const glm::vec2 casterRange = axisRange(axis, casters);
    const float extent = std::max(casterRange.y - casterRange.x, 1e-3f);
    // Near: nothing in front of the nearest caster can occlude. Far: receivers behind the casters are
    // clamped to depth 1, which keeps their test right but collapses their distance to the farthest
    // casters; half the casters' extent of room behind them (if any receiver is there) keeps that
    // distance at a third of the range or more, so exponential warps (ESM, EVSM) still separate them.
    float nearest = casterRange.x - 0.01f * extent;
    float farthest = std::min(casterRange.y + 0.5f * extent, std::max(axisRange(axis, all).y, casterRange.y)) +
                     0.01f * extent;
    // Nothing outside the light's own near/far planes is rasterised (spot lights: nothing behind it).
    nearest = std::max(nearest, light.nearPlane);
    farthest = std::min(farthest, light.farPlane);
    if (!(farthest > nearest)) farthest = nearest + 1e-3f;   // no caster in front of the light
    const float scale = 1.0f / (farthest - nearest);
    return {light, glm::vec4(glm::vec3(axis) * scale, (axis.w - nearest) * scale)};
}

inline float linearLightDepth(const MomentLightSpace& space, glm::vec3 world) {
    return std::clamp(glm::dot(space.depthPlane, glm::vec4(world, 1.0f)), 0.0f, 1.0f);
}

} // namespace shadowlab::kit
