// virtual-sm's blocks and storage bindings, shared by virtual_sm.cpp, virtual_sm_pages.cpp and
// every GLSL stage of the plugin (see shadowlab/kit/shared.h for the convention).
#ifndef VIRTUAL_SM_SHARED_H
#define VIRTUAL_SM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(virtual_sm)
SHADOWLAB_TEXTURE_UNIT(kAtlasUnit, 6)             // sampler2DShadow: the physical depth atlas
SHADOWLAB_TEXTURE_UNIT(kPrepassDepthUnit, 7)      // the camera's depth-only pre-pass (window depth)
SHADOWLAB_IMAGE_UNIT(kLevelImageUnit, 1)          // debug image "page levels", written by the mark pass
SHADOWLAB_UNIFORM_BLOCK(VsmUniforms, 2) {
    mat4 uLightView;         // world -> light space: x, y across the virtual map, z along the light
    vec4 uLevel[16];         // level i: x, y first page of its window (page units), z page world size, w texel world size
    vec4 uVsmDepth;          // x: light-space z of depth 0, y: 1 / z range, z: normal offset (texels), w: level bias
    ivec4 uVsmSizes;         // x: levels, y: pages per level side, z: atlas pages per side, w: filter (0 hardware, 1 pcf)
    ivec4 uVsmOptions;       // x: debug levels tint, y: drawn objects, z: physical pages, w: frame serial (low 31 bits)
};
SHADOWLAB_SHARED_END

#define VSM_PAGE_TEXELS 128
#define VSM_MAX_LEVELS 16
// A pixel marks every page within this many texels of its point (the 3 x 3 PCF kernel's reach
// and its bilinear taps), so a lookup never lands on a page nobody asked for.
#define VSM_MARK_MARGIN_TEXELS 2.5

// Storage bindings (std430). 0 is the host's object transforms.
#define VSM_PAGE_TABLE_BINDING 2   // uvec4 per virtual page: physical + 1 (0 absent), page x, y (the tag), frame drawn
#define VSM_REQUEST_BINDING 3      // uint per virtual page: 1 when a pixel marked it this frame
#define VSM_STATE_BINDING 4        // VsmState: counters, statistics and the clear pass's indirect command
#define VSM_FREE_BINDING 5         // uint stack of free physical pages
#define VSM_DIRTY_BINDING 6        // uvec4 per page to draw this frame: level, page x, page y, physical
#define VSM_OBJECT_BINDING 7       // per opaque caster: light-space rectangle, its triangles
#define VSM_COMMAND_BINDING 8      // DrawArraysIndirectCommand per object
#define VSM_PAIR_BINDING 9         // uvec2 (dirty page, object): the instances of the draws
#define VSM_VERTEX_BINDING 10      // the host's adjacency extension: vertices, indices, transforms
#define VSM_INDEX_BINDING 11
#define VSM_TRANSFORM_BINDING 12

// VsmState's words (uint each); kVsmStatsWords of them from the start go to the statistics.
#define VSM_FREE_COUNT 0     // int: free pages on the stack
#define VSM_DIRTY_COUNT 1    // pages allocated this frame (drawn)
#define VSM_NEED 2           // marked pages without a physical page
#define VSM_EVICT 3          // int: pages still to evict this frame
#define VSM_MARKED 4
#define VSM_CACHED 5         // marked and already resident: not drawn
#define VSM_FAILED 6         // marked, but no physical page left
#define VSM_PAIRS 7          // (page, object) instances appended by the cull pass
#define VSM_DRAWN_TOTAL 8    // pages drawn since the cache was last invalidated
#define VSM_RESIDENT 9       // physical pages in use after this frame's allocation
#define VSM_STATS_WORDS 12
#define VSM_CLEAR_COMMAND 12 // 4 words: DrawArraysIndirectCommand of the clear pass
#define VSM_STATE_WORDS 16
#endif
