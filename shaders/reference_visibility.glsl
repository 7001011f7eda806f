// Ray-traced reference, main-pass side: the traced visibility of this pixel.
layout(binding = 4) uniform sampler2D uReferenceVisibility;

vec3 shadowTerm(ShadowInput s) {
    return texelFetch(uReferenceVisibility, ivec2(s.fragCoord), 0).rgb;
}
