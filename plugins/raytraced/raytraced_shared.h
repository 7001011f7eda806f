// raytraced's blocks and units, shared by raytraced.cpp, raytraced_trace.comp (the screen-space
// pass) and raytraced.glsl (main pass); see shadowlab/kit/shared.h.
#ifndef RAYTRACED_SHARED_H
#define RAYTRACED_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(raytraced)
SHADOWLAB_TEXTURE_UNIT(kVisibilityUnit, 4)       // main pass: this frame's visibility image
SHADOWLAB_TEXTURE_UNIT(kPrepassPositionUnit, 5)  // the camera pre-pass: world position (w = 1 drawn)
SHADOWLAB_TEXTURE_UNIT(kPrepassNormalUnit, 6)    // the camera pre-pass: world normal
SHADOWLAB_TEXTURE_UNIT(kHistoryUnit, 7)          // temporal: the previous frame's visibility image
SHADOWLAB_IMAGE_UNIT(kVisibilityImage, 1)        // RGBA16F out: rgb visibility, a = view depth (w of clip)
SHADOWLAB_IMAGE_UNIT(kHeatImage, 2)              // RGBA8 out: cost heat map (counters on)
SHADOWLAB_UNIFORM_BLOCK(RaytracedUniforms, 2) {
    mat4 uRtPreviousViewProjection;   // FrameContext::previousViewProjection
    vec4 uRtLightPosition;            // xyz, w = type (0 directional, 1 spot, 2 point)
    vec4 uRtLightDirection;           // xyz travel direction, w = size (radius, or angular radius)
    vec4 uRtParams;                   // x ray offset, y cos(spot outer angle), z history weight, w match tolerance
    uvec4 uRtOptions;                 // x rays per pixel (1: hard), y frame seed, z 1 history valid, w 1 pass = fragment
};
SHADOWLAB_SHARED_END
// Storage binding of the counter totals (counters on): uint lo/hi pairs of rays, node visits,
// triangle tests and traced pixels (64-bit sums carried by hand).
#define RT_COUNTER_BINDING 2
#endif
