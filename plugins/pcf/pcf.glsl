// Percentage-closer filtering, main-pass side (seed 000 sec. 3.2.4): average the binary shadow
// test s(t, z) = H(d(t) - z) over an n x n box of texel-aligned offsets around the shaded
// point's map position, keeping its depth z (optionally minus the cone bias). With GL_LINEAR
// each tap is itself the texture unit's 2x2 bilinear comparison (Fig. 3.11c).
#include "light_space.glsl"
#include "disc_sampling.glsl"

#include "shadowlab/kit/depth_map_shared.h"
#include "pcf_shared.h"

layout(binding = kDepthMapUnit) uniform sampler2DShadow uShadowMap;

float discTap(vec2 uv, float ref) { return texture(uShadowMap, vec3(uv, ref)); }

vec3 shadowTerm(ShadowInput s) {
    vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
    if (!insideShadowMap(coord)) return vec3(1.0);
    float texel = 1.0 / uLightDepth.w;
    // Cone bias (sec. 3.2.4, last paragraph): a tap r texels from the centre may see the
    // receiver's own surface up to slope * r closer to the light; accept that much.
    float slope = uConeBias * receiverDepthSlope(s.worldNormal, uLightAxis, coord.z, uLightDepth, uLightWorldSize);
    float centre = 0.5 * float(uKernel - 1);
    float lit = 0.0;
    for (int j = 0; j < uKernel; ++j)
        for (int i = 0; i < uKernel; ++i) {
            vec2 offset = (vec2(i, j) - centre) * uOffsetScale;   // texels, multiples of 1/s
            lit += discTap(coord.xy + offset * texel, coord.z - slope * length(offset));
        }
    return vec3(lit / float(uKernel * uKernel));
}
