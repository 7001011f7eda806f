// raytraced, main-pass side: the visibility the screen-space pass traced for this pixel
// (raytraced_trace.comp), where this fragment is the surface the camera pre-pass saw there (the
// opaque surfaces: the same rasterisation, so the same point to float rounding). Any other
// fragment, a translucent receiver in front, is traced here and now with the same rays (seed 001's
// translucent receivers; only the translucent surfaces pay for it); a fragment behind the surface
// the pre-pass saw is hidden later and traces nothing. pass = fragment: every
// fragment traces here (no compute pass, no pre-pass).
#include "raytraced_shared.h"
#include "ray_trace.glsl"
#include "raytraced_rays.glsl"

layout(binding = kVisibilityUnit) uniform sampler2D uRtVisibility;
layout(binding = kPrepassPositionUnit) uniform sampler2D uRtPrepassPosition;

vec3 shadowTerm(ShadowInput s) {
    ivec2 texel = ivec2(s.fragCoord);
    ivec2 size = textureSize(uRtPrepassPosition, 0);
    vec4 seen = texelFetch(uRtPrepassPosition, texel, 0);
    if (uRtOptions.w == 0u && seen.w > 0.5) {
        if (distance(seen.xyz, s.worldPos) <= uRtParams.w) return texelFetch(uRtVisibility, texel, 0).rgb;
        // Behind the nearest opaque surface the pre-pass saw here: a fragment drawn before its
        // occluder, which the depth test discards later. Without this, every overdrawn fragment
        // traced all its rays (the H200 run of 2026-12-04 saw the main pass grow with the soft
        // rays: 4.05, 12.8, 47.8 ms at 4, 16, 64 rays on contact).
        if (distance(uCameraPosition.xyz, s.worldPos) > distance(uCameraPosition.xyz, seen.xyz) + uRtParams.w)
            return vec3(1.0);
    }
    uint rays;
    return traceRays(s.worldPos, s.worldNormal, uint(texel.y * size.x + texel.x), rays);
}
