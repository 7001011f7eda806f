// The kit's cube depth map: the six faces in one pass. Invocation i projects the triangle with
// face i's matrix into layer i of the cube (gl_Layer); a triangle wholly outside one side of a
// face's frustum is not emitted there, so most triangles reach one or two faces.
#include "shadowlab/kit/cube_depth_map_shared.h"

layout(triangles, invocations = 6) in;
layout(triangle_strip, max_vertices = 3) out;

out vec3 gWorldPos;

void main() {
    mat4 faceMatrix = uCubeFaceMatrix[gl_InvocationID];
    vec4 clip[3];
    for (int i = 0; i < 3; ++i) clip[i] = faceMatrix * gl_in[i].gl_Position;
    for (int axis = 0; axis < 3; ++axis) {
        if (clip[0][axis] < -clip[0].w && clip[1][axis] < -clip[1].w && clip[2][axis] < -clip[2].w) return;
        if (clip[0][axis] > clip[0].w && clip[1][axis] > clip[1].w && clip[2][axis] > clip[2].w) return;
    }
    for (int i = 0; i < 3; ++i) {
        gl_Layer = gl_InvocationID;
        gl_Position = clip[i];
        gWorldPos = gl_in[i].gl_Position.xyz;
        EmitVertex();
    }
    EndPrimitive();
}
