// A camera for the tests that build maps by hand (test_focus.cpp, test_tsm.cpp): looking from `eye`
// at `target` (up +y), 60 degrees vertical, square.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include "camera.h"

namespace shadowlab::test {

inline CameraInfo lookAtCamera(glm::vec3 eye, glm::vec3 target, float nearPlane, float farPlane) {
    CameraInfo c{};
    c.position = eye;
    c.view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
    c.projection = glm::perspective(glm::radians(60.0f), 1.0f, nearPlane, farPlane);
    c.viewProjection = c.projection * c.view;
    c.nearPlane = nearPlane;
    c.farPlane = farPlane;
    c.fovY = glm::radians(60.0f);
    c.aspect = 1.0f;
    completeCameraInfo(c);
    return c;
}

} // namespace shadowlab::test
