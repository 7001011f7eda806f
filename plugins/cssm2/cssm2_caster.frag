// cssm2's light pass (McGuire and Enderton 2011 via seed 001 sec. 2.1.3 and 4.2.2), both halves in
// one render pass as seed 001 does (it drops the published copy of the depth into the colour map).
//   OPAQUE_CASTER: depth test LESS with writes, no blending; every channel holds the caster's depth.
//   otherwise (translucent casters): depth-tested against the opaque depth without writing, blend
//     MIN; channel c writes max(depth, [xi_c >= p_c]) with p = alpha (1 - t): its depth where the
//     photon of channel c stops here (probability p_c), 1 (no effect under MIN) where it passes.
// After both, channel c of a texel is the depth where its photon stopped, so a receiver at depth z
// is lit in c with probability [z <= C_c] -> prod_i (1 - p_i,c) = prod_i ((1 - a_i) + a_i t_i,c),
// the physical model M2. (Seed 001 writes the condition as xi > p; with xi uniform in [0, 1) the
// >= of kit/stochastic_shared.h stops a photon with probability p exactly.)
// The depth written to the colour map carries the bias glPolygonOffset would add (factor times the
// depth slope plus units of 2^-24): a colour attachment gets no polygon offset.
#include "common.glsl"
#include "shadowlab/kit/stochastic_shared.h"

in vec2 vUv;
#ifndef OPAQUE_CASTER
flat in uint vObject;
#endif

layout(location = 0) out vec4 outDepths;

float biasedDepth() {
    float z = gl_FragCoord.z;
    float slope = max(abs(dFdx(z)), abs(dFdy(z)));
    return min(z + uSlopeBias * slope + uConstantBias * (1.0 / 16777216.0), 1.0);
}

void main() {
    float depth = biasedDepth();
#ifdef OPAQUE_CASTER
    outDepths = vec4(depth);
#else
    vec4 surface = surfaceTransmission(vUv);
    vec3 stopProbability = surface.a * (1.0 - surface.rgb);   // p = alpha (1 - t)
    vec3 xi = vec3(fragmentXi(vObject, 0u), fragmentXi(vObject, 1u), fragmentXi(vObject, 2u));
    outDepths = vec4(max(vec3(depth), vec3(greaterThanEqual(xi, stopProbability))), 1.0);
#endif
}
