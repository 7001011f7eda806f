// The passes of the kit's moment map (shadowlab/kit/moment_map.h) that depend on the technique.
// A technique's moment file (e.g. plugins/vsm/vsm_moments.glsl) defines
//     vec4 momentsFromDepth(float depth)   // depth: linear light depth in [0, 1] (moment_shadows.glsl)
// returning its moments in the channels of its map's format, and includes this file last. The kit
// builds that file as:
//   MOMENT_PASS_FRAGMENT  the fragment stage of the colour moment pass (blur = fragment, and moments
//                         that need screen-space derivatives: vsm's eq. 3.16), after moment_depth.vert;
//   MOMENT_PASS_COMPUTE   the first pass of the compute blur: depth buffer -> moments -> blur along x
//                         (separable_blur.comp).
#if defined(MOMENT_PASS_FRAGMENT)
in float vLightDepth;
layout(location = 0) out vec4 outMoments;   // channels beyond the map's format are dropped

void main() {
    outMoments = momentsFromDepth(vLightDepth);
}
#elif defined(MOMENT_PASS_COMPUTE)
#include "separable_blur.comp"
#else
#error "a moment file is built by kit::MomentMap with MOMENT_PASS_FRAGMENT or MOMENT_PASS_COMPUTE"
#endif
