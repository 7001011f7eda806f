// stochastic-sm's main-pass block, shared by stochastic-sm.cpp and stochastic-sm.glsl (see
// shadowlab/kit/shared.h).
#ifndef STOCHASTIC_SM_SHARED_H
#define STOCHASTIC_SM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(stochastic_sm)
// The multisampled map (msaa > 1), a sampler2DMS; the single-sample one is on kDepthMapUnit (4).
SHADOWLAB_TEXTURE_UNIT(kMultisampleMapUnit, 5)
SHADOWLAB_UNIFORM_BLOCK(StochasticSmUniforms, 2) {
    int uKernel;         // n: n x n taps one texel apart
    int uBilinear;       // 1: each tap is the texture unit's 2x2 bilinear comparison
    float uConeBias;     // 0 off, else multiplier of the receiver slope
    int uSamples;        // samples per texel of the multisampled map; 0: the single-sample map
};
SHADOWLAB_SHARED_END
#endif
