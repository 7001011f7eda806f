// edtsm's blocks, units and image unit, shared by edtsm.cpp, its compute passes (edtsm.comp) and
// its main pass (edtsm.glsl); see shadowlab/kit/shared.h.
#ifndef EDTSM_SHARED_H
#define EDTSM_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(edtsm)
SHADOWLAB_TEXTURE_UNIT(kEdtSitesUnit, 5)      // nearest sites: xy caster-edge texel, zw background-edge texel
SHADOWLAB_IMAGE_UNIT(kEdtSitesImageUnit, 1)   // the compute passes' output (rgba32f)
// One block per compute pass (the seeds, then one per jump), written when the map is reallocated.
SHADOWLAB_UNIFORM_BLOCK(EdtPassUniforms, 3) {
    int uEdtStep;          // 0: seed pass; k > 0: jump-flooding pass reading neighbours k texels away
    int uEdtPad0;
    float uEdtEdgeDepth;   // world units: a 4-neighbour this much farther from the light makes a depth edge
    float uEdtPad1;
};
// The main pass.
SHADOWLAB_UNIFORM_BLOCK(EdtMainUniforms, 2) {
    float uEdtWidth;       // texels: width of the transition across the rebuilt edge
    float uEdtReach;       // texels: sites farther than this are ignored (the flood's reach)
    float uEdtMainEdgeDepth;   // world units: how far behind the caster-edge site a receiver must lie
    float uEdtMainPad;
};
SHADOWLAB_SHARED_END
#ifndef __cplusplus
const float kEdtNoSite = -1.0e6;   // a coordinate no texel has: no site found (yet)
#endif
#endif
