// Host camera pre-pass (extension "shadowlab.camera-prepass/1"): the world position, normal
// (facing the viewer, as the main pass shades it) and object id of the nearest opaque surface.
#include "common.glsl"

in VertexOut {
    vec3 worldPos;
    vec3 worldNormal;
    vec2 uv;
    flat uint objectId;
} vIn;

layout(location = 0) out vec4 outPosition;   // w = 1 where geometry was drawn
layout(location = 1) out vec4 outNormal;
layout(location = 2) out uint outObjectId;   // object index + 1; 0 = background

void main() {
    vec3 N = normalize(vIn.worldNormal);
    if (!gl_FrontFacing) N = -N;
    outPosition = vec4(vIn.worldPos, 1.0);
    outNormal = vec4(N, 0.0);
    outObjectId = vIn.objectId;
}
