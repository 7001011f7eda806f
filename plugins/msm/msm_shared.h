// msm's block, shared by msm.cpp, its moment file and msm.glsl (shadowlab/kit/shared.h).
#ifndef MSM_SHARED_H
#define MSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(msm)
SHADOWLAB_UNIFORM_BLOCK(MsmUniforms, 2) {
    int uQuantized;                 // 1: rgba16 storage through the optimised quantisation
    float uMomentBias;
    float uDepthBias;
    float uLightBleedingReduction;
};
SHADOWLAB_SHARED_END
#endif
