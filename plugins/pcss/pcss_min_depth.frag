// pcss: one level of the min-depth mips. Texel x of this level holds the minimum of source texels
// 2x .. 2x + 2 in each direction (3 wide, not 2: with odd source sizes the last texel then still
// covers the leftover row or column; overlapping a neighbour only loosens the bound). The source
// is the shadow map (level 0) or the previous level of the same texture: fetched with an explicit
// lod, so the level being written is never read (separate draws, with a texture barrier between).
#include "pcss_shared.h"

layout(binding = kMinDepthSourceUnit) uniform sampler2D uSource;

layout(location = 0) out float outMinDepth;

void main() {
    // Level size from level 0 (see nearestDepthIn in pcss.glsl: llvmpipe's textureSize with a
    // non-constant lod was off by a level there).
    ivec2 last = max(textureSize(uSource, 0) >> uSourceLevel, ivec2(1)) - 1;
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    float nearest = 1.0;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x)
            nearest = min(nearest, texelFetch(uSource, min(base + ivec2(x, y), last), uSourceLevel).r);
    outMinDepth = nearest;
}
