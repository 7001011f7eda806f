// Host main pass, vertex stage: world position and normal for lighting and the shadow term.
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 1) in vec3 inNormal;
layout(location = 2) in vec2 inUv;

out VertexOut {
    vec3 worldPos;
    vec3 worldNormal;
    vec2 uv;
    flat uint objectId;   // object index + 1 (the camera pre-pass writes it)
} vOut;

// The camera pre-pass uses this stage too: both must produce the same depth, bit for bit.
invariant gl_Position;

void main() {
    vec4 world = uModel * vec4(inPosition, 1.0);
    vOut.worldPos = world.xyz;
    vOut.worldNormal = uNormalMatrix * inNormal;
    vOut.uv = inUv;
    vOut.objectId = uint(uFirstObject + gl_InstanceID) + 1u;
    gl_Position = uViewProjection * world;
}
