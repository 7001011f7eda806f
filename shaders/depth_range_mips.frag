// One level of the depth-range mips (kit/depth_range_mips.h). Texel x of this level holds the
// minimum (r) and maximum (g) of source texels 2x and 2x + 1 in each direction, and 2x + 2 too for
// the last texel of a level whose source has an odd size (so the leftover row or column is still
// covered): a level-k texel stands for exactly map texels [x 2^(k+1), (x + 1) 2^(k+1)) of a
// power-of-two map, a tight bound. The source is the depth map (level 0) or the previous level of
// the same texture, fetched with an explicit lod, so the level being written is never read
// (separate draws, with a texture barrier between).
#include "shadowlab/kit/depth_range_mips_shared.h"

layout(binding = kDepthRangeSourceUnit) uniform sampler2D uSource;

layout(location = 0) out vec2 outDepthRange;

void main() {
    // Level size from level 0 (see depthRangeIn in depth_range.glsl: llvmpipe's textureSize with a
    // non-constant lod was off by a level).
    ivec2 last = max(textureSize(uSource, 0) >> uSourceLevel, ivec2(1)) - 1;
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    // 3 wide where this is the last texel and the source has an odd size (2 x + 2 = its last texel).
    ivec2 width = ivec2(base.x + 2 == last.x ? 3 : 2, base.y + 2 == last.y ? 3 : 2);
    vec2 range = vec2(1.0, 0.0);
    for (int y = 0; y < width.y; ++y)
        for (int x = 0; x < width.x; ++x) {
            vec2 texel = texelFetch(uSource, min(base + ivec2(x, y), last), uSourceLevel).rg;
            if (uSourceIsMap != 0) texel.g = texel.r;
            range = vec2(min(range.x, texel.r), max(range.y, texel.g));
        }
    outDepthRange = range;
}
