// An n x n box of percentage-closer tests around a shadow-map position (seed 000 sec. 3.2.4): the
// taps of `pcf` (and, by boxPcfOffset, of `csm`'s cascades), and of the stochastic maps of seed 001
// (stochastic-sm on a depth map, cssm2 on a colour map of depths), whose noise only a wide kernel
// averages away (sec. 2.1.2). Tap (i, j)
// sits at u + ((i, j) - (n - 1) / 2) s texels (u = coord.xy * resolution, s the spacing in texels,
// 1 for the colour map) and compares against the
// point's depth less the cone bias, slope * its distance from the centre (light_depth.glsl):
// far taps may see the receiver's own tilted surface closer to the light.
#ifndef SHADOWLAB_BOX_PCF_GLSL
#define SHADOWLAB_BOX_PCF_GLSL

vec2 boxPcfOffset(int i, int j, int kernel) {
    return vec2(i, j) - 0.5 * float(kernel - 1);
}

// Depth map through a comparison sampler: with GL_LINEAR every tap is the texture unit's 2x2
// bilinear comparison ("hardware 2x2 plus an n x n shader kernel", seed 001 Fig. 5.3.C); nearest
// taps are looked up at their texel's centre (as pcf.glsl does, so the rounding of a position on a
// texel edge cannot pick the neighbour). Mean of the n^2 tests.
float boxPcfDepth(sampler2DShadow map, vec3 coord, float resolution, int kernel, float spacing, float slope,
                  bool bilinear) {
    vec2 u = coord.xy * resolution;
    float lit = 0.0;
    for (int j = 0; j < kernel; ++j)
        for (int i = 0; i < kernel; ++i) {
            vec2 offset = boxPcfOffset(i, j, kernel) * spacing;
            vec2 position = bilinear ? u + offset : floor(u + offset) + 0.5;
            lit += texture(map, vec3(position / resolution, coord.z - slope * length(offset)));
        }
    return lit / float(kernel * kernel);
}

// Colour map holding a depth per channel (cssm2): no comparison sampler exists for a colour
// texture, so every tap fetches its texel and compares the three channels in the shader,
// lit_c = [z <= C_c] (seed 001 sec. 2.1.3). Taps past the edge clamp to it. Mean per channel.
vec3 boxPcfChannels(sampler2D map, vec3 coord, int kernel, float slope) {
    ivec2 size = textureSize(map, 0);
    vec2 u = coord.xy * vec2(size);
    vec3 lit = vec3(0.0);
    for (int j = 0; j < kernel; ++j)
        for (int i = 0; i < kernel; ++i) {
            vec2 offset = boxPcfOffset(i, j, kernel);
            ivec2 texel = clamp(ivec2(floor(u + offset)), ivec2(0), size - 1);
            vec3 stored = texelFetch(map, texel, 0).rgb;
            lit += vec3(greaterThanEqual(stored, vec3(coord.z - slope * length(offset))));
        }
    return lit / float(kernel * kernel);
}

#endif
