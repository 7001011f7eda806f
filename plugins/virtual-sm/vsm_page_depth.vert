// The depth of one caster into one physical page (an instance of its indirect draw): vertices
// pulled from the host's adjacency buffers (corners a, b, c of each 6-index triangle), projected
// orthographically along the light into the page's tile of the atlas; four clip distances keep
// the triangle inside the tile, so neighbouring pages are never touched.
#include "virtual_sm_pages.glsl"
#include "vsm_objects.glsl"

layout(location = 0) in uvec2 aPair;   // per instance: dirty page, object
layout(std430, binding = VSM_VERTEX_BINDING) readonly buffer Vertices { float uVertices[]; };   // 8 floats each
layout(std430, binding = VSM_INDEX_BINDING) readonly buffer Indices { uint uIndices[]; };
layout(std430, binding = VSM_TRANSFORM_BINDING) readonly buffer Transforms { mat4 uTransforms[]; };   // model, normal

out gl_PerVertex {
    vec4 gl_Position;
    float gl_ClipDistance[4];
};

void main() {
    VsmObject object = uObjects[aPair.y];
    uint triangle = object.firstTriangle + uint(gl_VertexID) / 3u;
    uint index = uint(int(uIndices[6u * triangle + 2u * (uint(gl_VertexID) % 3u)]) + object.baseVertex);
    vec3 local = vec3(uVertices[8u * index], uVertices[8u * index + 1u], uVertices[8u * index + 2u]);
    vec3 light = vsmLightSpace((uTransforms[2u * object.transform] * vec4(local, 1.0)).xyz);
    uvec4 dirty = uDirty[aPair.x];
    // Texels from the page's corner, relative first (world coordinates lose bits at fine levels).
    vec2 texel = (light.xy - vsmPageRect(dirty).xy) / uLevel[dirty.x].w;
    gl_ClipDistance[0] = texel.x;
    gl_ClipDistance[1] = float(VSM_PAGE_TEXELS) - texel.x;
    gl_ClipDistance[2] = texel.y;
    gl_ClipDistance[3] = float(VSM_PAGE_TEXELS) - texel.y;
    vec2 atlas = (vsmTileOrigin(dirty.w) + texel) / vsmAtlasTexels();
    gl_Position = vec4(atlas * 2.0 - 1.0, vsmDepth(light.z) * 2.0 - 1.0, 1.0);
}
