// Host present pass: turns a host image into what is shown or saved.
//   mode 0: lit colour, linear -> sRGB
//   mode 1: visibility (shadow term) as grey, masked pixels dark blue
//   mode 2: depth-like image (debug image of a technique), normalised by its range
//   mode 3: colour image as is (already display-referred, e.g. the error heatmap)
//   mode 4: moments / arbitrary float image, first two channels
in vec2 vUv;
out vec4 outColor;

layout(binding = 0) uniform sampler2D uImage;
layout(location = 0) uniform int uMode;
layout(location = 1) uniform vec2 uRange;   // mode 2: values mapped from [x, y] to [0, 1]

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    vec4 texel = texture(uImage, vUv);
    if (uMode == 0) {
        outColor = vec4(linearToSrgb(texel.rgb), 1.0);
    } else if (uMode == 1) {
        outColor = texel.a > 0.5 ? vec4(linearToSrgb(texel.rgb), 1.0) : vec4(0.05, 0.05, 0.15, 1.0);
    } else if (uMode == 2) {
        float v = clamp((texel.r - uRange.x) / max(uRange.y - uRange.x, 1e-6), 0.0, 1.0);
        outColor = vec4(vec3(v), 1.0);
    } else if (uMode == 3) {
        outColor = vec4(texel.rgb, 1.0);
    } else {
        outColor = vec4(clamp(texel.rg, 0.0, 1.0), 0.0, 1.0);
    }
}
