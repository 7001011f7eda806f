// Planar projection matrix (Blinn 1988), seed 000 eq. 3.1-3.3 generalised to any plane.
// For a plane P = (n, d) (points x with dot(n, x) + d = 0, n towards the light) and a light in
// homogeneous coordinates L (w = 1 for a point or spot light, w = 0 for a directional light, with
// xyz pointing towards the light), M = dot(P, L) I - L P^T maps a point v to where the ray from
// the light through v meets the plane. With P = (0, 1, 0, 0) and L = (lx, ly, lz, 1) it is exactly
// eq. 3.3: rows (ly, -lx, 0, 0), (0, 0, 0, 0), (0, -lz, ly, 0), (0, -1, 0, ly).
// Header-only so the tests can check it against the closed form.
#pragma once

#include <glm/glm.hpp>

namespace planar {

inline glm::mat4 projectionMatrix(const glm::vec4& plane, const glm::vec4& light) {
    // glm::outerProduct(c, r)[col][row] = c[row] * r[col], i.e. the matrix L P^T.
    return glm::mat4(glm::dot(plane, light)) - glm::outerProduct(light, plane);
}

} // namespace planar
