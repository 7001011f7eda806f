// EVSM's moments of a light depth: the depth warped by a positive and a negative exponential, each
// with its square (Lauritzen and McCool 2008): (p, p^2, n, n^2) with p = exp(c+ x), n = -exp(-c- x),
// for an RGBA32F map. As in Lauritzen's implementation the depth is first mapped to x = 2 d - 1 in
// [-1, 1]: for the same largest value exp(2 c) of the squares (the 32-bit limit, c <= 42) the warp
// is twice as steep as on [0, 1]. Both warps increase with d, so "behind" keeps its meaning. Built
// by the kit as the colour moment pass or the compute blur's first pass (moment_map_passes.glsl).
#include "evsm_shared.h"

vec4 momentsFromDepth(float d) {
    float x = 2.0 * d - 1.0;
    float p = exp(uExponents.x * x);
    float n = -exp(-uExponents.y * x);
    return vec4(p, p * p, n, n * n);
}

#include "moment_map_passes.glsl"
