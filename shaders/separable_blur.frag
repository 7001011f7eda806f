// One direction of a separable blur of a moment map (vsm, esm, evsm, msm). Moments are linear in
// the filter weights, so filtering them is filtering the shadow test (seed 000 section 3.2.5: a
// separable filter costs 2 N M^2 instead of N^2 M^2 taps). Run it twice, along x then along y.
//
// A kernel of N taps is centred on the texel: offsets (i - (N - 1) / 2) texels, i = 0..N-1. For
// even N the taps fall between two texels and the bilinear unit averages them, so the footprint
// grows smoothly with N instead of jumping by two texels. Box: equal weights. Gaussian: weights
// exp(-x^2 / (2 sigma^2)) with sigma = N / 6 (the kernel spans +-3 sigma), normalised to sum 1.
in vec2 vUv;
layout(location = 0) out vec4 outMoments;

#include "shadowlab/kit/moment_map_shared.h"   // BlurUniforms: uStep, uKernelSize, uGaussian

layout(binding = kBlurSourceUnit) uniform sampler2D uSource;

void main() {
    float half_ = 0.5 * float(uKernelSize - 1);
    float sigma = max(float(uKernelSize) / 6.0, 1e-3);
    vec4 sum = vec4(0.0);
    float weightSum = 0.0;
    for (int i = 0; i < uKernelSize; ++i) {
        float x = float(i) - half_;
        float w = uGaussian != 0 ? exp(-0.5 * x * x / (sigma * sigma)) : 1.0;
        sum += w * textureLod(uSource, vUv + x * uStep.xy, 0.0);
        weightSum += w;
    }
    outMoments = sum / weightSum;
}
