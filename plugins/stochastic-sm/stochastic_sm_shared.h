// stochastic-sm's main-pass block, shared by stochastic-sm.cpp and stochastic-sm.glsl (see
// shadowlab/kit/shared.h).
#ifndef STOCHASTIC_SM_SHARED_H
#define STOCHASTIC_SM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(stochastic_sm)
SHADOWLAB_UNIFORM_BLOCK(StochasticSmUniforms, 2) {
    int uKernel;         // n: n x n taps one texel apart
    int uBilinear;       // 1: each tap is the texture unit's 2x2 bilinear comparison
    float uConeBias;     // 0 off, else multiplier of the receiver slope
    float uStochasticSmPad;
};
SHADOWLAB_SHARED_END
#endif
