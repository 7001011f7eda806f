// Shadow volumes: what the geometry stage (volume.geom), the compute extraction
// (volume_extract.comp) and its draw (volume_indirect.vert) share, so that both variants make
// every decision and every vertex with the same arithmetic (and draw the same triangles).
#ifndef SHADOW_VOLUME_COMMON_GLSL
#define SHADOW_VOLUME_COMMON_GLSL
#include "common.glsl"
#include "shadow_volumes_shared.h"

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

// Which sides and caps the triangle with adjacency (corner[0..2] counter-clockwise; neighbour[e]
// the corner opposite edge e = corner[e] -> corner[e + 1] in the other triangle, or corner[e + 2]
// itself where the host found none) contributes: bit e set when edge e gets a side; `lit` whether
// it faces the light; false when it contributes nothing (no area, or closed and facing away).
// The rules (volume.geom's header): closed meshes the classic set, any other mesh every triangle
// turned to face the light with a side wherever there is no neighbour or it faces the other way.
bool volumeOf(vec3 corner[3], vec3 neighbour[3], bool closedMesh, out bool lit, out int sideMask) {
    lit = false;
    sideMask = 0;
    vec3 n = cross(corner[1] - corner[0], corner[2] - corner[0]);
    if (dot(n, n) == 0.0) return false;   // no area, no shadow
    lit = facesLight(corner[0], corner[1], corner[2]);
    if (closedMesh && !lit) return false;
    for (int e = 0; e < 3; ++e) {
        vec3 a = corner[e], b = corner[(e + 1) % 3];
        bool open = neighbour[e] == corner[(e + 2) % 3];   // the host's mark: no neighbour
        // The neighbour is (b, a, neighbour) in its own winding.
        if (open || facesLight(b, a, neighbour[e]) != lit) sideMask |= 1 << e;
    }
    return true;
}
#endif
