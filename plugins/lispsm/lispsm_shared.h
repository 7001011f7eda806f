// lispsm's block and units for its biasing methods (seed 002 ch. 5), shared by lispsm.cpp, its
// depth pass (lispsm_depth.vert/.frag) and its main-pass GLSL (see shadowlab/kit/shared.h).
#ifndef LISPSM_SHARED_H
#define LISPSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(lispsm)
SHADOWLAB_TEXTURE_UNIT(kFirstDepthUnit, 5)    // the nearest layer, raw depths (two-layer methods)
SHADOWLAB_TEXTURE_UNIT(kSecondDepthUnit, 6)   // the second layer
SHADOWLAB_UNIFORM_BLOCK(LispsmUniforms, 2) {
    vec4 uLinearDepthPlane;   // world plane: linear depth 0..1 along the light over B (sec. 5.3, TSM's linear z)
    int uLinearDepth;         // 1: the map stores linear depth, else the warp's hyperbolic z
    int uBiasMethod;          // 0 polygon offset (incl. inverted back faces), 1 midpoint (eq. 5.1), 2 second depth
    int uPeel;                // depth pass: 1 keeps only fragments behind the first layer (the second layer)
    float uZOffset;           // eq. 5.1's z_offset, in map depth units [0, 1]
    float uSlopeFactor;       // the slope-scaled bias done in the fragment stage (eq. 5.2), both depths
    float uConstantUnits;     //   and its constant part, in units of 2^-24
    float uLispsmPad0;
    float uLispsmPad1;
};
SHADOWLAB_SHARED_END
#endif
