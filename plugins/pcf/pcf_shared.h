// pcf's main-pass block, shared by pcf.cpp and pcf.glsl (see
// shadowlab/kit/shared.h).
#ifndef PCF_SHARED_H
#define PCF_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(pcf)
SHADOWLAB_UNIFORM_BLOCK(PcfUniforms, 2) {
    int uKernel;           // n: n x n taps
    float uOffsetScale;    // texels between neighbouring taps
    float uConeBias;       // 0 off, else multiplier of the receiver slope
    int uSampling;         // 0 taps, 1 gather (textureGather), 2 folded (bilinear comparisons); 1, 2: unit spacing only
    int uBilinear;         // 1: the taps are bilinear comparisons (gather and folded weight their texels so)
    int uClassify;         // 1: decide lit and shadowed pixels by the depth-range mips first (unit 7: kit/depth_range_mips_shared.h)
    int uPcfPad1;
    int uPcfPad2;
};
SHADOWLAB_SHARED_END
#endif
