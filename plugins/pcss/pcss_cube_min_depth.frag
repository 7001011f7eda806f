// pcss under a point light: one level of the cube's min-depth mips, each face of the cube as a
// layer of a 2D array (the 2D map's mips are the kit's depth-range mips). Texel x of this level
// holds the minimum of source texels 2x .. 2x + 2 in each direction (3 wide, not 2: with odd
// source sizes the last texel then still covers the leftover row or column; overlapping a
// neighbour only loosens the bound). Level 0 reads the cube's texels at their centres' directions
// (nearest, so each lookup is one texel: a cube has no texelFetch), later levels the previous level
// of the same layer by explicit lod, so the level being written is never read (separate draws,
// with a texture barrier between).
#include "pcss_shared.h"

layout(location = 0) out float outMinDepth;

#include "cube_faces.glsl"

layout(binding = kCubeMinDepthSourceUnit) uniform samplerCube uCubeSource;
layout(binding = kMinDepthSourceUnit) uniform sampler2DArray uArraySource;
// uCubeSourceLevel, uCubeLayer, uCubeFaceSize: PcssCubeMinDepthUniforms (pcss_shared.h).

float sourceTexel(ivec2 texel) {
    if (uCubeSourceLevel < 0) {
        vec2 st = (vec2(texel) + 0.5) / float(uCubeFaceSize) * 2.0 - 1.0;
        return textureLod(uCubeSource, cubeFaceDirection(uCubeLayer, st), 0.0).r;
    }
    return texelFetch(uArraySource, ivec3(texel, uCubeLayer), uCubeSourceLevel).r;
}

void main() {
    int size = uCubeSourceLevel < 0 ? uCubeFaceSize : max(textureSize(uArraySource, 0).x >> uCubeSourceLevel, 1);
    ivec2 last = ivec2(size - 1);
    ivec2 base = ivec2(gl_FragCoord.xy) * 2;
    float nearest = 1.0;
    for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 3; ++x) nearest = min(nearest, sourceTexel(min(base + ivec2(x, y), last)));
    outMinDepth = nearest;
}
