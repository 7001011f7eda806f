// shadow-volumes: bindings shared by the plugin's C++ and GLSL.
#ifndef SHADOW_VOLUMES_SHARED_H
#define SHADOW_VOLUMES_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(shadow_volumes)
SHADOWLAB_TEXTURE_UNIT(kVolumeMaskUnit, 4)     // R8: 1 lit, 0 inside a volume (screen space)
// The uniform location (an integer constant like a unit) of the world distance the volumes start
// beyond each caster.
SHADOWLAB_TEXTURE_UNIT(kPushLocation, 16)
SHADOWLAB_SHARED_END
#endif
