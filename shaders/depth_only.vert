// Depth-only pass from a light: shadow maps. uLightMatrix is the technique's light
// view-projection (it may fit the light differently from the host's default).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;
layout(location = 16) uniform mat4 uLightMatrix;

void main() {
    gl_Position = uLightMatrix * uModel * vec4(inPosition, 1.0);
}
