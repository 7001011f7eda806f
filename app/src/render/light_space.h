// Light view/projection fitted around a box of the scene: orthographic for directional lights,
// perspective for spot and point lights (a single map; point lights outside the casters only).
#pragma once

#include "shadowlab/technique.h"

namespace shadowlab {

// `casters` (optional): the map's depth range reaches towards the light until it holds them, so
// casters outside the fitted region still cast into it.
LightSpace fitLightSpaceToPoints(const LightInfo& light, const glm::vec3* points, size_t count,
                                 const Bounds* casters = nullptr);
LightSpace fitLightSpace(const LightInfo& light, const Bounds& bounds, const Bounds* casters = nullptr);
// The corners of the camera frustum between view depths near and far (same order as boxCorners).
void frustumSliceCorners(const CameraInfo& camera, float nearDistance, float farDistance, glm::vec3 corners[8]);
// The 8 corners of a box.
void boxCorners(const Bounds& bounds, glm::vec3 corners[8]);

} // namespace shadowlab
