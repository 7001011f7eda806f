// Moment shadow mapping, main-pass side: undo the quantisation (an affine map, so it commutes with
// the filtering already done), reconstruct with Hamburger 4MSM, reduce light bleeding.
#include "moment_shadows.glsl"
#include "hamburger4msm.glsl"

#include "msm_shared.h"

vec3 shadowTerm(ShadowInput s) {
    MomentSample m = sampleMoments(s.worldPos);
    vec4 b = uQuantized != 0 ? dequantizeMoments(m.moments) : m.moments;
    float visibility = 1.0 - hamburger4MsmShadowIntensity(b, m.depth, uDepthBias, uMomentBias);
    visibility = reduceLightBleeding(visibility, uLightBleedingReduction);
    return vec3(m.inside ? visibility : 1.0);
}
