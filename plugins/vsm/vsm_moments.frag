// VSM moment pass: the first two moments of the light depth, M1 = d and M2 = d^2 (seed 000
// section 3.2.5), into an RG32F target.
in float vLightDepth;
layout(location = 0) out vec2 outMoments;

#include "vsm_shared.h"

void main() {
    float d = vLightDepth;
    float m2 = d * d;
    if (uDerivativeMoment != 0) {
        // seed 000 eq. 3.16, M2 = mu^2 + 1/4 ((df/dx)^2 + (df/dy)^2) (as printed in the seed;
        // derived again). Over one texel a planar surface's depth is d + x dd/dx + y dd/dy with x, y
        // the offsets from the texel centre. If the depth sits at the texel's edges, x, y = +-1/2
        // (the worst case, a two-point distribution per axis), the variance is
        // (dd/dx^2 + dd/dy^2) / 4: Donnelly and Lauritzen's term (uniform x, y would give 1/12, a
        // third of it). The extra variance is a slope-scaled bias: tilted receivers, whose depth
        // changes across a texel, stop shadowing themselves.
        float dx = dFdx(d);
        float dy = dFdy(d);
        m2 += 0.25 * (dx * dx + dy * dy);
    }
    outMoments = vec2(d, m2);
}
