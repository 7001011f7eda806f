// The depth-range mips' units and block (kit/depth_range_mips.h), shared by its C++, its pass
// (shaders/depth_range_mips.frag) and the lookups of the techniques that read it
// (shaders/depth_range.glsl: adaptive-pcf, pcss, pcf).
#ifndef SHADOWLAB_KIT_DEPTH_RANGE_MIPS_SHARED_H
#define SHADOWLAB_KIT_DEPTH_RANGE_MIPS_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(depth_range)
SHADOWLAB_TEXTURE_UNIT(kDepthRangeSourceUnit, 4)   // the pass: the shadow map or the previous level
SHADOWLAB_TEXTURE_UNIT(kDepthRangeMipsUnit, 7)     // main pass: the mips
SHADOWLAB_UNIFORM_BLOCK(DepthRangeLevelUniforms, 3) {
    int uSourceLevel;      // level of uSource read by this draw
    int uSourceIsMap;      // 1: uSource is the depth map (one channel: min = max = depth)
    int uDepthRangePad0;
    int uDepthRangePad1;
};
SHADOWLAB_SHARED_END
#endif
