// The GPU reference (`--reference-device gpu`, app/src/render/gpu_reference.h): the Embree
// reference's rays (app/src/groundtruth/embree/embree_groundtruth.cpp) traced through the host's
// BVH with shaders/ray_trace.glsl, one invocation per G-buffer texel. Hard: one ray to the light's
// centre. Soft: all N strata of the reference's jittered grid in index order (uniform, never
// adaptive), the jitter from ray_trace.glsl's hash instead of the reference's SplitMix64, so the
// same estimator with other random numbers. Also the reference's per-pixel sampling error: the
// collapsed-strata standard error (adjacent pairs along rows and along columns, the smaller),
// accumulated while tracing. Out: rgb visibility, a = sqrt(2/pi) x that standard error (soft).
#include "ray_trace.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 4) uniform sampler2D uRefPositions;   // xyz world, w = 1 where drawn
layout(binding = 5) uniform sampler2D uRefNormals;     // xyz unit normal
layout(binding = 7, rgba32f) uniform writeonly image2D uRefOut;
layout(location = 0) uniform vec4 uRefLightPosition;   // xyz, w = type
layout(location = 1) uniform vec4 uRefLightDirection;  // xyz travel direction, w = size
layout(location = 2) uniform vec4 uRefParams;          // x ray offset, y cos(spot outer angle)
layout(location = 3) uniform uvec4 uRefOptions;        // x N (1 hard), y seed, z translucency model

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uRefPositions, 0);
    if (any(greaterThanEqual(texel, size))) return;
    rtTranslucencyModel = uRefOptions.z;
    vec4 position = texelFetch(uRefPositions, texel, 0);
    vec3 n = texelFetch(uRefNormals, texel, 0).xyz;
    int type = int(uRefLightPosition.w + 0.5);
    vec3 lightPos = uRefLightPosition.xyz, lightDir = uRefLightDirection.xyz;
    float size_ = uRefLightDirection.w, offset = uRefParams.x;
    vec3 p = position.xyz;
    vec3 toLight = type == 0 ? -lightDir : (length(lightPos - p) > 0.0 ? normalize(lightPos - p) : -lightDir);
    // groundtruth.h facesLight: drawn, finite, facing the light, inside a spot's cone.
    if (position.w == 0.0 || !finite3(p) || !finite3(n) || dot(n, toLight) <= 0.0 ||
        (type == 1 && dot(-toLight, lightDir) <= uRefParams.y)) {
        imageStore(uRefOut, texel, vec4(0.0));
        return;
    }
    n = normalize(n);
    vec3 facing;
    vec3 origin = rtShadowOrigin(p, n, toLight, offset, facing);
    int count = int(uRefOptions.x);
    vec3 direction;
    float tMax;
    if (count <= 1 || size_ <= 0.0) {
        rtEmitterRay(type, lightPos, lightDir, size_, origin, offset, vec2(0.5), true, direction, tMax);
        imageStore(uRefOut, texel, vec4(rtTransmittance(origin, direction, tMax, offset), 0.0));
        return;
    }
    int nx = max(1, int(sqrt(float(count)) + 1e-4)), ny = count / nx;
    float lastRow[64];   // the previous row's scalar results (nx <= 64 for N <= 4096)
    float previous = 0.0, rows = 0.0, columns = 0.0;
    vec3 sum = vec3(0.0);
    uint pixel = uint(texel.y * size.x + texel.x);
    for (int k = 0; k < count; ++k) {
        vec2 u = rtStratum(k, count, rtRandom2(pixel, uRefOptions.y, uint(k)));
        rtEmitterRay(type, lightPos, lightDir, size_, origin, offset, u, false, direction, tMax);
        vec3 result = dot(direction, facing) > 0.0 ? rtTransmittance(origin, direction, tMax, offset) : vec3(0.0);
        sum += result;
        if (k >= nx * ny) continue;
        float y = (result.r + result.g + result.b) / 3.0;
        int x = k % nx, row = k / nx;
        // Pairs (0, 1), (2, 3), ... and, for an odd count, the last two again (standardError).
        if (x >= 1 && (x % 2 == 1 || (x == nx - 1 && nx % 2 == 1))) rows += (y - previous) * (y - previous);
        if (row >= 1 && (row % 2 == 1 || (row == ny - 1 && ny % 2 == 1)))
            columns += (y - lastRow[x]) * (y - lastRow[x]);
        lastRow[x] = y;
        previous = y;
    }
    vec3 visibility = sum / float(count);
    float variance = nx >= 2 && ny >= 2 ? min(rows, columns) : (nx >= 2 ? rows : columns);
    float mean = (visibility.r + visibility.g + visibility.b) / 3.0;
    variance += float(count - nx * ny) * clamp(mean * (1.0 - mean), 0.0, 0.25);
    float error = sqrt(2.0 / 3.14159265) * sqrt(variance) / float(count);
    imageStore(uRefOut, texel, vec4(visibility, error));
}
