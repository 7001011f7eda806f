// raytraced: one invocation per pixel of the host's camera pre-pass traces N shadow rays
// (shaders/ray_trace.glsl) and writes the visible fraction of the light, rgb (coloured casters
// under the physical model), into the screen-space visibility image that raytraced.glsl reads.
// N = 1: one ray to the light's centre (hard). N > 1: a jittered stratified set over the emitter,
// as the Embree reference's soft mode, jittered anew every frame by FrameContext::randomSeed.
// Temporal (weight > 0): blended with the previous frame's image at the point's reprojected
// pixel (previousViewProjection), unless that pixel held another surface (view depth differs).
#include "shadowlab/frame_block.h"
#include "raytraced_shared.h"
#ifdef RT_WITH_COUNTERS
#define RT_COUNTERS
#endif
#include "ray_trace.glsl"
#include "raytraced_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kPrepassPositionUnit) uniform sampler2D uPrepassPosition;
layout(binding = kPrepassNormalUnit) uniform sampler2D uPrepassNormal;
layout(binding = kHistoryUnit) uniform sampler2D uHistory;
layout(binding = kVisibilityImage, rgba16f) uniform writeonly image2D uVisibility;

#ifdef RT_WITH_COUNTERS
layout(binding = kHeatImage, rgba8) uniform writeonly image2D uHeat;
layout(std430, binding = RT_COUNTER_BINDING) buffer RtCounterTotals { uint uTotals[8]; };
shared uint sTotals[4];

// 64-bit sums in lo/hi pairs: the adder whose add wraps the low word carries into the high one.
void addTotal(int i, uint value) {
    if (value == 0u) return;
    uint old = atomicAdd(uTotals[2 * i], value);
    if (old + value < old) atomicAdd(uTotals[2 * i + 1], 1u);
}

// Blue (cheap) to red (costly), log scale up to 1024 node visits and triangle tests per ray.
vec3 heat(float x) {
    x = clamp(x, 0.0, 1.0);
    return clamp(vec3(1.5 - abs(4.0 * x - vec3(3.0, 2.0, 1.0))), 0.0, 1.0);
}
#endif

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(uPrepassPosition, 0);
#ifdef RT_WITH_COUNTERS
    if (gl_LocalInvocationIndex < 4u) sTotals[gl_LocalInvocationIndex] = 0u;
    barrier();
#endif
    if (all(lessThan(texel, size))) {
        vec4 position = texelFetch(uPrepassPosition, texel, 0);
        vec3 visibility = vec3(0.0);
        float depth = 0.0;
        uint rays = 0u;
        if (position.w > 0.5) {
            vec3 n = normalize(texelFetch(uPrepassNormal, texel, 0).xyz);
            visibility = traceRays(position.xyz, n, uint(texel.y * size.x + texel.x), rays);
            depth = (uViewProjection * vec4(position.xyz, 1.0)).w;
            if (uRtOptions.z != 0u && uRtParams.z > 0.0) {
                vec4 clip = uRtPreviousViewProjection * vec4(position.xyz, 1.0);
                if (clip.w > 0.0) {
                    ivec2 previous = ivec2(floor((clip.xy / clip.w * 0.5 + 0.5) * vec2(size)));
                    if (all(greaterThanEqual(previous, ivec2(0))) && all(lessThan(previous, size))) {
                        vec4 history = texelFetch(uHistory, previous, 0);
                        // The same surface: its view depth then (stored) matches the point's now.
                        if (history.a > 0.0 && abs(history.a - clip.w) <= 0.02 * clip.w)
                            visibility = mix(visibility, history.rgb, uRtParams.z);
                    }
                }
            }
        }
        imageStore(uVisibility, texel, vec4(visibility, depth));
#ifdef RT_WITH_COUNTERS
        float cost = rays > 0u ? float(rtNodeVisits + rtTriangleTests) / float(rays) : 0.0;
        imageStore(uHeat, texel, vec4(position.w > 0.5 ? heat(log2(1.0 + cost) / 10.0) : vec3(0.0), 1.0));
        atomicAdd(sTotals[0], rays);
        atomicAdd(sTotals[1], rtNodeVisits);
        atomicAdd(sTotals[2], rtTriangleTests);
        atomicAdd(sTotals[3], rays > 0u ? 1u : 0u);
#endif
    }
#ifdef RT_WITH_COUNTERS
    barrier();
    if (gl_LocalInvocationIndex < 4u) addTotal(int(gl_LocalInvocationIndex), sTotals[gl_LocalInvocationIndex]);
#endif
}
