// esm's block, shared by esm.cpp, its moment file and esm.glsl (shadowlab/kit/shared.h).
#ifndef ESM_SHARED_H
#define ESM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(esm)
SHADOWLAB_UNIFORM_BLOCK(EsmUniforms, 2) {
    float uExponent;                // c
    float uEsmPad0;
    float uEsmPad1;
    float uEsmPad2;
};
SHADOWLAB_SHARED_END
#endif
