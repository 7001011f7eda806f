// Orbit and fly cameras (see camera.h). Orbit keeps the target fixed and moves on a sphere; fly
// moves the eye and turns the view.
#include "camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace shadowlab {

void CameraController::reset(const SceneCamera& camera) {
    target_ = camera.target;
    position_ = camera.position;
    const glm::vec3 toEye = camera.position - camera.target;
    distance_ = std::max(glm::length(toEye), 1e-3f);
    const glm::vec3 dir = -toEye / distance_;
    yaw_ = std::atan2(dir.x, -dir.z);
    pitch_ = std::asin(std::clamp(dir.y, -1.0f, 1.0f));
    fovY_ = camera.fovY;
    near_ = camera.nearPlane;
    far_ = camera.farPlane;
}

SceneCamera CameraController::pose() const {
    SceneCamera camera;
    camera.position = mode_ == Mode::Orbit ? target_ - forward() * distance_ : position_;
    camera.target = mode_ == Mode::Orbit ? target_ : position_ + forward() * distance_;
    camera.fovY = fovY_;
    camera.nearPlane = near_;
    camera.farPlane = far_;
    return camera;
}

glm::vec3 CameraController::forward() const {
    return {std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

CameraInfo CameraController::info(glm::ivec2 viewport) const {
    CameraInfo c{};
    c.position = mode_ == Mode::Orbit ? target_ - forward() * distance_ : position_;
    const glm::vec3 lookAt = mode_ == Mode::Orbit ? target_ : position_ + forward();
    c.view = glm::lookAt(c.position, lookAt, glm::vec3(0, 1, 0));
    const float aspect = float(std::max(viewport.x, 1)) / float(std::max(viewport.y, 1));
    // tan(fovY'/2) * aspect = tan(fovY/2) * framingAspect: the same horizontal half-angle.
    const float fovY = framingAspect_ > aspect
                           ? 2.0f * std::atan(std::tan(0.5f * fovY_) * framingAspect_ / aspect)
                           : fovY_;
    c.projection = glm::perspective(fovY, aspect, near_, far_);
    c.viewProjection = c.projection * c.view;
    c.nearPlane = near_;
    c.farPlane = far_;
    c.fovY = fovY;
    c.aspect = aspect;
    c.viewport = viewport;
    completeCameraInfo(c);
    return c;
}

void completeCameraInfo(CameraInfo& camera) {
    camera.inverseViewProjection = glm::inverse(camera.viewProjection);
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 ndc{i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f, 1.0f};
        const glm::vec4 world = camera.inverseViewProjection * ndc;
        camera.frustumCorners[i] = glm::vec3(world) / world.w;
    }
}

void CameraController::setMode(Mode mode) {
    if (mode == mode_) return;
    if (mode == Mode::Fly) {
        position_ = target_ - forward() * distance_;
    } else {
        target_ = position_ + forward() * distance_;
    }
    mode_ = mode;
}

void CameraController::orbit(glm::vec2 d) {
    yaw_ += d.x * 0.005f;
    pitch_ = std::clamp(pitch_ - d.y * 0.005f, -1.5f, 1.5f);
    keepAboveFloor();
}

// eye.y = target.y - sin(pitch) d >= floor + margin bounds sin(pitch) from above; a target
// panned under the floor is lifted onto it first.
void CameraController::keepAboveFloor() {
    if (mode_ != Mode::Orbit || floor_ <= -1e29f) return;
    const float margin = std::max(0.01f, 0.01f * distance_);
    target_.y = std::max(target_.y, floor_);
    const float highest = (target_.y - floor_ - margin) / distance_;
    if (std::sin(pitch_) > highest) pitch_ = std::asin(std::clamp(highest, -1.0f, 1.0f));
}

void CameraController::pan(glm::vec2 d) {
    const glm::vec3 right = glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, forward());
    const float scale = distance_ * 0.0015f;
    target_ += (-right * d.x + up * d.y) * scale;
    keepAboveFloor();
}

void CameraController::zoom(float wheel) {
    distance_ = std::clamp(distance_ * std::pow(0.9f, wheel), 0.05f, far_);
    keepAboveFloor();
}

void CameraController::fly(glm::vec3 move, float seconds) {
    const glm::vec3 right = glm::normalize(glm::cross(forward(), glm::vec3(0, 1, 0)));
    position_ += (right * move.x + glm::vec3(0, 1, 0) * move.y + forward() * move.z) * flySpeed * seconds;
}

void CameraController::look(glm::vec2 d) {
    if (mode_ == Mode::Fly) {
        yaw_ += d.x * 0.003f;
        pitch_ = std::clamp(pitch_ - d.y * 0.003f, -1.5f, 1.5f);
    } else {
        orbit(d);
    }
}

} // namespace shadowlab
