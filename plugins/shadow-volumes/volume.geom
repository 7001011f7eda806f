// Shadow volumes from triangles with adjacency (the host's DrawPrimitive::TrianglesAdjacency).
//
// Each triangle T, turned to face the light, bounds a prism: T itself (the near cap), T projected
// to infinity away from the light (the far cap, w = 0) and one side per edge. A point is in shadow
// when it lies inside at least one prism, i.e. when the count of prism faces crossed between the
// eye and the point is not zero (Crow 1977; Heidmann 1991 counts with the stencil buffer). Sides
// shared by two prisms with opposite orientations cancel and are not drawn: what remains are the
// silhouette edges.
//
// Closed meshes (every edge has its neighbour: uClosedMesh) use the classic set: the triangles
// facing the light, a side where the neighbour faces away (the silhouette). Any other mesh (the
// ground, terrain, OBJ files with holes) uses every triangle turned towards the light, and a side
// wherever there is no neighbour or the neighbour faces the light the other way. Per edge this is
// the sum of the turned triangles' sides, Kolivand's edge multiplicity realised one triangle at a
// time: an edge of k triangles contributes k sides less those that cancel, so open and
// non-manifold meshes count correctly (each of their triangles is a closed prism).
//
// Exactness: each decision is made the same way by both triangles of an edge (facing computed
// from the corners in a canonical order), so no side is drawn once where two cancel; the near
// cap starts `uPush` beyond the caster, as the ray-traced reference starts its rays 1e-4 of the
// scene's size off the surface, so lit faces do not shadow themselves. Far points are at
// infinity (w = 0) and the pass runs with GL_DEPTH_CLAMP: nothing is clipped by the far plane
// (Everitt and Kilgard 2002).
#include "volume_common.glsl"

layout(triangles_adjacency) in;
#ifdef SHADOW_VOLUME_EDGES
layout(line_strip, max_vertices = 6) out;   // the debug view: silhouette edges only
#else
layout(triangle_strip, max_vertices = 18) out;   // three sides of 4 and two caps of 3
#endif
in vec3 vWorld[];

layout(location = 6) uniform int uClosedMesh;

#ifdef SHADOW_VOLUME_EDGES
void side(vec3 from, vec3 to) {
    gl_Position = nearPoint(from);
    EmitVertex();
    gl_Position = nearPoint(to);
    EmitVertex();
    EndPrimitive();
}
#else
// The side of edge from -> to (the turned triangle's winding): B, A, B', A' as a strip, facing out.
void side(vec3 from, vec3 to) {
    gl_Position = nearPoint(to);
    EmitVertex();
    gl_Position = nearPoint(from);
    EmitVertex();
    gl_Position = farPoint(to);
    EmitVertex();
    gl_Position = farPoint(from);
    EmitVertex();
    EndPrimitive();
}
#endif

void main() {
    vec3 corner[3] = vec3[3](vWorld[0], vWorld[2], vWorld[4]);
    vec3 neighbour[3] = vec3[3](vWorld[1], vWorld[3], vWorld[5]);
    bool lit;
    int sides;
    if (!volumeOf(corner, neighbour, uClosedMesh != 0, lit, sides)) return;
    for (int e = 0; e < 3; ++e) {
        if ((sides & (1 << e)) == 0) continue;
        vec3 a = corner[e], b = corner[(e + 1) % 3];
        if (lit) side(a, b);
        else side(b, a);
    }
#ifndef SHADOW_VOLUME_EDGES
    // Caps, turned to face the light: near cap counter-clockwise from the light, far cap reversed.
    // Depth-pass needs them too: a near cap is pushed beyond its caster, so at a silhouette pixel
    // it can cover background behind the caster (without them single pixels went wrong there).
    vec3 p0 = corner[0], p1 = lit ? corner[1] : corner[2], p2 = lit ? corner[2] : corner[1];
    gl_Position = nearPoint(p0);
    EmitVertex();
    gl_Position = nearPoint(p1);
    EmitVertex();
    gl_Position = nearPoint(p2);
    EmitVertex();
    EndPrimitive();
    if (!directional()) {   // a directional light's far cap is one point at infinity
        gl_Position = farPoint(p0);
        EmitVertex();
        gl_Position = farPoint(p2);
        EmitVertex();
        gl_Position = farPoint(p1);
        EmitVertex();
        EndPrimitive();
    }
#endif
}
