// Orbit and fly cameras for the interactive view; both start from the scene's camera.
#pragma once

#include "scene/scene.h"
#include "shadowlab/technique.h"

namespace shadowlab {

class CameraController {
public:
    enum class Mode { Orbit, Fly };

    void reset(const SceneCamera& camera);
    // Where the camera is now, as a scene camera (orbit: its target; fly: a point ahead at the
    // orbit distance): reset(pose()) gives the same view. Saved sessions and tour steps use it.
    SceneCamera pose() const;
    CameraInfo info(glm::ivec2 viewport) const;
    // The interactive window: a viewport narrower than `aspect` (a side panel, half of a side by
    // side comparison) widens the vertical field of view so the horizontal extent the scene was
    // framed for stays in view. 0 (the default, headless renders and benchmarks): fovY as given.
    void setFramingAspect(float aspect) { framingAspect_ = aspect; }

    // The orbit camera's eye stays above this height (the receivers' lowest point, set with each
    // scene): orbiting, panning and zooming never take it under the ground to look at the
    // receivers from below. Fly mode is free.
    void setFloor(float y) { floor_ = y; }

    // Input, in pixels of mouse motion and seconds.
    void orbit(glm::vec2 mouseDelta);
    void pan(glm::vec2 mouseDelta);
    void zoom(float wheel);
    void fly(glm::vec3 localMove, float seconds);   // x right, y up, z forward
    void look(glm::vec2 mouseDelta);

    // Switching keeps the current view: fly starts at the orbit eye, orbit around a point ahead.
    void setMode(Mode mode);
    Mode mode() const { return mode_; }
    float flySpeed = 3.0f;

private:
    glm::vec3 forward() const;
    void keepAboveFloor();
    Mode mode_ = Mode::Orbit;
    glm::vec3 target_{0.0f};
    glm::vec3 position_{0.0f, 2.0f, 5.0f};
    float yaw_ = 0.0f;      // radians around +y
    float pitch_ = 0.0f;    // radians, positive looks up
    float distance_ = 5.0f;
    float fovY_ = 0.785f, near_ = 0.1f, far_ = 100.0f;
    float framingAspect_ = 0.0f;
    float floor_ = -1e30f;
};

// Fills the derived fields of a camera whose view and projection are set: inverse
// view-projection and world-space frustum corners.
void completeCameraInfo(CameraInfo& camera);

} // namespace shadowlab
