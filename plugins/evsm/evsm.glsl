// Exponential variance shadow maps, main-pass side (Lauritzen and McCool 2008): the Chebyshev
// bound of seed 000 eq. 3.13-3.15 applied to each warped depth, then the smaller of the two
// bounds (each is an upper bound of the same lit fraction, so the minimum is the tighter one),
// then the light-bleeding reduction.
#include "moment_shadows.glsl"

#include "evsm_shared.h"

vec3 shadowTerm(ShadowInput s) {
    MomentSample m = sampleMoments(s.worldPos);
    float x = 2.0 * m.depth - 1.0;   // as in evsm_moments.glsl
    float p = exp(uExponents.x * x);
    float n = -exp(-uExponents.y * x);
    // The minimum variance is given for the depth d; a warp w scales small deviations by dw/dd, so
    // the variance by (dw/dd)^2 (first-order error propagation): dw/dd = 2 c+ p and 2 c- |n|.
    // Squared last: (dw/dd)^2 alone overflows 32-bit floats near c+ = 40.
    vec2 minDeviation = sqrt(uMinVariance) * 2.0 * uExponents.xy * vec2(p, -n);
    vec2 minVariance = minDeviation * minDeviation;
    float positive = chebyshevUpperBound(m.moments.xy, p, minVariance.x);
    float negative = chebyshevUpperBound(m.moments.zw, n, minVariance.y);
    float visibility = reduceLightBleeding(min(positive, negative), uLightBleedingReduction);
    return vec3(m.inside ? visibility : 1.0);
}
