// rbsm's main-pass block, shared by rbsm.cpp and rbsm.glsl (see shadowlab/kit/shared.h).
#ifndef RBSM_SHARED_H
#define RBSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(rbsm)
// The raw depths (texelFetch) on the kit's depth-map unit: the neighbour tests compare the
// receiver's own depth against each neighbouring texel.
SHADOWLAB_UNIFORM_BLOCK(RbsmUniforms, 2) {
    int uRbsmConservative;   // 1: the boundary may only move into lit texels (the shadow never shrinks)
    int uRbsmMaxSearch;      // texels walked along an edge on either side before it counts as straight
    int uRbsmFiltered;       // 1: coverage of the revectorized boundary over the pixel's footprint
    int uRbsmPad;
};
SHADOWLAB_SHARED_END
#endif
