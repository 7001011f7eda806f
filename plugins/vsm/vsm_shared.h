// vsm's block, shared by vsm.cpp, its moment file and vsm.glsl (shadowlab/kit/shared.h).
#ifndef VSM_SHARED_H
#define VSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(vsm)
SHADOWLAB_UNIFORM_BLOCK(VsmUniforms, 2) {
    int uDerivativeMoment;          // 1: eq. 3.16 (moment pass)
    float uMinVariance;             // in depth^2
    float uLightBleedingReduction;
    float uVsmPad;
};
SHADOWLAB_SHARED_END
#endif
