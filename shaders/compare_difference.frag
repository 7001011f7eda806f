// The comparison's "difference" view (app/src/ui/session.cpp): where the shadow terms of two
// techniques differ, on the same camera and light. Unit 0: technique A's visibility target
// (copied before B ran), unit 1: B's. Alpha is the host's compared-pixel mask.
//   orange: A darker than B, blue: B darker than A, strength sqrt(|difference|) so a pixel of acne
//   shows; equal pixels show B's shadow term dimmed, so the scene stays readable.
in vec2 vUv;
out vec4 outColor;

layout(binding = 0) uniform sampler2D uVisibilityA;
layout(binding = 1) uniform sampler2D uVisibilityB;

void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec4 a = texelFetch(uVisibilityA, texel, 0);
    vec4 b = texelFetch(uVisibilityB, texel, 0);
    if (a.a < 0.5 && b.a < 0.5) {
        outColor = vec4(0.05, 0.05, 0.15, 1.0);   // background: not compared
        return;
    }
    float va = dot(clamp(a.rgb, 0.0, 1.0), vec3(1.0 / 3.0));
    float vb = dot(clamp(b.rgb, 0.0, 1.0), vec3(1.0 / 3.0));
    float d = va - vb;
    vec3 base = vec3(0.15 + 0.3 * vb);
    vec3 hue = d < 0.0 ? vec3(1.0, 0.55, 0.0) : vec3(0.2, 0.55, 1.0);
    outColor = vec4(mix(base, hue, sqrt(min(abs(d), 1.0))), 1.0);
}
