// Casters culled per page (one invocation per opaque caster): the object's light-space bounds
// against the rectangle of each page drawn this frame (its box reaches along the whole light
// axis: a caster anywhere towards the light shades the page). The pages an object overlaps become
// the instances of its indirect draw, contiguous from an atomically reserved base; an object
// that overlaps none draws nothing (instance count 0), so a frame whose pages are all cached
// draws no triangle. Like the "cull per page" pass of UE5 and StratusGFX vsm_cull.cs, without
// their hierarchical depth test.
#include "virtual_sm_pages.glsl"
#include "vsm_objects.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = VSM_STATE_BINDING) buffer State { int uState[VSM_STATE_WORDS]; };
struct DrawArraysCommand {
    uint count;
    uint instanceCount;
    uint first;
    uint baseInstance;
};
layout(std430, binding = VSM_COMMAND_BINDING) writeonly buffer Commands { DrawArraysCommand uCommands[]; };
layout(std430, binding = VSM_PAIR_BINDING) writeonly buffer Pairs { uvec2 uPairs[]; };
layout(location = 16) uniform uint uPairCapacity;

bool overlaps(vec4 a, vec4 b) { return all(lessThanEqual(a.xy, b.zw)) && all(lessThanEqual(b.xy, a.zw)); }

void main() {
    uint object = gl_GlobalInvocationID.x;
    if (object >= uint(uVsmOptions.y)) return;
    vec4 rect = uObjects[object].lightRect;
    uint pages = uint(uState[VSM_DIRTY_COUNT]);
    uint count = 0u;
    for (uint k = 0u; k < pages; ++k) count += overlaps(rect, vsmPageRect(uDirty[k])) ? 1u : 0u;
    uint base = count > 0u ? uint(atomicAdd(uState[VSM_PAIRS], int(count))) : 0u;
    uint kept = base >= uPairCapacity ? 0u : min(count, uPairCapacity - base);
    uint written = 0u;
    for (uint k = 0u; k < pages && written < kept; ++k)
        if (overlaps(rect, vsmPageRect(uDirty[k]))) uPairs[base + written++] = uvec2(k, object);
    uCommands[object] = DrawArraysCommand(3u * uObjects[object].triangleCount, kept, 0u, base);
}
