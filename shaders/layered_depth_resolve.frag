// kit::LayeredDepthMap::resolve() (seed 002 ch. 5): the two layers of a texel into the one depth
// a comparison tests against, so the filtering techniques' kernels, gathers, depth-range mips and
// blocker searches read the biased surface as a plain depth map. The same tests as
// layered_depth.glsl's layeredShadowMap(), moved from the lookup to the map.
#include "shadowlab/kit/layered_depth_shared.h"

layout(binding = kFirstDepthUnit) uniform sampler2D uFirstLayer;
layout(binding = kSecondDepthUnit) uniform sampler2D uSecondLayer;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float first = texelFetch(uFirstLayer, texel, 0).r, second = texelFetch(uSecondLayer, texel, 0).r;
    // Eq. 5.1 (midpoint): halfway to the second surface, at most z_offset past the first. Second
    // depth (Wang and Molnar): the second surface itself. A texel with no second surface keeps the
    // cleared 1.0 there, so the midpoint goes halfway to the far plane, as the per-lookup test does.
    gl_FragDepth = uBiasMethod == 1 ? first + min(0.5 * (second - first), uZOffset) : second;
}
