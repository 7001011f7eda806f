// The app along a camera and light path (see app_paths.h).
#include "app_paths.h"

#include <algorithm>

#include "render/light_space.h"
#include "shadowlab/kit/focus.h"

namespace shadowlab {

void setPathFrame(App& app, const CameraPath& path, int frame, const SceneCamera& camera, const LightInfo& light) {
    SceneCamera c = camera;
    LightInfo l = light;
    applyPathState(samplePath(path, path.frameTime(frame)), c, l);
    app.camera().reset(c);
    app.light() = l;
}

double techniqueTexelWorldSize(App& app, const TechniqueInfo& info, const SceneCamera& camera, const LightInfo& light,
                               glm::ivec2 viewSize) {
    const auto& values = app.params().values(info);
    const int resolutionIndex = info.paramIndex("resolution"), fitIndex = info.paramIndex("fit"),
              snapIndex = info.paramIndex("snap");
    const int resolution = resolutionIndex >= 0 ? int(values[size_t(resolutionIndex)]) : 2048;
    kit::FitConfig fit;
    if (fitIndex >= 0) fit.fit = kit::Fit(int(values[size_t(fitIndex)]));
    if (snapIndex >= 0) fit.snap = values[size_t(snapIndex)] != 0.0;
    const Bounds bounds = app.scene().worldBounds(DrawSet::All);
    CameraController controller;
    controller.reset(camera);
    const LightSpace sceneFit = fitLightSpace(light, bounds);
    const auto focused = kit::focusLightSpace(sceneFit, controller.info(viewSize), light, bounds, fit, resolution);
    return focused.light.perspective ? 0.0 : double(focused.light.worldSizeAtUnitDepth.x) / resolution;
}

} // namespace shadowlab
