// The block of kit::WarpedFaceMaps (kit/warped_faces.h): a point light's six cube faces, each a
// map of its own (warped or focused) in one atlas, shared by the C++ and the main-pass lookup
// shaders/warped_faces.glsl. Binding 13: the kit's, beside kit::LayeredDepthMap's 14; the atlas
// reads through the depth map's unit 4 and the layers' units 12-13 (no unit of its own).
#ifndef SHADOWLAB_KIT_WARPED_FACES_SHARED_H
#define SHADOWLAB_KIT_WARPED_FACES_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(warped_faces)
SHADOWLAB_UNIFORM_BLOCK(WarpedFacesUniforms, 13) {
    mat4 uFaceMatrix[6];       // world -> clip of each face's map, GL's face order (+x, -x, +y, -y, +z, -z)
    vec4 uFaceLinearPlane[6];  // each face's linear depth plane (when the layered block's uLinearDepth is 1)
    vec4 uFaceTile[6];         // xy: the face's tile origin in atlas coordinates, zw: its size there
    vec4 uFaceLight;           // xyz: the light's position; w: half a texel, in a tile's [0, 1]
    ivec4 uFaceInfo;           // x: 1 when the faces are the map (a point light); y: bit i set when face i was drawn
};
SHADOWLAB_SHARED_END
#endif
