// The moment map's blocks (kit/moment_map.h), shared by its C++, shaders/moment_shadows.glsl,
// shaders/moment_depth.vert, shaders/separable_blur.frag and shaders/separable_blur.comp.
#ifndef SHADOWLAB_KIT_MOMENT_MAP_SHARED_H
#define SHADOWLAB_KIT_MOMENT_MAP_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(moment_map)
SHADOWLAB_TEXTURE_UNIT(kMomentMapUnit, 4)
SHADOWLAB_TEXTURE_UNIT(kBlurSourceUnit, 4)
SHADOWLAB_TEXTURE_UNIT(kCubeMomentMapUnit, 14)      // point lights: the cube moment map (kit/cube_moment_map.h)
SHADOWLAB_IMAGE_UNIT(kBlurDestinationImageUnit, 0)   // the compute blur's output (image unit 0)
SHADOWLAB_UNIFORM_BLOCK(MomentMapUniforms, 1) {
    mat4 uShadowMatrix;       // light view-projection
    vec4 uLightDepthPlane;    // world point -> linear light depth in [0, 1]
};
SHADOWLAB_UNIFORM_BLOCK(BlurUniforms, 1) {
    vec4 uStep;               // xy: one texel along the blur direction, in uv
    int uKernelSize;          // taps, >= 1
    int uGaussian;            // 0 box, 1 Gaussian
    int uBlurSource;          // compute blur: 0 reads moments, 1 reads the depth buffer and derives them
    int uRoundToUnorm16;      // compute blur from depth: round the derived moments as an RGBA16 target would
};
SHADOWLAB_SHARED_END
#endif
