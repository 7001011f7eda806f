// An object's transform in a scene file: built from translate, rotate and scale, and checked for
// what single precision can use. Its own file so that the sanitizer build compiles it optimised
// (app/CMakeLists.txt): a repeat block builds and checks up to a million of them, which took
// 15 s at -O0 with GLM inlined and 0.3 s in Release.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace shadowlab {

// Scale, then rotate about x, y and z (in that order, fixed axes), then translate.
glm::mat4 objectToWorld(glm::vec3 translate, glm::vec3 rotateRadians, glm::vec3 scale);
// Where a transform stops being usable in single precision: not finite, not invertible (a scale
// that underflows), or the box `local` reaching beyond +-kMaxWorldCoordinate, where squared
// lengths overflow. The problem, or "" when it is usable; the caller names the object (and only
// when one fails: a repeat block checks a million).
std::string transformProblem(const glm::mat4& transform, const Bounds& local);
// World plane (n, d) of a "plane" object: its object-space plane y = 0 with normal +y.
glm::vec4 worldPlane(const glm::mat4& transform);

} // namespace shadowlab
