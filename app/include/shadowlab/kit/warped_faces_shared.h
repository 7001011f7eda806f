// The block of kit::WarpedFaceMaps (kit/warped_faces.h): a point light's six cube faces, each a
// map of its own (warped or focused) in one atlas, shared by the C++ and the main-pass lookup
// shaders/warped_faces.glsl, and each face's depth-pass block (shaders/warped_face_depth.vert).
// Bindings 12-13: the kit's, beside kit::LayeredDepthMap's 14; the atlas reads through the depth
// map's unit 4 and the layers' units 12-13 (no unit of its own).
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
// A face's depth pass: casters clipped to w > 0 of the warp and of the face's own perspective.
// A projective warp's w is the product of the face's w and the distance t from the warp's centre,
// so w > 0 alone also keeps the points behind both the light and the centre: their mirror images.
// Depth clamp turns off the near-plane clipping that would drop them otherwise.
SHADOWLAB_UNIFORM_BLOCK(WarpedFacePassUniforms, 12) {
    vec4 uFaceClipPlanes[2];   // world planes: 0 the map matrix's w row, 1 the face perspective's
};
SHADOWLAB_SHARED_END
#endif
