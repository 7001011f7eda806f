// ESM moment pass: one exponential moment of the light depth (Annen et al. 2008), stored as
// exp(c (d - 1)) = exp(c d) exp(-c). The constant factor exp(-c) cancels in the test (esm.glsl)
// and keeps the stored values in (0, 1]: no overflow for c up to 85 in 32-bit floats, and a
// readable debug image.
in float vLightDepth;
layout(location = 0) out float outMoment;

#include "esm_shared.h"

void main() {
    outMoment = exp(uExponent * (vLightDepth - 1.0));
}
