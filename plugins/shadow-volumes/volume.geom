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
#include "common.glsl"
#include "shadow_volumes_shared.h"

layout(triangles_adjacency) in;
#ifdef SHADOW_VOLUME_EDGES
layout(line_strip, max_vertices = 6) out;   // the debug view: silhouette edges only
#else
layout(triangle_strip, max_vertices = 18) out;   // three sides of 4 and two caps of 3
#endif
in vec3 vWorld[];

layout(location = 6) uniform int uClosedMesh;
layout(location = kPushLocation) uniform float uPush;

bool directional() { return lightType() == LIGHT_DIRECTIONAL; }

vec3 awayFromLight(vec3 p) { return directional() ? uLightDirection.xyz : normalize(p - uLightPosition.xyz); }

bool lessThanLexical(vec3 a, vec3 b) {
    return a.x < b.x || (a.x == b.x && (a.y < b.y || (a.y == b.y && a.z < b.z)));
}

// Whether the triangle (a, b, c), counter-clockwise, faces the light: computed from its corners in
// lexical order (with the sign of the permutation), so every invocation that looks at the same
// triangle, whichever corner it starts from, decides alike.
bool facesLight(vec3 a, vec3 b, vec3 c) {
    bool flipped = false;
    vec3 t;
    if (lessThanLexical(b, a)) { t = a; a = b; b = t; flipped = !flipped; }
    if (lessThanLexical(c, b)) { t = b; b = c; c = t; flipped = !flipped; }
    if (lessThanLexical(b, a)) { t = a; a = b; b = t; flipped = !flipped; }
    vec3 toLight = directional() ? -uLightDirection.xyz : uLightPosition.xyz - a;
    float side = dot(cross(b - a, c - a), toLight);
    return flipped ? side < 0.0 : side > 0.0;
}

vec4 nearPoint(vec3 p) { return uViewProjection * vec4(p + uPush * awayFromLight(p), 1.0); }
vec4 farPoint(vec3 p) { return uViewProjection * vec4(awayFromLight(p), 0.0); }

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
    vec3 n = cross(corner[1] - corner[0], corner[2] - corner[0]);
    if (dot(n, n) == 0.0) return;   // no area, no shadow
    bool lit = facesLight(corner[0], corner[1], corner[2]);
    if (uClosedMesh != 0 && !lit) return;
    for (int e = 0; e < 3; ++e) {
        vec3 a = corner[e], b = corner[(e + 1) % 3];
        vec3 neighbour = vWorld[2 * e + 1];
        bool open = neighbour == corner[(e + 2) % 3];   // the host's mark: no neighbour
        // The neighbour is (b, a, neighbour) in its own winding.
        if (open || facesLight(b, a, neighbour) != lit) {
            if (lit) side(a, b);
            else side(b, a);
        }
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
