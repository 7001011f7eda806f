// csm's blocks, shared by csm.cpp, csm.glsl (main pass), csm_cascades.geom (the layered shadow
// pass) and shaders/view_depth_bounds.comp (the depth reduction: sdsm, range = receivers); see shadowlab/kit/shared.h.
#ifndef CSM_SHARED_H
#define CSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(csm)
SHADOWLAB_TEXTURE_UNIT(kCascadeMapsUnit, 4)      // sampler2DArrayShadow, one layer per cascade
SHADOWLAB_TEXTURE_UNIT(kPrepassDepthUnit, 5)     // the host's camera pre-pass depth (the reduction)
SHADOWLAB_UNIFORM_BLOCK(CsmUniforms, 2) {
    mat4 uCascadeMatrix[8];   // world -> clip of cascade i (kit::kMaxCascades)
    vec4 uCascadeRange[8];    // x: served view depth begin, y: end, z: fitted begin (blend band), w: texel world size
    vec4 uCsmParams;          // x: cascade count, y: blend band (fraction of a cascade), z: debug colours, w: resolution
    ivec4 uCsmOptions;        // x: PCF kernel n, y: 1 bilinear taps, z, w: 0
};
SHADOWLAB_SHARED_END
// The depth reduction's storage binding (std430): uint min view depth, uint ~max view depth (both
// reduced with atomicMin over the float bits: positive floats order as their bits do).
#define CSM_DEPTH_BOUNDS_BINDING 1
#endif
