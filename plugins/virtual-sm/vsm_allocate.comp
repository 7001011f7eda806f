// Page allocation on the GPU, one invocation per virtual page, in dispatches (VSM_PHASE, in the
// order 1, 5, 2, 3, 4):
//   1 release: a resident page whose slot now holds another page of the moved window goes back
//     to the free list; marked pages are counted as cached (resident) or needed;
//   5 (one invocation): the shortfall, pages needed beyond the free list;
//   2 evict: only when the free list is shorter than the need, resident pages nobody marked this
//     frame are freed, as many as are missing (the cache keeps everything else);
//   3 allocate: each marked page without a physical page pops one from the free list, is tagged
//     and appended to the list of pages to clear and draw this frame;
//   4 finalize (one invocation): the counters become the frame's statistics and the clear pass's
//     indirect command.
// Pushes and pops never share a dispatch, so the free list is a plain stack with one atomic
// counter (StratusGFX vsm_mark_pages.cs / vsm_free_pages.cs keep theirs the same way).
#include "virtual_sm_pages.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = VSM_PAGE_TABLE_BINDING) buffer PageTable { uvec4 uPageTable[]; };
layout(std430, binding = VSM_REQUEST_BINDING) readonly buffer Requests { uint uRequest[]; };
layout(std430, binding = VSM_STATE_BINDING) buffer State { int uState[VSM_STATE_WORDS]; };
layout(std430, binding = VSM_FREE_BINDING) buffer FreeList { uint uFree[]; };
layout(std430, binding = VSM_DIRTY_BINDING) writeonly buffer Dirty { uvec4 uDirty[]; };

void pushFree(uint physical) {
    int slot = atomicAdd(uState[VSM_FREE_COUNT], 1);
    uFree[slot] = physical;
}

void main() {
#if VSM_PHASE == 5
    if (gl_GlobalInvocationID.x != 0u) return;
    uState[VSM_EVICT] = max(uState[VSM_NEED] - uState[VSM_FREE_COUNT], 0);
#elif VSM_PHASE == 4
    if (gl_GlobalInvocationID.x != 0u) return;
    uState[VSM_FREE_COUNT] = max(uState[VSM_FREE_COUNT], 0);
    uState[VSM_DRAWN_TOTAL] += uState[VSM_DIRTY_COUNT];
    uState[VSM_RESIDENT] = uVsmOptions.z - uState[VSM_FREE_COUNT];
    uState[VSM_CLEAR_COMMAND + 0] = 4;   // a triangle strip per page
    uState[VSM_CLEAR_COMMAND + 1] = uState[VSM_DIRTY_COUNT];
    uState[VSM_CLEAR_COMMAND + 2] = 0;
    uState[VSM_CLEAR_COMMAND + 3] = 0;
#else
    int P = uVsmSizes.y;
    int index = int(gl_GlobalInvocationID.x);
    if (index >= uVsmSizes.x * P * P) return;
    int level = index / (P * P);
    ivec2 slot = ivec2(index % P, (index / P) % P);
    // The absolute page this slot holds in the current window: the one congruent to it mod P.
    ivec2 first = ivec2(uLevel[level].xy);
    ivec2 page = first + ivec2(mod(vec2(slot - first), float(P)));
    uvec4 entry = uPageTable[index];
    bool resident = entry.x != 0u;
    bool marked = uRequest[index] != 0u;
#if VSM_PHASE == 1
    if (resident && ivec2(entry.yz) != page) {
        pushFree(entry.x - 1u);
        uPageTable[index] = uvec4(0u);
        resident = false;
    }
    if (!marked) return;
    atomicAdd(uState[VSM_MARKED], 1);
    // Two plain atomics, not one on a ternary index: NVIDIA's 580 compiler fails to link the
    // latter ("fatal error C9999: unexpected expression in DUI_foreachId").
    if (resident)
        atomicAdd(uState[VSM_CACHED], 1);
    else
        atomicAdd(uState[VSM_NEED], 1);
#elif VSM_PHASE == 2
    if (!resident || marked) return;
    if (atomicAdd(uState[VSM_EVICT], -1) <= 0) return;   // the shortfall phase 5 left
    pushFree(entry.x - 1u);
    uPageTable[index] = uvec4(0u);
#elif VSM_PHASE == 3
    if (!marked || resident) return;
    int top = atomicAdd(uState[VSM_FREE_COUNT], -1);
    if (top <= 0) {
        atomicAdd(uState[VSM_FAILED], 1);
        return;
    }
    uint physical = uFree[top - 1];
    uPageTable[index] = uvec4(physical + 1u, uvec2(page), uint(uVsmOptions.w));
    uDirty[atomicAdd(uState[VSM_DIRTY_COUNT], 1)] = uvec4(uint(level), uvec2(page), physical);
#endif
#endif
}
