// EVSM moment pass: the light depth warped by a positive and a negative exponential, each with its
// square (Lauritzen and McCool 2008): (p, p^2, n, n^2) with p = exp(c+ x), n = -exp(-c- x), into
// RGBA32F. As in Lauritzen's implementation the depth is first mapped to x = 2 d - 1 in [-1, 1]:
// for the same largest value exp(2 c) of the squares (the 32-bit limit, c <= 42) the warp is
// twice as steep as on [0, 1]. Both warps increase with d, so "behind" keeps its meaning.
in float vLightDepth;
layout(location = 0) out vec4 outMoments;

#include "evsm_shared.h"

void main() {
    float x = 2.0 * vLightDepth - 1.0;
    float p = exp(uExponents.x * x);
    float n = -exp(-uExponents.y * x);
    outMoments = vec4(p, p * p, n, n * n);
}
