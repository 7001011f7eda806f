// The depth map's block (kit/depth_map.h), shared by its C++ and the GLSL of the techniques built
// on it (shadowmap, pcf, adaptive-pcf, pcss, area-reference) and by shaders/depth_only.vert.
#ifndef SHADOWLAB_KIT_DEPTH_MAP_SHARED_H
#define SHADOWLAB_KIT_DEPTH_MAP_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(depth_map)
SHADOWLAB_TEXTURE_UNIT(kDepthMapUnit, 4)
SHADOWLAB_UNIFORM_BLOCK(DepthMapUniforms, 1) {
    mat4 uShadowMatrix;       // light view-projection (world -> clip)
    vec4 uLightDepth;         // near, far, 1 perspective / 0 orthographic, resolution
    vec4 uLightWorldSize4;    // xy: map extent in world units (orthographic) or at unit distance (perspective)
    vec4 uLightAxis4;         // xyz: unit world direction along which the map measures depth
    vec4 uDepthClipPlane;     // depth pass: world plane, casters clipped where dot(plane, (p, 1)) < 0
                              // (GL_CLIP_DISTANCE0 on only when DepthMapConfig::clipPlane is set)
};
SHADOWLAB_SHARED_END

#ifndef __cplusplus
#define uLightWorldSize (uLightWorldSize4.xy)
#define uLightAxis (uLightAxis4.xyz)
#endif
#endif
