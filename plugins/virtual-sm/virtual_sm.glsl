// Virtual shadow maps, main-pass side: the point's level from its screen footprint (the same
// function the mark pass used, so its page is resident), the page table gives the physical page,
// and the texture unit's 2x2 comparison reads the atlas tile (filter = pcf: 3 x 3 such taps one
// texel apart, each through the page table). Taps are clamped half a texel inside their tile,
// so a bilinear footprint never reads the neighbouring tile, which holds an unrelated page.
// Spot and point lights: the kit's single map or cube (the fallback virtual_sm.cpp documents).
#include "virtual_sm_pages.glsl"
#include "light_space.glsl"
#include "cube_shadow.glsl"
#include "shadowlab/kit/depth_map_shared.h"

layout(binding = kAtlasUnit) uniform sampler2DShadow uAtlas;
layout(binding = kDepthMapUnit) uniform sampler2DShadow uFallbackMap;
layout(std430, binding = VSM_PAGE_TABLE_BINDING) readonly buffer PageTable { uvec4 uPageTable[]; };

// One hardware 2x2 comparison at texel `t` of the level's window (from its corner: small
// numbers, where world coordinates would lose the bits of fine levels); -1 where the page is not
// resident.
float vsmTap(int level, vec2 t, float depth, inout uint drawnFrame) {
    vec2 pageInWindow = floor(t / float(VSM_PAGE_TEXELS));
    ivec2 page = ivec2(uLevel[level].xy + pageInWindow);
    uvec4 entry = uPageTable[vsmEntry(level, page)];
    if (entry.x == 0u || ivec2(entry.yz) != page) return -1.0;
    drawnFrame = entry.w;
    vec2 inPage = clamp(t - pageInWindow * float(VSM_PAGE_TEXELS), vec2(0.5), vec2(float(VSM_PAGE_TEXELS) - 0.5));
    // The texture may be larger than the atlas in use (it only grows: virtual_sm_pages.cpp).
    vec2 atlas = (vsmTileOrigin(entry.x - 1u) + inPage) / vec2(textureSize(uAtlas, 0));
    return texture(uAtlas, vec3(atlas, depth));
}

// The lit fraction at `level`, or -1 when its centre page is missing.
float vsmLit(int level, vec3 light, inout uint drawnFrame) {
    vec2 t = (light.xy - uLevel[level].xy * uLevel[level].z) / uLevel[level].w;
    float depth = vsmDepth(light.z);
    float centre = vsmTap(level, t, depth, drawnFrame);
    if (centre < 0.0 || uVsmSizes.w == 0) return centre;
    float sum = 0.0;
    for (int y = -1; y <= 1; ++y)
        for (int x = -1; x <= 1; ++x) {
            uint ignored = 0u;
            float tap = (x == 0 && y == 0) ? centre : vsmTap(level, t + vec2(x, y), depth, ignored);
            sum += tap < 0.0 ? centre : tap;
        }
    return sum / 9.0;
}

vec3 shadowTerm(ShadowInput s) {
    if (lightType() == LIGHT_POINT) return vec3(cubeShadow(s.worldPos, s.worldNormal, 1, 1.0, 0.0));
    if (lightType() == LIGHT_SPOT) {
        vec3 coord = shadowMapCoord(uShadowMatrix, s.worldPos);
        return vec3(insideShadowMap(coord) ? texture(uFallbackMap, coord) : 1.0);
    }
    float viewDepth = -(uView * vec4(s.worldPos, 1.0)).z;
    int footprintLevel = vsmFootprintLevel(viewDepth);
    vec3 light = vsmLightSpace(s.worldPos + s.worldNormal * (uVsmDepth.z * uLevel[footprintLevel].w));
    int level = vsmLevelFor(viewDepth, light.xy);
    if (level < 0) return vec3(1.0);   // beyond the coarsest window, which holds every caster
    // The mark pass chose the same level from the same point; a neighbour level is a safety net
    // for the last bit of a footprint computed in another stage.
    uint drawnFrame = 0u;
    float lit = vsmLit(level, light, drawnFrame);
    if (lit < 0.0 && level + 1 < uVsmSizes.x) lit = vsmLit(++level, light, drawnFrame);
    if (lit < 0.0 && level >= 2) lit = vsmLit(level -= 2, light, drawnFrame);
    if (lit < 0.0) return vec3(1.0);
    if (uVsmOptions.x != 0) {
        // Debug: the level's colour; pages drawn this frame bright, cached ones dimmer.
        float fresh = drawnFrame == uint(uVsmOptions.w) ? 1.0 : 0.55;
        return vec3(lit) * 0.5 + vsmLevelColour(level) * fresh * (0.25 + 0.25 * lit);
    }
    return vec3(lit);
}
