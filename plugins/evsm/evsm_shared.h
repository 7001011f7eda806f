// evsm's block, shared by evsm.cpp, its moment file and evsm.glsl (shadowlab/kit/shared.h).
#ifndef EVSM_SHARED_H
#define EVSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(evsm)
SHADOWLAB_UNIFORM_BLOCK(EvsmUniforms, 2) {
    vec4 uExponents;                // xy: c+, c-
    float uMinVariance;             // in depth^2, before warping
    float uLightBleedingReduction;
    float uEvsmPad0;
    float uEvsmPad1;
};
SHADOWLAB_SHARED_END
#endif
