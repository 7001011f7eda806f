// stochastic-sm's light pass for translucent casters (Enderton et al. 2010 via seed 001 sec.
// 2.1.2): the fragment is kept, an opaque depth, with probability alpha and discarded otherwise,
// so a texel behind surfaces of alpha a_1..a_k stays lit with probability prod (1 - a_i).
#include "common.glsl"
#include "shadowlab/kit/stochastic_shared.h"

in vec2 vUv;
flat in uint vObject;

void main() {
    float alpha = surfaceTransmission(vUv).a;
    if (fragmentXi(vObject, 0u) >= alpha) discard;
}
