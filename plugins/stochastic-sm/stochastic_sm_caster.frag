// stochastic-sm's light pass for translucent casters (Enderton et al. 2010 via seed 001 sec.
// 2.1.2): the fragment is kept, an opaque depth, with probability alpha and discarded otherwise,
// so a texel behind surfaces of alpha a_1..a_k stays lit with probability prod (1 - a_i).
// Built with STOCHASTIC_SM_MSAA for a multisampled map (the `msaa` parameter): the coin is flipped
// per covered sample instead, through gl_SampleMask, as stochastic transparency does (Enderton et
// al. 2010; seed 001 sec. 2.1.2, "Stochastic transparency": each sample still depth-tests as
// usual): each sample of a texel then holds its own coin flip, and the lookup averages
// samples x n x n of them.
#include "common.glsl"
#include "shadowlab/kit/stochastic_shared.h"

in vec2 vUv;
flat in uint vObject;

void main() {
    float alpha = surfaceTransmission(vUv).a;
#ifdef STOCHASTIC_SM_MSAA
    // One xi per sample, the sample index folded into the hash; the mask is ANDed with the
    // triangle's coverage, so uncovered samples stay untouched. gl_SampleID is not read, so the
    // shader still runs once per texel.
    int mask = 0;
    for (int s = 0; s < gl_NumSamples; ++s)
        if (fragmentSampleXi(vObject, 0u, s) < alpha) mask |= 1 << s;
    if (mask == 0) discard;
    gl_SampleMask[0] = mask;
#else
    if (fragmentXi(vObject, 0u) >= alpha) discard;
#endif
}
