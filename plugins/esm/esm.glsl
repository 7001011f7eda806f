// Exponential shadow maps, main-pass side (Annen et al. 2008). For a receiver at depth d_r behind
// all occluders of the filter window (d_r >= z), the shadow test is the limit of
// exp(-c (d_r - z)) for large c, and by linearity of the filter
//   visibility = E[exp(-c (d_r - z))] = exp(-c d_r) E[exp(c z)],
// clamped to [0, 1]: where the receiver is in front of some stored depth (z > d_r: lit samples,
// the receiver's own surface), the terms exceed 1 and the clamp saturates to lit. With the stored
// exp(c (z - 1)) this reads exp(c (1 - d_r)) E[exp(c (z - 1))].
#include "moment_shadows.glsl"

#include "esm_shared.h"

vec3 shadowTerm(ShadowInput s) {
    MomentSample m = sampleMoments(s.worldPos);
    // Both factors stay finite in 32-bit floats for c <= 85: exp(85) < 3.4e38, and every stored value,
    // hence their average E, is at least exp(-85), a normal float.
    float visibility = exp(uExponent * (1.0 - m.depth)) * m.moments.r;
    return vec3(m.inside ? clamp(visibility, 0.0, 1.0) : 1.0);
}
