// area-reference pre-pass: the world position of the nearest opaque surface in each pixel of the
// host camera (drawn with main.vert, so it rasterises exactly like the main pass); w = 1 where
// geometry was drawn, the clear value (w = 0) elsewhere.
#include "common.glsl"

in VertexOut {
    vec3 worldPos;
    vec3 worldNormal;
    vec2 uv;
} vIn;

layout(location = 0) out vec4 outPosition;

void main() {
    outPosition = vec4(vIn.worldPos, 1.0);
}
