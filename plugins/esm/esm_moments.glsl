// ESM's moment of a light depth: one exponential moment (Annen et al. 2008), stored as
// exp(c (d - 1)) = exp(c d) exp(-c). The constant factor exp(-c) cancels in the test (esm.glsl)
// and keeps the stored values in (0, 1]: no overflow for c up to 85 in 32-bit floats, and a
// readable debug image. Built by the kit as the colour moment pass or the compute blur's first
// pass (moment_map_passes.glsl).
#include "esm_shared.h"

vec4 momentsFromDepth(float d) {
    return vec4(exp(uExponent * (d - 1.0)), 0.0, 0.0, 0.0);
}

#include "moment_map_passes.glsl"
