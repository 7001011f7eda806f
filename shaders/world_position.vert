// World position as gl_Position, for a geometry stage that projects each triangle into several
// maps in one pass (the kit's cube depth map: six faces; csm: every cascade, layered rendering).
#include "common.glsl"

layout(location = 0) in vec3 inPosition;

void main() {
    gl_Position = uModel * vec4(inPosition, 1.0);
}
