// The translucent-shadow maps' units and blocks (kit/translucent_maps.h), shared by its C++ and
// GLSL (shaders/translucent_maps.glsl, shaders/translucent_shadow_colour.frag; see
// shadowlab/kit/shared.h). The opaque depth D_o is on the kit depth map's unit.
#ifndef SHADOWLAB_KIT_TRANSLUCENT_MAPS_SHARED_H
#define SHADOWLAB_KIT_TRANSLUCENT_MAPS_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(translucent_maps)
SHADOWLAB_TEXTURE_UNIT(kTranslucentDepthUnit, 5)   // D_t
SHADOWLAB_TEXTURE_UNIT(kShadowColourUnit, 6)       // C
// What a translucent caster multiplies C by (the `variant` parameter's values).
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
