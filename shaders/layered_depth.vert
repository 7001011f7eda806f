// kit::LayeredDepthMap's depth pass (linear depth, depth peeling): the light matrix (warped or
// not) places the fragment, the linear depth along the light (uLinearDepthPlane) travels as a
// varying to the fragment stage.
#include "common.glsl"
#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/layered_depth_shared.h"

layout(location = 0) in vec3 inPosition;

out float vLinearDepth;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vLinearDepth = dot(uLinearDepthPlane, world);
    gl_ClipDistance[0] = dot(uDepthClipPlane, world);
    gl_Position = uShadowMatrix * world;
}
