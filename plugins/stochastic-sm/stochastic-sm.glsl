// Stochastic shadow maps, main-pass side (seed 001 sec. 2.1.2): the map is an ordinary depth map
// in which each translucent texel is a coin flip, so an ordinary PCF over it estimates
// prod (1 - a_i), the translucency model M1 (coverage; uncoloured). The n x n box of bilinear
// comparisons averages about (n + 1)^2 texels of the noise.
#include "light_space.glsl"
#include "light_depth.glsl"
#include "box_pcf.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "stochastic_sm_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, uKernel, 1.0, slope, uBilinear != 0));
}
