// Depth-only pass from a light: shadow maps (kit/depth_map.h) and the bench's depth floor.
// uShadowMatrix is the technique's light view-projection, in the depth map's block.
#include "common.glsl"
#include "shadowlab/kit/depth_map_shared.h"

layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;

out vec2 vUv;   // for fragment stages that sample the material's textures (surfaceTransmission)

void main() {
    vUv = inUv;
    vec4 world = uModel * vec4(inPosition, 1.0);
    gl_ClipDistance[0] = dot(uDepthClipPlane, world);
    gl_Position = uShadowMatrix * world;
}
