// adaptive-pcf's main-pass block and units, shared by adaptive-pcf.cpp and adaptive-pcf.glsl.
#ifndef ADAPTIVE_PCF_SHARED_H
#define ADAPTIVE_PCF_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(adaptive_pcf)
SHADOWLAB_TEXTURE_UNIT(kDiscOffsetsUnit, 5)
SHADOWLAB_TEXTURE_UNIT(kCounterBinding, 4)    // atomic counter buffer binding (the host uses none)
SHADOWLAB_UNIFORM_BLOCK(AdaptivePcfUniforms, 2) {
    int uGrid;             // n: n x n samples per set
    float uRadius;         // filter radius in texels
    float uConeBias;       // 0 off, else multiplier of the receiver slope
    int uCoherent;         // 1: early-out decision per 2x2 quad
    int uCountEarlyOuts;   // 1: count calls and early outs (atomic counters)
    int uClassify;         // 0 ring, 1 depth-range bounds first (unit 7: kit/depth_range_mips_shared.h)
    int uAdaptivePad1;
    int uAdaptivePad2;
};
SHADOWLAB_SHARED_END
#endif
