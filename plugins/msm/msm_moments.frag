// MSM moment pass: b = (z, z^2, z^3, z^4) of the light depth, as 32-bit floats or, quantised by the
// paper's optimised affine transform, as 16-bit unorm (RGBA16).
#include "hamburger4msm.glsl"

in float vLightDepth;
layout(location = 0) out vec4 outMoments;

#include "msm_shared.h"

void main() {
    vec4 b = momentsOfDepth(vLightDepth);
    outMoments = uQuantized != 0 ? quantizeMoments(b) : b;
}
