// Planar shadows, main-pass side: the mask drawn in this pixel (1 lit, 0 shadowed).
layout(binding = 4) uniform sampler2D uPlanarMask;

vec3 shadowTerm(ShadowInput s) {
    return vec3(texelFetch(uPlanarMask, ivec2(s.fragCoord), 0).r);
}
