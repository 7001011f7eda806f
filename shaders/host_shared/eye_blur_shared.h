// The host's eye-space depth-dependent blur of the shadow term (seed 002 sec. 6.3 and 9.4.2),
// declared once for its C++ (render/renderer.cpp, tests) and GLSL (shaders/main.frag,
// shaders/eye_blur.frag).
//
// Sec. 6.3: a shadow map holds depths, and blurring depths makes no sense for the depth test, so
// the blur is applied after the test: the shadow term of unlit, unicoloured geometry (Fig. 6.5)
// is written to a screen texture, blurred, and used to attenuate the diffuse light in the final
// pass (sec. 9.4.2: "no shadow calculations are necessary" there). A uniform blur removes
// projection aliasing near the viewer but over-blurs distant shadows (Fig. 6.6), so "near the
// viewer the shadow map is blurred more, and with increasing depth the shadows are less and less
// blurred". The seed gives no law for the kernel; here the kernel's width in pixels falls as 1/z,
// like the screen size of a fixed world-space width (eq. 8.1's perspective term):
//
//   w(z) = W z_b / max(z, z_b)     (pixels; W = host.shadow_blur, z_b = host.shadow_blur_depth,
//                                   the camera's near plane when 0)
//
// The kernel is a box w(z) pixels wide, each tap weighted by how much of its pixel lies inside
// [-w/2, w/2] (eyeBlurTapWeight), so a hard edge becomes a linear ramp w pixels wide and the
// width grows smoothly with w; w <= 1 leaves the term exactly as it was. Taps whose view depth
// differs from the centre's by more than kEyeBlurDepthTolerance (relative) are dropped, so shadow
// does not bleed across silhouettes; background pixels (depth 0) are never taps.
#ifndef SHADOWLAB_EYE_BLUR_SHARED_H
#define SHADOWLAB_EYE_BLUR_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(eye_blur)
// The blurred term in the main pass, and the blur's source (a host unit: 0-3 are the host's).
SHADOWLAB_TEXTURE_UNIT(kEyeBlurTermUnit, 3)
SHADOWLAB_SHARED_END

// Host uniform locations (0-15 are the host's; common.glsl uses 0 and 2-5).
#define SHADOWLAB_EYE_BLUR_READ_LOCATION 6    // main pass (blurred variant): 1 read the term, 0 call shadowTerm()
#define SHADOWLAB_LIGHTING_LOCATION 7         // every main pass: 0 phong (sec. 6.2's rules), 1 none (Fig. 6.5)
#define SHADOWLAB_EYE_BLUR_MAX_RADIUS 9       // taps -9..9: enough for w = 16 (half-width 8, plus the partial tap)
#define kEyeBlurDepthTolerance 0.05

// w(z) above, in pixels.
#ifdef __cplusplus
inline float eyeBlurWidth(float width, float referenceDepth, float viewDepth)
#else
float eyeBlurWidth(float width, float referenceDepth, float viewDepth)
#endif
{
    return width * referenceDepth / (viewDepth > referenceDepth ? viewDepth : referenceDepth);
}

// The weight of the tap `offset` pixels from the centre in a box `blurWidth` pixels wide: the
// length of [offset - 1/2, offset + 1/2] inside [-blurWidth/2, blurWidth/2] (the weights sum to
// blurWidth for blurWidth >= 1).
#ifdef __cplusplus
inline float eyeBlurTapWeight(float blurWidth, int offset)
#else
float eyeBlurTapWeight(float blurWidth, int offset)
#endif
{
    float w = 0.5f * blurWidth + 0.5f - float(offset < 0 ? -offset : offset);
    return w < 0.0f ? 0.0f : (w > 1.0f ? 1.0f : w);
}

#endif
