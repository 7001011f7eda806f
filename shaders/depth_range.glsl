// Lookups in the depth-range mips (kit/depth_range_mips.h): the nearest and the farthest depth
// stored anywhere in a region of the shadow map, from at most 2 x 2 texels of one level. Level k
// texel x covers map texels [x 2^(k+1), (x + 1) 2^(k+1)) and a little more; the level is the first
// whose texels span the region's width, so the region overlaps at most two per axis.
// Used to decide a pixel from the bounds alone (adaptive-pcf, pcss, pcf): every tap of a kernel inside
// the region is lit when the region's nearest depth is at or behind the receiver, and shadowed
// when its farthest depth is in front of the receiver's most biased reference.
#ifndef SHADOWLAB_DEPTH_RANGE_GLSL
#define SHADOWLAB_DEPTH_RANGE_GLSL

// (min, max) of the level texels lo .. hi (inclusive) of one level of the mips.
vec2 depthRangeOfLevelTexels(sampler2D mips, int level, ivec2 lo, ivec2 hi) {
    vec2 range = vec2(1.0, 0.0);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            vec2 texel = texelFetch(mips, ivec2(x, y), level).rg;
            range = vec2(min(range.x, texel.x), max(range.y, texel.y));
        }
    return range;
}

// (min, max) map depth within radiusUv of uv; `resolution` is the shadow map's.
vec2 depthRangeIn(sampler2D mips, vec2 uv, vec2 radiusUv, float resolution) {
    float radiusTexels = max(radiusUv.x, radiusUv.y) * resolution;
    int top = textureQueryLevels(mips) - 1;
    int level = clamp(int(ceil(log2(max(radiusTexels, 1.0)))), 0, top);
    // Level sizes from level 0 (the levels halve with floor, as GL's do); llvmpipe (Mesa 22.3)
    // returned the size of the next level down for textureSize with a non-constant lod.
    ivec2 size = max(textureSize(mips, 0) >> level, ivec2(1));
    int span = 2 << level;   // map texels per texel of this level
    ivec2 lo = clamp(ivec2(floor((uv - radiusUv) * resolution)) / span, ivec2(0), size - 1);
    ivec2 hi = clamp(ivec2(floor((uv + radiusUv) * resolution)) / span, ivec2(0), size - 1);
    return depthRangeOfLevelTexels(mips, level, lo, hi);
}

// (min, max) map depth over the map texels lo .. hi (inclusive, per axis; clamped to the map as a
// CLAMP_TO_EDGE lookup clamps them), for a kernel that knows exactly which texels it reads (pcf).
// Level k is the first whose texels (2^(k+1) map texels wide) span the region's width, so it
// overlaps at most two of them per axis; every texel t maps to level texel min(t >> (k + 1),
// size - 1), which holds it (the last texel of an odd level also holds the leftover row/column).
vec2 depthRangeInTexels(sampler2D mips, ivec2 lo, ivec2 hi, float resolution) {
    ivec2 last = ivec2(int(resolution) - 1);
    lo = clamp(lo, ivec2(0), last);
    hi = clamp(hi, ivec2(0), last);
    int width = max(hi.x - lo.x, hi.y - lo.y) + 1;
    int top = textureQueryLevels(mips) - 1;
    int level = clamp(findMSB(width - 1), 0, top);   // 2^(level+1) >= width (findMSB(0) = -1)
    ivec2 size = max(textureSize(mips, 0) >> level, ivec2(1));   // from level 0: see depthRangeIn
    ivec2 a = min(lo >> (level + 1), size - 1);
    ivec2 b = min(hi >> (level + 1), size - 1);
    return depthRangeOfLevelTexels(mips, level, a, b);
}

#endif
