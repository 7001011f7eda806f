#include "scene/object_transform.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "util/strings.h"

namespace shadowlab {
namespace {

bool finiteMatrix(const glm::mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

} // namespace

glm::mat4 objectToWorld(glm::vec3 translate, glm::vec3 rotateRadians, glm::vec3 scale) {
    glm::mat4 transform = glm::translate(glm::mat4(1.0f), translate);
    transform = glm::rotate(transform, rotateRadians.z, glm::vec3(0.0f, 0.0f, 1.0f));
    transform = glm::rotate(transform, rotateRadians.y, glm::vec3(0.0f, 1.0f, 0.0f));
    transform = glm::rotate(transform, rotateRadians.x, glm::vec3(1.0f, 0.0f, 0.0f));
    return glm::scale(transform, scale);
}

std::string transformProblem(const glm::mat4& transform, const Bounds& local) {
    const glm::mat3 linear(transform);
    const float determinant = glm::determinant(linear);
    if (!finiteMatrix(transform) || !std::isnormal(determinant) ||
        !finiteMatrix(glm::mat4(glm::transpose(glm::inverse(linear))))) {
        return "transform is not finite and invertible in single precision (scale " +
               formatNumber(std::cbrt(std::abs(double(determinant)))) + "; check scale, scaleRange and translate)";
    }
    for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 point{(corner & 1) ? local.max.x : local.min.x, (corner & 2) ? local.max.y : local.min.y,
                              (corner & 4) ? local.max.z : local.min.z};
        const glm::vec3 world{transform * glm::vec4(point, 1.0f)};
        for (int axis = 0; axis < 3; ++axis) {
            if (!(std::abs(world[axis]) <= kMaxWorldCoordinate)) {
                return "reaches " + formatNumber(world[axis]) + " in world space, beyond +-" +
                       formatNumber(kMaxWorldCoordinate) + " (the largest coordinate shadowlab handles)";
            }
        }
    }
    return {};
}

glm::vec4 worldPlane(const glm::mat4& transform) {
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    const glm::vec3 normal = glm::normalize(normalMatrix * glm::vec3(0.0f, 1.0f, 0.0f));
    const glm::vec3 origin{transform[3]};
    return {normal, -glm::dot(normal, origin)};
}

} // namespace shadowlab
