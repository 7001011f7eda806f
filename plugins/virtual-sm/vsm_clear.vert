// Clearing the pages drawn this frame: an instanced quad per page at depth 1 over its tile
// (depth test ALWAYS). A depth texture cannot be a compute image in OpenGL, so this one step of
// the allocation is a draw; its instance count comes from the allocation pass (indirect).
#include "virtual_sm_pages.glsl"

layout(std430, binding = VSM_DIRTY_BINDING) readonly buffer Dirty { uvec4 uDirty[]; };

void main() {
    vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));
    vec2 atlas = (vsmTileOrigin(uDirty[gl_InstanceID].w) + corner * float(VSM_PAGE_TEXELS)) /
                 vsmAtlasTexels();
    gl_Position = vec4(atlas * 2.0 - 1.0, 1.0, 1.0);
}
