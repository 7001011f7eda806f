// Shadow volumes, extract = compute: the records volume_extract.comp wrote, drawn with
// glDrawArraysIndirect (no vertex buffer; gl_VertexID picks the record and its corner). Each
// primitive is the one volume.geom emits for the same triangle, from the same world points through
// the same nearPoint()/farPoint(), in the order its strips are rasterised, so the two variants
// draw the same triangles (their images differ at most where llvmpipe rounds a geometry stage's
// output depth differently: docs/shadow-volumes.md).
#include "volume_common.glsl"

layout(std430, binding = kSidesBinding) readonly buffer Sides { float sides[]; };
layout(std430, binding = kCapsBinding) readonly buffer Caps { float caps[]; };

layout(location = kCapacityLocation) uniform uvec2 uCapacity;
layout(location = kDrawLocation) uniform int uDraw;   // kDrawSides, kDrawNearCaps, kDrawFarCaps, kDrawEdges

// Outside the clip volume: a primitive of records past the capacity draws nothing.
const vec4 kNowhere = vec4(2.0, 2.0, 2.0, 1.0);

vec3 sidePoint(uint record, uint k) { return vec3(sides[6u * record + 3u * k], sides[6u * record + 3u * k + 1u], sides[6u * record + 3u * k + 2u]); }
vec3 capPoint(uint record, uint k) { return vec3(caps[9u * record + 3u * k], caps[9u * record + 3u * k + 1u], caps[9u * record + 3u * k + 2u]); }

void main() {
    uint vertex = uint(gl_VertexID);
    if (uDraw == kDrawSides || uDraw == kDrawEdges) {
        uint record = vertex / 6u, corner = vertex % 6u;
        if (record >= uCapacity.x) {
            gl_Position = kNowhere;
            return;
        }
        vec3 from = sidePoint(record, 0u), to = sidePoint(record, 1u);
        if (uDraw == kDrawEdges) {   // GL_LINES: the edge from the first pair, nothing from the others
            gl_Position = corner == 0u ? nearPoint(from) : corner == 1u ? nearPoint(to) : kNowhere;
            return;
        }
        // volume.geom's strip (near(to), near(from), far(to), far(from)) as the triangles a strip
        // rasterises to, (0, 1, 2) and (2, 1, 3).
        const uint strip[6] = uint[6](0u, 1u, 2u, 2u, 1u, 3u);
        uint k = strip[corner];
        vec3 p = (k == 0u || k == 2u) ? to : from;
        gl_Position = k < 2u ? nearPoint(p) : farPoint(p);
        return;
    }
    uint record = vertex / 3u, corner = vertex % 3u;
    if (record >= uCapacity.y) {
        gl_Position = kNowhere;
        return;
    }
    if (uDraw == kDrawNearCaps) gl_Position = nearPoint(capPoint(record, corner));
    else gl_Position = farPoint(capPoint(record, corner == 0u ? 0u : 3u - corner));   // reversed: p0, p2, p1
}
