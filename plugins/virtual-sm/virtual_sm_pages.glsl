// Virtual shadow map addressing, shared by the mark pass, the page draws and shadowTerm().
// The virtual map of a directional light is a stack of clipmap levels: level L has texels of
// world size t_L = t_0 2^L and a window of P x P pages of 128 x 128 texels around the camera,
// moved in whole pages (uLevel[L].xy), so a page's content depends only on its absolute page
// coordinates in light space, never on the camera. A virtual page lives in page-table slot
// (page mod P) of its level (toroidal addressing, as clipmaps do): when the window moves by one
// page, only the row or column that enters reuses slots, and the entry's tag (its absolute page)
// tells a stale slot from a valid one. Sources: Fernando et al. / UE5 virtual shadow maps
// (clipmap levels of 16K, 128^2 pages), StratusGFX Source/Shaders/vsm_*.cs (page marking from
// the depth buffer, GPU free list), Frogfood data/shaders/shadows/vsm/ and Blender EEVEE Next
// eevee_shadow.cc (tile marking by screen footprint, page caching across frames).
#include "shadowlab/frame_block.h"
#include "virtual_sm_shared.h"

vec3 vsmLightSpace(vec3 world) { return (uLightView * vec4(world, 1.0)).xyz; }
float vsmDepth(float lightZ) { return (lightZ - uVsmDepth.x) * uVsmDepth.y; }

// The finest level whose texel is at least the pixel's world footprint (the size of a pixel at
// view depth z: 2 z tan(fovY / 2) / height = 2 z / (P[1][1] height)), shifted by the level bias.
int vsmFootprintLevel(float viewDepth) {
    float footprint = max(viewDepth, 1e-6) * 2.0 / (uProjection[1][1] * uViewport.y);
    float level = ceil(log2(footprint / uLevel[0].w) - 1e-3) + uVsmDepth.w;
    return int(clamp(level, 0.0, float(uVsmSizes.x - 1)));
}

// Whether the point (light-space xy) and its margin lie inside level L's window.
bool vsmInWindow(int level, vec2 xy, float marginTexels) {
    vec2 page = xy / uLevel[level].z;
    vec2 margin = vec2(marginTexels / float(VSM_PAGE_TEXELS));
    return all(greaterThanEqual(page - margin, uLevel[level].xy)) &&
           all(lessThan(page + margin, uLevel[level].xy + float(uVsmSizes.y)));
}

// The level a point needs: its footprint's, or the first coarser one whose window holds it; -1
// beyond the coarsest window (fitted to hold the scene: nothing there casts).
int vsmLevelFor(float viewDepth, vec2 xy) {
    for (int level = vsmFootprintLevel(viewDepth); level < uVsmSizes.x; ++level)
        if (vsmInWindow(level, xy, VSM_MARK_MARGIN_TEXELS)) return level;
    return -1;
}

int vsmEntry(int level, ivec2 page) {
    int P = uVsmSizes.y;
    ivec2 slot = ivec2(mod(vec2(page), float(P)));
    return (level * P + slot.y) * P + slot.x;
}

// Atlas texel of the physical page's corner.
vec2 vsmTileOrigin(uint physical) {
    uint Q = uint(uVsmSizes.z);
    return vec2(float(physical % Q), float(physical / Q)) * float(VSM_PAGE_TEXELS);
}

// The atlas in use, in texels: physical pages (uVsmOptions.z) in rows of uVsmSizes.z.
vec2 vsmAtlasTexels() {
    return vec2(float(uVsmSizes.z), float(uVsmOptions.z / uVsmSizes.z)) * float(VSM_PAGE_TEXELS);
}

vec3 vsmLevelColour(int level) {
    const vec3 kColours[8] = vec3[8](vec3(1.0, 0.25, 0.25), vec3(0.25, 1.0, 0.25), vec3(0.3, 0.45, 1.0),
                                     vec3(1.0, 0.9, 0.2), vec3(1.0, 0.3, 1.0), vec3(0.2, 1.0, 1.0),
                                     vec3(1.0, 0.6, 0.2), vec3(0.7, 0.7, 0.7));
    return kColours[level % 8];
}
