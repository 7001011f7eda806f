// The app along a camera and light path (scene/camera_path.h): what the window's path player, the
// tour pages and the path runs (bench/path_run.h) share.
#pragma once

#include <glm/glm.hpp>

#include "app.h"
#include "scene/camera_path.h"

namespace shadowlab {

// The world size of one texel of `technique`'s map seen from `camera` at `viewSize` under `light`:
// its fit, snap and resolution parameters as set now (seed 000 eq. 3.9-3.10 for the frustum crop,
// seed 002 eq. 4.2 for the focus body), 2048 texels over the scene fit for a technique without
// them; 0 for a perspective map (the dolly then uses its default). The built-in dolly moves by a
// fraction of it (the stress suite's shimmer case, a tour step's dolly).
double techniqueTexelWorldSize(App& app, const TechniqueInfo& technique, const SceneCamera& camera, const LightInfo& light,
                               glm::ivec2 viewSize);

// Puts frame `frame` of `path` on the app's camera and light, starting from `camera` and `light`
// (the scene's, with any overrides): what the path does not set keeps their value.
void setPathFrame(App& app, const CameraPath& path, int frame, const SceneCamera& camera, const LightInfo& light);

} // namespace shadowlab
