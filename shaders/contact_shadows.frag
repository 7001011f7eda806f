// The host's screen-space contact shadows (issue 30; host_shared/contact_shadows_shared.h says
// why, docs/contact-shadows.md shows where it helps and where it fails). One full-screen pass
// after the camera pre-pass: per pixel 1 (nothing found) or 0 (an occluder within the ray), which
// the main pass combines with the technique's term by minimum.
//
// The method, in the family of Bend Studio's and Unreal's screen-space shadows, here in world
// units: the pixel's world position P comes from the camera depth; the ray runs from P (lifted
// one pixel footprint along the surface normal, itself taken from the depth buffer) towards the
// light for `length` world units (at most to a point or spot light's position) in `steps` equal
// steps, each sample offset backwards by jitter * a per-pixel noise in [0, 1) of a step so that
// the steps' banding turns into noise. Each sample is projected into the camera; where the depth
// buffer's surface there lies in front of the sample by more than a bias and less than
// `thickness`, the sample is inside something the camera sees: occluded. A sample outside the
// view or behind the camera ends the march lit (the depth buffer knows nothing there).
#include "common.glsl"
#include "host_shared/contact_shadows_shared.h"

layout(location = 0) out vec4 outContact;   // r: 1 lit, 0 occluded (an R8 target)

layout(binding = kContactDepthUnit) uniform sampler2D uCameraDepth;
layout(location = SHADOWLAB_CONTACT_INVERSE_VP_LOCATION) uniform mat4 uInverseViewProjection;
layout(location = SHADOWLAB_CONTACT_PARAMS_LOCATION) uniform vec4 uContact;   // length, thickness, steps, jitter

bool perspective() { return uProjection[2][3] != 0.0; }

// View depth (positive, world units) of a window-space depth d in [0, 1].
float viewDepthOf(float d) {
    float ndc = d * 2.0 - 1.0;
    return perspective() ? uProjection[3][2] / (ndc + uProjection[2][2]) : (uProjection[3][2] - ndc) / uProjection[2][2];
}

// The world size of one pixel at view depth z.
float pixelFootprint(float z) {
    float perUnit = 2.0 / (uProjection[1][1] * uViewport.y);
    return perspective() ? z * perUnit : perUnit;
}

vec3 worldAt(ivec2 pixel, float d) {
    vec2 ndc = (vec2(pixel) + 0.5) * uViewport.zw * 2.0 - 1.0;
    vec4 p = uInverseViewProjection * vec4(ndc, d * 2.0 - 1.0, 1.0);
    return p.xyz / p.w;
}

// The neighbour on the side (+1 or -1 along `axis`) whose depth is nearer the centre's, so that
// the normal across a silhouette is taken from the pixel's own surface.
vec3 nearerNeighbour(ivec2 pixel, ivec2 axis, float d, vec3 p) {
    ivec2 size = textureSize(uCameraDepth, 0);
    ivec2 a = clamp(pixel + axis, ivec2(0), size - 1), b = clamp(pixel - axis, ivec2(0), size - 1);
    float da = texelFetch(uCameraDepth, a, 0).r, db = texelFetch(uCameraDepth, b, 0).r;
    bool useA = abs(da - d) <= abs(db - d);
    vec3 q = worldAt(useA ? a : b, useA ? da : db);
    return useA ? q - p : p - q;
}

// Interleaved gradient noise (Jimenez 2014): well spread over a few neighbouring pixels, fixed
// per pixel (the same every frame: renders are reproducible).
float gradientNoise(vec2 pixel) { return fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715)))); }

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float d = texelFetch(uCameraDepth, pixel, 0).r;
    outContact = vec4(1.0);
    if (d >= 1.0) return;   // background
    vec3 p = worldAt(pixel, d);
    vec3 n = normalize(cross(nearerNeighbour(pixel, ivec2(1, 0), d, p), nearerNeighbour(pixel, ivec2(0, 1), d, p)));
    if (dot(n, uCameraPosition.xyz - p) < 0.0) n = -n;
    vec3 toLight = directionToLight(p);
    if (dot(n, toLight) <= 0.0) return;   // faces away from the light: unlit already, not ours to judge
    float rayLength = uContact.x;
    if (lightType() != LIGHT_DIRECTIONAL) rayLength = min(rayLength, distance(uLightPosition.xyz, p));
    int steps = clamp(int(uContact.z), 1, SHADOWLAB_CONTACT_MAX_STEPS);
    float stepLength = rayLength / float(steps);
    float jitter = uContact.w * gradientNoise(gl_FragCoord.xy);
    vec3 origin = p + n * pixelFootprint(viewDepthOf(d));
    // Clip coordinates are linear in the world position: the samples' are stepped, not projected.
    vec4 clipOrigin = uViewProjection * vec4(origin, 1.0);
    vec4 clipStep = uViewProjection * vec4(toLight * stepLength, 0.0);
    for (int i = 0; i < steps; ++i) {
        vec4 clip = clipOrigin + clipStep * (float(i) + 1.0 - jitter);
        if (clip.w <= 0.0) return;
        vec3 ndc = clip.xyz / clip.w;
        if (any(greaterThan(abs(ndc), vec3(1.0)))) return;   // outside the view: nothing known
        vec2 screen = (ndc.xy * 0.5 + 0.5) * uViewport.xy;
        if (distance(screen, gl_FragCoord.xy) < kContactStartPixels) continue;
        float sceneDepth = texelFetch(uCameraDepth, ivec2(screen), 0).r;
        if (sceneDepth >= 1.0) continue;   // background there
        float rayZ = perspective() ? clip.w : viewDepthOf(ndc.z * 0.5 + 0.5);
        float behind = rayZ - viewDepthOf(sceneDepth);
        if (behind > kContactBiasPixels * pixelFootprint(rayZ) && behind < uContact.y) {
            outContact = vec4(0.0);
            return;
        }
    }
}
