// Stochastic shadow maps, main-pass side (seed 001 sec. 2.1.2): the map is an ordinary depth map
// in which each translucent texel is a coin flip, so an ordinary PCF over it estimates
// prod (1 - a_i), the translucency model M1 (coverage; uncoloured). The n x n box of bilinear
// comparisons averages about (n + 1)^2 texels of the noise.
// A multisampled map (msaa > 1) holds one coin flip per sample (Enderton et al. 2010; seed 001
// sec. 2.1.2: "if multisampling is leveraged much better results can be achieved"). Multisample
// textures have no comparison sampling, so every sample of the n x n nearest texels is fetched and
// compared here: samples x n^2 coin flips averaged, so the noise falls with the sample count at
// the same kernel (and the same blur).
#include "light_space.glsl"
#include "light_depth.glsl"
#include "box_pcf.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "stochastic_sm_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;
layout(binding = kMultisampleMapUnit) uniform sampler2DMS uShadowMapMs;

// Mean of [z_tap <= stored] over every sample of the n x n nearest texels, with the same taps and
// cone bias as boxPcfDepth's nearest taps (box_pcf.glsl). Taps past the edge clamp to it.
float boxPcfSamples(vec3 coord, float resolution, int kernel, float slope, int samples) {
    ivec2 size = textureSize(uShadowMapMs);
    vec2 u = coord.xy * resolution;
    float lit = 0.0;
    for (int j = 0; j < kernel; ++j)
        for (int i = 0; i < kernel; ++i) {
            vec2 offset = boxPcfOffset(i, j, kernel);
            ivec2 texel = clamp(ivec2(floor(u + offset)), ivec2(0), size - 1);
            float z = coord.z - slope * length(offset);
            for (int s = 0; s < samples; ++s) lit += z <= texelFetch(uShadowMapMs, texel, s).r ? 1.0 : 0.0;
        }
    return lit / float(kernel * kernel * samples);
}

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    if (uSamples > 0) return vec3(boxPcfSamples(coord, uLightDepth.w, uKernel, slope, uSamples));
    return vec3(boxPcfDepth(uShadowMap, coord, uLightDepth.w, uKernel, 1.0, slope, uBilinear != 0));
}
