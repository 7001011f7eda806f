// Reference G-buffer: world position and normal of the surface seen at each pixel, exactly as
// the main pass computes them (same vertex transform).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;

out vec3 vWorldPos;
out vec3 vWorldNormal;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vWorldPos = world.xyz;
    vWorldNormal = uNormalMatrix * inNormal;
    gl_Position = uViewProjection * world;
}
