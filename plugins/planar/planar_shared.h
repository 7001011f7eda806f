// planar's blocks and units, shared by planar.cpp, planar_project.vert, planar_mask.frag and
// planar.glsl (shadowlab/kit/shared.h).
#ifndef PLANAR_SHARED_H
#define PLANAR_SHARED_H
#include "shadowlab/kit/shared.h"
SHADOWLAB_SHARED_BEGIN(planar)
SHADOWLAB_TEXTURE_UNIT(kMaskUnit, 4)        // main pass: the shadow mask
SHADOWLAB_TEXTURE_UNIT(kObjectIdUnit, 5)    // mask pass: the camera pre-pass's object ids
SHADOWLAB_UNIFORM_BLOCK(PlanarUniforms, 2) {
    mat4 uPlanarProjection;   // seed 000 eq. 3.3 generalised (planar_projection.h)
    vec4 uPlane;              // (n, d), n towards the light
    vec4 uLight;              // homogeneous: w = 1 point/spot, 0 directional
    int uClipAntiShadow;
    uint uReceiverId;         // object index + 1 of the receiving plane; 0: no receiver test
    int uPlanarPad0;
    int uPlanarPad1;
};
SHADOWLAB_SHARED_END
#endif
