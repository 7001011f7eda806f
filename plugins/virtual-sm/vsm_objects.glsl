// The opaque casters as virtual-sm draws them: one record per object, written on the CPU when
// the scene or the light changes (virtual_sm_pages.cpp: VsmObject).
struct VsmObject {
    vec4 lightRect;        // the object's bounds in light space: min x, min y, max x, max y
    uint firstTriangle;    // in the adjacency extension's index buffer (6 indices a triangle)
    uint triangleCount;
    int baseVertex;
    uint transform;        // the object's index in the scene (its transform)
};
layout(std430, binding = VSM_OBJECT_BINDING) readonly buffer Objects { VsmObject uObjects[]; };
layout(std430, binding = VSM_DIRTY_BINDING) readonly buffer Dirty { uvec4 uDirty[]; };

// A dirty page's light-space rectangle (min xy, max xy).
vec4 vsmPageRect(uvec4 dirty) {
    float size = uLevel[dirty.x].z;
    vec2 lo = vec2(ivec2(dirty.yz)) * size;
    return vec4(lo, lo + size);
}
