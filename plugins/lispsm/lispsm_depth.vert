// lispsm's depth pass for linear depth and depth peeling: the warp places the fragment, the
// linear depth along the light (uLinearDepthPlane) travels as a varying to the fragment stage.
#include "common.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "lispsm_shared.h"

layout(location = 0) in vec3 inPosition;

out float vLinearDepth;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vLinearDepth = dot(uLinearDepthPlane, world);
    gl_ClipDistance[0] = dot(uDepthClipPlane, world);
    gl_Position = uShadowMatrix * world;
}
