// The host's per-frame uniform block, binding 0: declared once for the host's C++ and every
// program's GLSL (shaders/common.glsl includes it).
#ifndef SHADOWLAB_FRAME_BLOCK_H
#define SHADOWLAB_FRAME_BLOCK_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(frame)
SHADOWLAB_UNIFORM_BLOCK(Frame, 0) {
    mat4 uView;
    mat4 uProjection;
    mat4 uViewProjection;
    vec4 uCameraPosition;       // xyz
    vec4 uLightPosition;        // xyz, w = type (0 directional, 1 spot, 2 point)
    vec4 uLightDirection;       // xyz travel direction, w = size (radius or angular radius)
    vec4 uLightColor;           // rgb
    vec4 uLightSpot;            // cos(outer), cos(inner)
    vec4 uAmbient;              // rgb
    vec4 uViewport;             // width, height, 1/width, 1/height
};
SHADOWLAB_SHARED_END
#endif
