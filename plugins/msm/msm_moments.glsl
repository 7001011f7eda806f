// MSM's moments of a light depth: b = (z, z^2, z^3, z^4) (Peters and Klein 2015), as 32-bit floats
// or, quantised by the paper's optimised affine transform, for 16-bit unorm storage (RGBA16). Built
// by the kit as the colour moment pass or the compute blur's first pass (moment_map_passes.glsl).
#include "hamburger4msm.glsl"

#include "msm_shared.h"

vec4 momentsFromDepth(float d) {
    vec4 b = momentsOfDepth(d);
    return uQuantized != 0 ? quantizeMoments(b) : b;
}

#include "moment_map_passes.glsl"
