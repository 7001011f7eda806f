// Lookups in the depth-range mips (kit/depth_range_mips.h): the nearest and the farthest depth
// stored anywhere in a region of the shadow map, from at most 2 x 2 texels of one level. Level k
// texel x covers map texels [x 2^(k+1), (x + 1) 2^(k+1)) and a little more; the level is the first
// whose texels span the region's width, so the region overlaps at most two per axis.
// Used to decide a pixel from the bounds alone (adaptive-pcf, pcss): every tap of a kernel inside
// the region is lit when the region's nearest depth is at or behind the receiver, and shadowed
// when its farthest depth is in front of the receiver's most biased reference.
#ifndef SHADOWLAB_DEPTH_RANGE_GLSL
#define SHADOWLAB_DEPTH_RANGE_GLSL

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
    vec2 range = vec2(1.0, 0.0);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            vec2 texel = texelFetch(mips, ivec2(x, y), level).rg;
            range = vec2(min(range.x, texel.x), max(range.y, texel.y));
        }
    return range;
}

#endif
