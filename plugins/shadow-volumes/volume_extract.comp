// Shadow volumes, extract = compute: the silhouettes and caps found in a compute pass and written
// to storage buffers, which volume_indirect.vert then draws with glDrawArraysIndirect (the
// commands' counts written here with atomics, so the CPU never reads them). The approach of
// dormon/Shadows' CSSV (compute-shader silhouettes drawn indirectly; Kolivand's multiplicity);
// the decisions are volume.geom's, through the same functions (volume_common.glsl), one
// invocation per triangle of each caster object instead of one geometry-stage invocation, so
// both variants draw the same triangles from the same vertices.
//
// Input: the host's vertices and triangles with adjacency (SHADOWLAB_EXT_ADJACENCY), one batch of
// objects sharing a mesh per dispatch (uBatch: first object, objects in this dispatch, first
// triangle, triangles a mesh; uMesh: base vertex, closed). Output: one record per side (the edge's
// world points, from -> to as volume.geom's side(from, to)) and per cap (the triangle turned to
// face the light), at indices the atomics on the commands' vertex counts hand out: 6 vertices a
// side (two triangles), 3 a near cap, 3 a far cap (point and spot lights only, at the near cap's
// index). Records past the capacity (never, with the worst case allocated) are dropped and the
// draw turns them into nothing.
#include "volume_common.glsl"

layout(local_size_x = kExtractGroupSize) in;

layout(std430, binding = kVerticesBinding) readonly buffer Vertices { float vertices[]; };   // 8 floats a vertex
layout(std430, binding = kAdjacencyBinding) readonly buffer Adjacency { uint adjacency[]; };   // 6 a triangle
layout(std430, binding = kSidesBinding) writeonly buffer Sides { float sides[]; };
layout(std430, binding = kCapsBinding) writeonly buffer Caps { float caps[]; };
layout(std430, binding = kCommandsBinding) coherent buffer Commands { uint commands[]; };

layout(location = kCapacityLocation) uniform uvec2 uCapacity;
layout(location = kBatchLocation) uniform uvec4 uBatch;
layout(location = kMeshLocation) uniform ivec2 uMesh;

// The world position of adjacency entry k of triangle t of `object`: as volume.vert computes it.
vec3 worldCorner(uint object, uint t, uint k) {
    uint v = uint(int(adjacency[6u * t + k]) + uMesh.x);
    vec3 p = vec3(vertices[8u * v], vertices[8u * v + 1u], vertices[8u * v + 2u]);
    return (uObjectTransforms[object].model * vec4(p, 1.0)).xyz;
}

void writePoint(inout uint at, vec3 p, bool side) {
    if (side) {
        sides[at] = p.x;
        sides[at + 1u] = p.y;
        sides[at + 2u] = p.z;
    } else {
        caps[at] = p.x;
        caps[at + 1u] = p.y;
        caps[at + 2u] = p.z;
    }
    at += 3u;
}

void main() {
    uint linear = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * gl_WorkGroupSize.x + gl_LocalInvocationID.x;
    uint triangles = uBatch.w;
    if (triangles == 0u || linear >= uBatch.y * triangles) return;
    uint object = uBatch.x + linear / triangles;
    uint t = uBatch.z + linear % triangles;
    vec3 corner[3], neighbour[3];
    for (uint e = 0u; e < 3u; ++e) {
        corner[e] = worldCorner(object, t, 2u * e);
        neighbour[e] = worldCorner(object, t, 2u * e + 1u);
    }
    bool lit;
    int sideBits;
    if (!volumeOf(corner, neighbour, uMesh.y != 0, lit, sideBits)) return;
    uint count = uint(bitCount(sideBits));
    if (count > 0u) {
        uint record = atomicAdd(commands[kSideCommand], 6u * count) / 6u;
        for (int e = 0; e < 3; ++e) {
            if ((sideBits & (1 << e)) == 0) continue;
            vec3 a = corner[e], b = corner[(e + 1) % 3];
            if (record < uCapacity.x) {
                uint at = 6u * record;
                writePoint(at, lit ? a : b, true);   // side(a, b) when lit, side(b, a) when turned
                writePoint(at, lit ? b : a, true);
            }
            ++record;
        }
    }
    uint cap = atomicAdd(commands[kNearCapCommand], 3u) / 3u;
    if (!directional()) atomicAdd(commands[kFarCapCommand], 3u);
    if (cap < uCapacity.y) {
        uint at = 9u * cap;
        writePoint(at, corner[0], false);
        writePoint(at, lit ? corner[1] : corner[2], false);
        writePoint(at, lit ? corner[2] : corner[1], false);
    }
}
