// csm's shadow pass: every cascade in one pass (layered rendering). Invocation i projects the
// triangle with cascade i's matrix into layer i of the 2D array (gl_Layer); cascades whose map the
// triangle misses on one side emit nothing. CSM_CASCADES (csm.cpp builds one program per count)
// sets the instances per triangle, so no invocation is spent on a cascade that does not exist. Depth is
// clamped (GL_DEPTH_CLAMP), so casters nearer the light than a cascade's near plane still land.
#include "shadowlab/kit/csm_shared.h"

layout(triangles, invocations = CSM_CASCADES) in;
layout(triangle_strip, max_vertices = 3) out;

void main() {
    int cascade = gl_InvocationID;
    mat4 toClip = uCascadeMatrix[cascade];
    vec4 clip[3];
    for (int i = 0; i < 3; ++i) clip[i] = toClip * gl_in[i].gl_Position;
    for (int axis = 0; axis < 2; ++axis) {
        if (clip[0][axis] < -clip[0].w && clip[1][axis] < -clip[1].w && clip[2][axis] < -clip[2].w) return;
        if (clip[0][axis] > clip[0].w && clip[1][axis] > clip[1].w && clip[2][axis] > clip[2].w) return;
    }
    for (int i = 0; i < 3; ++i) {
        gl_Layer = cascade;
        gl_Position = clip[i];
        EmitVertex();
    }
    EndPrimitive();
}
