// The edges of each reported map's clip volume in the camera view (the light frustum, or the
// box an orthographic map covers): 12 edges, 24 vertices per instance (one instance a map).
#include "shadow_map_view.glsl"
out vec3 vColour;

const vec3 kMapColours[8] = vec3[](vec3(0.9, 0.2, 0.2), vec3(0.2, 0.8, 0.2), vec3(0.25, 0.4, 1.0), vec3(0.95, 0.8, 0.1),
                                   vec3(0.8, 0.3, 0.9), vec3(0.1, 0.85, 0.85), vec3(1.0, 0.55, 0.1), vec3(0.6, 0.6, 0.6));
// Corner pairs of a cube's 12 edges (corner bit 0 = +x, bit 1 = +y, bit 2 = +z).
const int kEdges[24] = int[](0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 1, 3, 4, 6, 5, 7, 0, 4, 1, 5, 2, 6, 3, 7);

void main() {
    int corner = kEdges[gl_VertexID % 24];
    vec3 ndc = vec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1) * 2.0 - 1.0;
    vec4 world = inverse(uMaps[gl_InstanceID].worldToClip) * vec4(ndc, 1.0);
    vColour = kMapColours[gl_InstanceID % 8];
    gl_Position = uCameraViewProjection * vec4(world.xyz / world.w, 1.0);
}
