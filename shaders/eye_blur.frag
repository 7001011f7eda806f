// One direction of the host's eye-space depth-dependent blur of the shadow term (seed 002 sec. 6.3,
// 9.4.2; the kernel and its width law in host_shared/eye_blur_shared.h). Run along x, then along y.
// The source holds rgb = the technique's shadow term of the opaque surface in each pixel and
// a = its view depth (0: no surface); the output keeps the centre's depth.
#include "host_shared/eye_blur_shared.h"

in vec2 vUv;
layout(location = 0) out vec4 outTerm;

layout(binding = kEyeBlurTermUnit) uniform sampler2D uTerm;
layout(location = 0) uniform ivec2 uDirection;        // (1, 0) or (0, 1)
layout(location = 1) uniform float uWidth;            // W: pixels at the reference depth
layout(location = 2) uniform float uReferenceDepth;   // z_b

void main() {
    ivec2 centre = ivec2(gl_FragCoord.xy);
    vec4 c = texelFetch(uTerm, centre, 0);
    float w = eyeBlurWidth(uWidth, uReferenceDepth, c.a);
    if (c.a <= 0.0 || w <= 1.0) {   // background, or a kernel no wider than the pixel: unchanged
        outTerm = c;
        return;
    }
    ivec2 size = textureSize(uTerm, 0);
    vec3 sum = vec3(0.0);
    float weightSum = 0.0;
    for (int k = -SHADOWLAB_EYE_BLUR_MAX_RADIUS; k <= SHADOWLAB_EYE_BLUR_MAX_RADIUS; ++k) {
        float weight = eyeBlurTapWeight(w, k);
        ivec2 p = centre + k * uDirection;
        if (weight <= 0.0 || any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) continue;
        vec4 tap = texelFetch(uTerm, p, 0);
        if (tap.a <= 0.0 || abs(tap.a - c.a) > kEyeBlurDepthTolerance * c.a) continue;   // another surface
        sum += weight * tap.rgb;
        weightSum += weight;
    }
    outTerm = vec4(sum / weightSum, c.a);
}
