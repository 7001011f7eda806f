// Planar shadows, pass 1: depth of the view (the stencil id is set by the host-side draw loop).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;

void main() {
    gl_Position = uViewProjection * uModel * vec4(inPosition, 1.0);
}
