// area-reference's units, shared by area-reference.cpp, area_accumulate.frag and
// area-reference.glsl (shadowlab/kit/shared.h). The sample's light matrix is the depth map's block.
#ifndef AREA_REFERENCE_SHARED_H
#define AREA_REFERENCE_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(area_reference)
SHADOWLAB_TEXTURE_UNIT(kAverageUnit, 4)        // main pass: average visibility
SHADOWLAB_TEXTURE_UNIT(kPositionsUnit, 4)      // accumulation: the camera pre-pass's world positions
SHADOWLAB_TEXTURE_UNIT(kSampleMapUnit, 5)      // accumulation: this sample's shadow map
SHADOWLAB_SHARED_END
#endif
