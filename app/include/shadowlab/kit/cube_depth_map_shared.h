// The kit's cube depth map (kit/cube_depth_map.h): its block and unit, shared by its C++, its
// passes (shaders/cube_depth.geom, cube_depth.frag) and the lookup (shaders/cube_shadow.glsl).
// Binding 15 and unit 15 are the kit's cube map, so a technique can hold it beside the 2D depth
// map (binding 1, unit 4) and its own blocks and units (2-14, 5-14).
#ifndef SHADOWLAB_KIT_CUBE_DEPTH_MAP_SHARED_H
#define SHADOWLAB_KIT_CUBE_DEPTH_MAP_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(cube_depth_map)
SHADOWLAB_TEXTURE_UNIT(kCubeDepthMapUnit, 15)
SHADOWLAB_UNIFORM_BLOCK(CubeDepthMapUniforms, 15) {
    mat4 uCubeFaceMatrix[6];   // world -> clip of each face, GL's face order (+x, -x, +y, -y, +z, -z)
    vec4 uCubeLight;           // xyz: light position; w: far distance (stored depth = distance / far)
    vec4 uCubeBias;            // x: slope factor, y: constant units (glPolygonOffset's meaning), z: resolution
};
SHADOWLAB_SHARED_END
#endif
