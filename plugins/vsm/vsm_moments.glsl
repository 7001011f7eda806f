// VSM's moments of a light depth, M1 = d and M2 = d^2 (seed 000 section 3.2.5), for an RG32F map.
// Built by the kit as the colour moment pass or the compute blur's first pass (moment_map_passes.glsl).
#include "vsm_shared.h"

vec4 momentsFromDepth(float d) {
    float m2 = d * d;
#ifdef MOMENT_PASS_FRAGMENT
    if (uDerivativeMoment != 0) {
        // seed 000 eq. 3.16, M2 = mu^2 + 1/4 ((df/dx)^2 + (df/dy)^2) (as printed in the seed;
        // derived again). Over one texel a planar surface's depth is d + x dd/dx + y dd/dy with x, y
        // the offsets from the texel centre. If the depth sits at the texel's edges, x, y = +-1/2
        // (the worst case, a two-point distribution per axis), the variance is
        // (dd/dx^2 + dd/dy^2) / 4: Donnelly and Lauritzen's term (uniform x, y would give 1/12, a
        // third of it). The extra variance is a slope-scaled bias: tilted receivers, whose depth
        // changes across a texel, stop shadowing themselves. It needs the rasteriser's screen-space
        // derivatives, so vsm.cpp asks the kit for the colour moment pass while it is on.
        float dx = dFdx(d);
        float dy = dFdy(d);
        m2 += 0.25 * (dx * dx + dy * dy);
    }
#endif
    return vec4(d, m2, 0.0, 0.0);
}

#include "moment_map_passes.glsl"
