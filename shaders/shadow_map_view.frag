// Host debug views of the reported shadow maps over the last frame's G-buffer:
//   mode 0: texel footprint m (pixels per texel, worst direction; seed 002 eq. 8.1) as a heat map
//           of log2 m: blue m <= 1/16, grey-green 1, red >= 16 (footprintHeatmap's colours)
//   mode 1: the map's texel grid projected on the receivers, over the lit image (every n-th edge
//           in cyan where edges would be under 8 pixels apart)
//   mode 2: which map serves each pixel (cascade colours), over the lit image
//   mode 3: the lit image dimmed, under the focus body B's edges and the maps' volumes
//   mode 4: the lit image a little dimmed, under the filter kernel's footprint
#include "shadow_map_view.glsl"
in vec2 vUv;
out vec4 outColor;

layout(binding = 0) uniform sampler2D uPosition;   // xyz world, w = 1 where drawn
layout(binding = 1) uniform sampler2D uNormal;
layout(binding = 2) uniform sampler2D uLit;        // linear lit colour
layout(location = 0) uniform int uMode;

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// Where the camera ray through `ndc` meets the plane through p with normal n.
bool rayOnPlane(vec2 ndc, vec3 p, vec3 n, out vec3 hit) {
    vec4 a = uCameraInverseViewProjection * vec4(ndc, -1.0, 1.0);
    vec4 b = uCameraInverseViewProjection * vec4(ndc, 1.0, 1.0);
    vec3 origin = a.xyz / a.w, direction = b.xyz / b.w - origin;
    float denominator = dot(n, direction);
    if (abs(denominator) <= 1e-3 * length(direction)) return false;
    hit = origin + direction * (dot(n, p - origin) / denominator);
    return true;
}

float footprint(int map, vec3 p, vec3 n) {
    vec4 clip = uCameraViewProjection * vec4(p, 1.0);
    vec2 ndc = clip.xy / clip.w, pixel = 2.0 / vec2(uMapCountViewport.yz);
    vec3 px, py;
    if (!rayOnPlane(ndc + vec2(pixel.x, 0.0), p, n, px) || !rayOnPlane(ndc + vec2(0.0, pixel.y), p, n, py)) return 0.0;
    vec2 t0 = texelOf(map, p), c1 = texelOf(map, px) - t0, c2 = texelOf(map, py) - t0;
    float a = dot(c1, c1), b = dot(c1, c2), c = dot(c2, c2);
    float lambdaMin = 0.5 * (a + c) - sqrt(0.25 * (a - c) * (a - c) + b * b);
    return lambdaMin <= 1e-12 ? 1e6 : 1.0 / sqrt(lambdaMin);
}

const vec3 kMapColours[8] = vec3[](vec3(0.9, 0.2, 0.2), vec3(0.2, 0.8, 0.2), vec3(0.25, 0.4, 1.0), vec3(0.95, 0.8, 0.1),
                                   vec3(0.8, 0.3, 0.9), vec3(0.1, 0.85, 0.85), vec3(1.0, 0.55, 0.1), vec3(0.6, 0.6, 0.6));

void main() {
    vec4 position = texture(uPosition, vUv);
    vec3 lit = linearToSrgb(texture(uLit, vUv).rgb);
    if (position.w < 0.5) {
        outColor = vec4(uMode == 0 ? vec3(24.0 / 255.0) : uMode == 3 ? lit * 0.5 : lit, 1.0);
        return;
    }
    if (uMode == 3 || uMode == 4) {
        outColor = vec4(lit * (uMode == 3 ? 0.5 : 0.8), 1.0);
        return;
    }
    int map = servingMap(position.xyz);
    if (uMode == 0) {
        vec3 colour = vec3(24.0 / 255.0);
        if (map >= 0) {
            float m = footprint(map, position.xyz, normalize(texture(uNormal, vUv).xyz));
            float t = clamp(log2(max(m, 1e-6)) / 4.0, -1.0, 1.0);
            vec3 low = vec3(40, 80, 230) / 255.0, unit = vec3(120, 190, 120) / 255.0, high = vec3(230, 40, 30) / 255.0;
            colour = m > 0.0 ? (t < 0.0 ? mix(unit, low, -t) : mix(unit, high, t)) : colour;
        }
        outColor = vec4(colour, 1.0);
    } else if (uMode == 1) {
        if (map < 0) {
            outColor = vec4(lit * 0.4, 1.0);
            return;
        }
        // Texel edges where the texel coordinate crosses an integer, one pixel wide on screen.
        // Where edges would come closer than 8 pixels (texels near or under a pixel, which used
        // to wash the view yellow) only every n-th is drawn, n a power of two so the lines of
        // neighbouring n nest, in cyan; the legend says so.
        // Each axis has its own n: on a receiver seen at a grazing angle the texels are squeezed
        // along one direction only.
        vec2 texel = texelOf(map, position.xyz);
        vec2 width = max(fwidth(texel), vec2(1e-6));
        vec2 n = exp2(max(vec2(0.0), ceil(log2(8.0 * width))));
        vec2 distance = abs(fract(texel / n + 0.5) - 0.5) / (width / n);
        float line = 1.0 - clamp(min(distance.x, distance.y), 0.0, 1.0);
        float nearest = distance.x < distance.y ? n.x : n.y;
        vec3 colour = nearest > 1.0 ? vec3(0.1, 0.85, 1.0) : vec3(1.0, 0.85, 0.1);
        outColor = vec4(mix(lit, colour, 0.8 * line), 1.0);
    } else {
        vec3 tint = map < 0 ? vec3(0.0) : kMapColours[map % 8];
        outColor = vec4(map < 0 ? lit * 0.3 : mix(lit, tint, 0.45), 1.0);
    }
}
