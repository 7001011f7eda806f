// The host's translucent layers (evaluation frames only), declared once for its C++
// (render/renderer.cpp) and GLSL (shaders/main.frag built with SHADOWLAB_TRANSLUCENT_PEEL).
//
// Seed 001 sec. 5.3.3 (Fig. 5.3.3.A) judges a technique by how it shades translucent surfaces
// behind other translucent ones from the light: the shadow term of a translucent receiver must be
// measured, not only that of the opaque surface behind it. The main pass blends translucent
// surfaces and keeps no G-buffer of them, so evaluation frames peel them from the camera (depth
// peeling, Everitt 2001; seed 001 sec. 2.1.2): layer k is the nearest translucent fragment in
// front of the opaque depth and behind layer k - 1, written with the technique's shadow term,
// world position and normal like the accuracy targets, and traced and compared like them.
#ifndef SHADOWLAB_TRANSLUCENT_LAYERS_SHARED_H
#define SHADOWLAB_TRANSLUCENT_LAYERS_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(translucent_layers)
// Host units (0-3 are the host's; 1 and 2 hold material textures): the previous layer's depth
// (DEPTH_COMPONENT32F, 0 where nothing was peeled yet) and the opaque depth of the main pass.
SHADOWLAB_TEXTURE_UNIT(kPeelPreviousDepthUnit, 0)
SHADOWLAB_TEXTURE_UNIT(kPeelOpaqueDepthUnit, 3)
SHADOWLAB_SHARED_END

// At most this many layers are peeled (eval --translucent-layers).
#define SHADOWLAB_MAX_TRANSLUCENT_LAYERS 8

#endif
