// Shared by the filterable shadow maps (vsm, esm, evsm, msm): where a point falls in the moment
// map (or, for point lights, the moment cube) and at which depth, and the Chebyshev bound with its
// light-bleeding reduction.
//
// Depth convention: every moment map stores a depth that is LINEAR in world space along the light's
// viewing axis, mapped to [0, 1] over the depth range of the shadow casters and some room behind
// them (d = dot(uLightDepthPlane, vec4(p, 1)), see shadowlab/kit/moment_light_space.h). Linear depth
// keeps the statistics of a filter window meaningful for perspective (spot) lights too, and fitting
// the casters, not the whole scene, spends the precision of the moments (and the exponent range of
// ESM/EVSM) where occluders are. Receivers outside that range are clamped: no occluder lies in
// front of depth 0 or behind depth 1, so the clamped test gives the same answer.
#ifndef SHADOWLAB_MOMENT_SHADOWS_GLSL
#define SHADOWLAB_MOMENT_SHADOWS_GLSL

#include "light_space.glsl"

#include "shadowlab/kit/moment_map_shared.h"   // uShadowMatrix, uLightDepthPlane, kMomentMapUnit

float linearLightDepth(vec3 worldPos) {
    return clamp(dot(uLightDepthPlane, vec4(worldPos, 1.0)), 0.0, 1.0);
}

#ifndef MOMENT_DEPTH_PASS
#include "shadowlab/kit/cube_depth_map_shared.h"   // point lights: uCubeLight (position, far)

layout(binding = kMomentMapUnit) uniform sampler2D uMomentMap;
layout(binding = kCubeMomentMapUnit) uniform samplerCube uMomentCube;   // point lights (kit/cube_moment_map.h)

struct MomentSample {
    vec4 moments;   // filtered moments (mipmapped and bilinear where enabled)
    float depth;    // receiver depth, same convention as the stored one
    bool inside;    // false outside the map: nothing there was rendered that could occlude
};

// Samples unconditionally (the lookup needs screen-space derivatives for mipmapping, so it must not
// sit behind a non-uniform branch); callers choose the result with `inside`.
// Point lights: the moment cube by the direction from the light, the receiver's distance / far
// as its depth (the cube stores that, linear in every direction); every direction is inside.
MomentSample sampleMoments(vec3 worldPos) {
    MomentSample m;
    if (lightType() == LIGHT_POINT) {   // a uniform: the lookup stays in uniform control flow
        vec3 toPoint = worldPos - uCubeLight.xyz;
        m.moments = texture(uMomentCube, toPoint);
        m.depth = clamp(length(toPoint) / uCubeLight.w, 0.0, 1.0);
        m.inside = true;
        return m;
    }
    vec3 coord = shadowMapCoord(uShadowMatrix, worldPos);
    m.moments = texture(uMomentMap, coord.xy);
    m.depth = linearLightDepth(worldPos);
    m.inside = all(greaterThanEqual(coord.xy, vec2(0.0))) && all(lessThanEqual(coord.xy, vec2(1.0)));
    return m;
}

// One-tailed Chebyshev inequality, seed 000 eq. 3.13-3.15:
//   mu = E[x] = M1 (3.13), sigma^2 = E[x^2] - E[x]^2 = M2 - M1^2 (3.14),
//   P(x >= t) <= p_max(t) = sigma^2 / (sigma^2 + (t - mu)^2) (3.15), valid for t > mu.
// For t <= mu the bound says nothing (p_max would be 1 anyway): the point is lit. The variance is
// clamped from below (seed 000 suggests 0.00002) against cancellation in M2 - M1^2 and acne.
float chebyshevUpperBound(vec2 moments, float t, float minVariance) {
    float mu = moments.x;
    float variance = max(moments.y - mu * mu, minVariance);
    float d = t - mu;
    float pMax = variance / (variance + d * d);
    return t <= mu ? 1.0 : pMax;
}

// Light-bleeding reduction (seed 000 section 3.2.5; Lauritzen, GPU Gems 3 ch. 8): the visibility
// range [amount, 1] is stretched to [0, 1] and everything below `amount` becomes fully shadowed.
// The spurious light of overlapping occluders is usually a small p_max, so it vanishes; the price
// is penumbrae that shrink and darken. amount = 0 leaves p unchanged.
float reduceLightBleeding(float p, float amount) {
    return clamp((p - amount) / max(1.0 - amount, 1e-6), 0.0, 1.0);
}
#endif

#endif
