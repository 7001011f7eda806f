// translucent-shadows' units and blocks, shared by translucent-shadows.cpp and its GLSL (see
// shadowlab/kit/shared.h). The opaque depth D_o is on the kit depth map's unit.
#ifndef TRANSLUCENT_SHADOWS_SHARED_H
#define TRANSLUCENT_SHADOWS_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(translucent_shadows)
SHADOWLAB_TEXTURE_UNIT(kTranslucentDepthUnit, 5)   // D_t
SHADOWLAB_TEXTURE_UNIT(kShadowColourUnit, 6)       // C
// Values of the `variant` parameter.
#ifdef __cplusplus
inline constexpr int kVariantOriginal = 0;
inline constexpr int kVariantModified = 1;
#else
const int kVariantOriginal = 0;
const int kVariantModified = 1;
#endif
// The colour pass's block.
SHADOWLAB_UNIFORM_BLOCK(ShadowColourPassUniforms, 2) {
    int uVariant;
    int uShadowColourPad0;
    int uShadowColourPad1;
    int uShadowColourPad2;
};
SHADOWLAB_SHARED_END
#endif
