// Shadow volumes: world positions for the geometry stage (volume.geom).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
out vec3 vWorld;

void main() {
    vWorld = (uModel * vec4(inPosition, 1.0)).xyz;
    gl_Position = vec4(vWorld, 1.0);
}
