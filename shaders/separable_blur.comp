// One direction of the moment map's separable blur as a compute pass (kit/moment_map.h with
// blur = compute): the same filter as separable_blur.frag, tap for tap, but each work group loads
// its row (MOMENT_BLUR_AXIS 0) or column (1) tile once into shared memory, with the kernel's apron
// on both sides, and every tap then reads shared memory instead of the texture unit.
//
// Built two ways. Alone, along y (MOMENT_BLUR_AXIS 1): moments in, moments out. Included at the end
// of a technique's moment file (moment_map_passes.glsl defines MOMENT_PASS_COMPUTE), along x: there
// momentsFromDepth() exists, and with uBlurSource = 1 the tile is loaded from the light's depth
// buffer and each depth turned into the technique's moments as it is loaded, so the shadow pass
// renders depth alone and the moment target, its bandwidth and a pass over it disappear.
//
// The filter (as in separable_blur.frag): N taps at offsets x_i = i - (N - 1) / 2 texels, weights
// 1 (box) or exp(-x^2 / (2 sigma^2)) with sigma = N / 6 (Gaussian), normalised by their sum. For
// even N the taps fall on the boundary between two texels, where the fragment pass's bilinear
// lookup averages them with weights 1/2 and 1/2: here (a + b) / 2. Texels beyond the map repeat its
// edge (GL_CLAMP_TO_EDGE). Moments are linear in the weights (seed 000 sec. 3.2.5; Donnelly and
// Lauritzen 2006 and Lauritzen, GPU Gems 3 ch. 8, for VSM; Peters and Klein 2015 for MSM, whose
// quantisation is affine and so commutes with the blur too), so blurring them filters the shadow
// test; the separable form costs 2 N taps per texel instead of N^2.
#include "shadowlab/kit/moment_map_shared.h"   // BlurUniforms, kBlurSourceUnit, kBlurDestinationImageUnit

#ifndef MOMENT_BLUR_AXIS
#define MOMENT_BLUR_AXIS 0
#endif

const int kMaxReach = 15;   // texels on either side the widest kernel (31 taps) reads
#if MOMENT_BLUR_AXIS == 0
// Along x: 256 texels of one row per group (consecutive threads, consecutive texels).
const int kAlong = 256;
const int kAcross = 1;
layout(local_size_x = 256, local_size_y = 1) in;
const ivec2 kAxis = ivec2(1, 0);
#else
// Along y: 64 rows of 4 neighbouring columns per group, so that a load of consecutive threads
// reads neighbouring texels of one row rather than one texel of each of 64 rows.
const int kAlong = 64;
const int kAcross = 4;
layout(local_size_x = 4, local_size_y = 64) in;
const ivec2 kAxis = ivec2(0, 1);
#endif

shared vec4 sTile[(kAlong + 2 * kMaxReach) * kAcross];

#ifdef MOMENT_CUBE
// The cube moment map (kit/cube_moment_map.h): one face per work group layer (z), each blurred as
// an image of its own (the kernel does not cross seams; texels beyond a face's edge repeat it).
// Along x: the six depth layers -> the scratch array; along y: the scratch -> the cube's faces.
layout(binding = kBlurSourceUnit) uniform sampler2DArray uSource;
#if MOMENT_BLUR_AXIS == 0
layout(binding = kBlurDestinationImageUnit) writeonly uniform image2DArray uDestination;
#else
layout(binding = kBlurDestinationImageUnit) writeonly uniform imageCube uDestination;
#endif
ivec2 sourceSize() { return textureSize(uSource, 0).xy; }
vec4 fetchSource(ivec2 texel) { return texelFetch(uSource, ivec3(texel, int(gl_WorkGroupID.z)), 0); }
void storeDestination(ivec2 texel, vec4 value) { imageStore(uDestination, ivec3(texel, int(gl_WorkGroupID.z)), value); }
#else
layout(binding = kBlurSourceUnit) uniform sampler2D uSource;   // moments, or the depth buffer
layout(binding = kBlurDestinationImageUnit) writeonly uniform image2D uDestination;   // format of the map
ivec2 sourceSize() { return textureSize(uSource, 0); }
vec4 fetchSource(ivec2 texel) { return texelFetch(uSource, texel, 0); }
void storeDestination(ivec2 texel, vec4 value) { imageStore(uDestination, texel, value); }
#endif

vec4 loadSource(ivec2 texel) {
#ifdef MOMENT_PASS_COMPUTE
    if (uBlurSource != 0) {
        vec4 moments = momentsFromDepth(fetchSource(texel).r);
        // The fragment path stores the moments in the map before blurring them: round as that
        // RGBA16 (unorm) target would, so both paths blur the same values.
        return uRoundToUnorm16 != 0 ? round(clamp(moments, 0.0, 1.0) * 65535.0) / 65535.0 : moments;
    }
#endif
    return fetchSource(texel);
}

void main() {
    ivec2 size = sourceSize();
    ivec2 origin = ivec2(gl_WorkGroupID.xy * gl_WorkGroupSize.xy);
    // Reach of the kernel: (N - 1) / 2 texels for odd N, N / 2 for even N (the outer taps' far texel).
    int reach = min(uKernelSize / 2, kMaxReach);

    // The tile: the group's texels and `reach` more on either side along the axis, loaded (and,
    // from depth, turned into moments) once, x fastest so that neighbouring threads read neighbours.
    ivec2 box = kAxis * (kAlong + 2 * reach) + (ivec2(1) - kAxis) * kAcross;
    int threads = kAlong * kAcross;
    for (int k = int(gl_LocalInvocationIndex); k < box.x * box.y; k += threads) {
        ivec2 local = ivec2(k % box.x, k / box.x);
        sTile[k] = loadSource(clamp(origin - kAxis * reach + local, ivec2(0), size - 1));
    }
    // The tile's writes visible to the whole group before any reads (barrier() alone does this for
    // shared variables since GLSL 4.30; the explicit memory barrier is for drivers that read it so).
    memoryBarrierShared();
    barrier();

    ivec2 texel = origin + ivec2(gl_LocalInvocationID.xy);
    if (any(greaterThanEqual(texel, size))) return;
    ivec2 centre = ivec2(gl_LocalInvocationID.xy) + kAxis * reach;   // this texel in the tile
    int stride = kAxis.x + kAxis.y * box.x;                         // one texel along the axis
    int centreIndex = centre.y * box.x + centre.x;

    // The loop of separable_blur.frag, with its arithmetic, so that both paths round alike.
    float half_ = 0.5 * float(uKernelSize - 1);
    float sigma = max(float(uKernelSize) / 6.0, 1e-3);
    vec4 sum = vec4(0.0);
    float weightSum = 0.0;
    for (int i = 0; i < uKernelSize; ++i) {
        float x = float(i) - half_;
        float w = uGaussian != 0 ? exp(-0.5 * x * x / (sigma * sigma)) : 1.0;
        int left = int(floor(x));   // x itself for odd N; the texel before the boundary for even N
        vec4 tap = sTile[centreIndex + left * stride];
        if (x != float(left)) tap = (tap + sTile[centreIndex + (left + 1) * stride]) * 0.5;
        sum += w * tap;
        weightSum += w;
    }
    storeDestination(texel, sum / weightSum);
}
