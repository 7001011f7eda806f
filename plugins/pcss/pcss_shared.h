// pcss's blocks and units, shared by pcss.cpp and pcss.glsl.
#ifndef PCSS_SHARED_H
#define PCSS_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(pcss)
SHADOWLAB_TEXTURE_UNIT(kSearchOffsetsUnit, 5)
SHADOWLAB_TEXTURE_UNIT(kFilterOffsetsUnit, 6)
// unit 7: the kit's depth-range mips (kit/depth_range_mips_shared.h)
SHADOWLAB_TEXTURE_UNIT(kCompareUnit, 8)        // the shadow map again, with the bilinear comparison sampler
// Point lights (the kit's cube at unit 15 compares): the cube's raw distances for the blocker
// search, and its min-depth mips, per face, as a 2D array of six layers.
SHADOWLAB_TEXTURE_UNIT(kCubeRawUnit, 9)
SHADOWLAB_TEXTURE_UNIT(kCubeMinDepthUnit, 10)
SHADOWLAB_TEXTURE_UNIT(kCubeMinDepthSourceUnit, 9)   // building level 0: the cube (levels 1+: kMinDepthSourceUnit)
SHADOWLAB_TEXTURE_UNIT(kMinDepthSourceUnit, 4)       // building the cube's min-depth levels 1+: the array itself
SHADOWLAB_UNIFORM_BLOCK(PcssUniforms, 2) {
    int uSearchGrid;       // n_s: n_s x n_s blocker-search samples
    int uFilterGrid;       // n_f: n_f x n_f filter samples
    float uConeBias;       // 0 off, else multiplier of the receiver slope
    float uLightSize;      // perspective: world radius; orthographic: tan(angular radius)
    int uBilinear;         // filter taps: 1 bilinear comparison, 0 nearest
    int uSearchBound;      // 0: near plane (eq. 3.18 as printed), 1: min-depth mips, 2: and fully blocked regions stop
    int uPcssPad0;
    int uPcssPad1;
};
// The cube's min-depth pass (pcss_cube_min_depth.frag), one draw per level and face: a pass-local
// block at binding 3, as the kit's depth-range level pass (kit/depth_range_mips_shared.h).
SHADOWLAB_UNIFORM_BLOCK(PcssCubeMinDepthUniforms, 3) {
    int uCubeSourceLevel;  // -1: the cube; else this level of uArraySource
    int uCubeLayer;        // the face written and read
    int uCubeFaceSize;     // the cube's face width in texels
    int uCubeMinDepthPad;
};
SHADOWLAB_SHARED_END
#endif
