// Coloured stochastic shadow maps, main-pass side (seed 001 sec. 2.1.3): each channel of the colour
// map is a depth map of its own photons, so lit_c = [z <= C_c], filtered by an n x n box of texel
// fetches compared in the shader (no hardware comparison exists for a colour map, sec. 2.1.3 and
// Fig. 5.3.D). Its expectation is prod ((1 - a) + a t) per channel: the physical model M2.
#include "light_space.glsl"
#include "light_depth.glsl"
#include "box_pcf.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "cssm2_shared.h"

layout(binding = kColourMapUnit) uniform sampler2D uColourShadowMap;

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    return boxPcfChannels(uColourShadowMap, coord, uKernel, slope);
}
