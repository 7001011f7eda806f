// cssm2's main-pass block and units, shared by cssm2.cpp and cssm2.glsl (see shadowlab/kit/shared.h).
#ifndef CSSM2_SHARED_H
#define CSSM2_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(cssm2)
SHADOWLAB_TEXTURE_UNIT(kColourMapUnit, 5)
SHADOWLAB_UNIFORM_BLOCK(Cssm2Uniforms, 2) {
    int uKernel;        // n: n x n taps one texel apart
    float uConeBias;    // 0 off, else multiplier of the receiver slope
    float uCssm2Pad0;
    float uCssm2Pad1;
};
SHADOWLAB_SHARED_END
#endif
