// The block and units of kit::LayeredDepthMap (kit/layered_depth.h): the depth pass that writes
// its own depth (linear depth, the bias in the fragment stage, depth peeling for a second layer;
// seed 002 ch. 5), shared by the C++, shaders/layered_depth.vert/.frag and the main-pass test
// shaders/layered_depth.glsl. Binding 14 and units 12-13: the kit's, clear of every technique's.
#ifndef SHADOWLAB_KIT_LAYERED_DEPTH_SHARED_H
#define SHADOWLAB_KIT_LAYERED_DEPTH_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(layered_depth)
SHADOWLAB_TEXTURE_UNIT(kFirstDepthUnit, 12)    // the nearest layer, raw depths (two-layer methods)
SHADOWLAB_TEXTURE_UNIT(kSecondDepthUnit, 13)   // the second layer
SHADOWLAB_UNIFORM_BLOCK(LayeredDepthUniforms, 14) {
    vec4 uLinearDepthPlane;   // world plane: linear depth 0..1 along the light over B (sec. 5.3, TSM's linear z)
    int uLinearDepth;         // 1: the map stores linear depth, else the light matrix's own z
    int uBiasMethod;          // 0 offset (incl. inverted back faces), 1 midpoint (eq. 5.1), 2 second depth
    int uPeel;                // depth pass: 1 keeps only fragments behind the first layer (the second layer)
    float uZOffset;           // eq. 5.1's z_offset, in map depth units [0, 1]
    float uSlopeFactor;       // the slope-scaled bias done in the fragment stage (eq. 5.2), both depths
    float uConstantUnits;     //   and its constant part, in units of 2^-24
    float uPeelTolerance;     // peeling: a stored depth's rounding (one unit of a 16- or 24-bit format, 0 for 32F)
    float uLayeredPad1;
};
SHADOWLAB_SHARED_END
#endif
