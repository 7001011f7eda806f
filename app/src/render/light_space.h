// Light view/projection fitted around a box of the scene: orthographic for directional lights,
// perspective for spot and point lights (a single map; point lights outside the casters only).
#pragma once

#include "shadowlab/technique.h"

namespace shadowlab {

LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds);
// The 8 corners of a box.
void boxCorners(const Bounds& bounds, glm::vec3 corners[8]);

} // namespace shadowlab
