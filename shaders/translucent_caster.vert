// Light pass of translucent casters for fragment stages that need to tell surfaces apart
// (stochastic-sm, cssm2: xi decorrelated per surface, kit/stochastic_shared.h): depth_only.vert
// plus the object's index, which gl_InstanceID gives only here.
#include "common.glsl"
#include "shadowlab/kit/depth_map_shared.h"

layout(location = 0) in vec3 inPosition;
layout(location = 2) in vec2 inUv;

out vec2 vUv;
flat out uint vObject;

void main() {
    vUv = inUv;
    vObject = uint(uFirstObject + gl_InstanceID);
    gl_Position = uShadowMatrix * uModel * vec4(inPosition, 1.0);
}
