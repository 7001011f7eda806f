// The LiSPSM matrix (seed 002 ch. 8 and sec. 9.2.1-9.2.5), without GL so that tests can check it
// (tests/test_focus.cpp): a perspective warp P in light space whose projection axis is the view
// direction projected onto the shadow-map plane, so light rays stay parallel (light direction and
// type unchanged) while texels are redistributed towards the viewer.
//
// Frame (sec. 9.2.3, with the axes named for what they do here rather than the seed's swapped y/z):
//   side   s = l x u                          map x (as a look-at along l with up u)
//   up     u = v projected off l, normalised  map y, the warp's axis (v: the view direction)
//   depth  l (the light's travel direction)   map depth
// rooted at the eye (directional lights). A point's frame coordinates are (a, b, c) = (s, u, l) .
// (p - eye). P's projection centre C lies on the eye's (a, c) line, n behind B's near side b_min
// along u (sec. 9.2.4: C_start on the near plane through e_ls, moved n back); with t = b - b_min + n
// (the distance from C along u, in [n, n + d] over B):
//   x_ndc = (a / t) normalised over B,  y_ndc = (f + n)/(f - n) - 2 f n / ((f - n) t),  z_ndc = (c / t)
//   normalised over B, f = n + d,
// all one projective 4x4 matrix with w = t, so rasterisation stays perspective-correct. Along a
// light ray a and b are fixed, so t is too: depth order along the ray is kept.
//
// n (sec. 8.2, 9.2.5): eq. 8.13, n_opt = d / (sqrt(z1 / z0) - 1). The extracted text reads
// d / sqrt(z1/z0 - 1); re-derived: only with the root over z1/z0 alone does it equal eq. 8.11,
// (z_n + sqrt(z_n (z_n + d sin g))) / sin g, for z0 = -z_n and z1 = -(z_n + d sin g) (multiply by
// sqrt(z1/z0) + 1), as the seed states, and eq. 8.10 for g = 90 degrees. Eq. 8.9 as extracted is
// garbled as well (its last term must be -nf/(z'(f-n)) for eq. 8.7 to be positive; seed audit);
// the error curve is dp/ds = (z - z_n + n)^2 (z_f - z_n) / (z n (n + z_f - z_n)).
// Here z0 = -z_n' with z_n' the eye depth of the nearest visible point (the camera's near plane, or
// the nearest point of V n S when the near plane leaves the scene: the seed's e_world) and
// z1 = z0 - d sin g: the general formula in the directional case, where it reduces to eq. 8.11.
// Where B reaches behind that nearest point along u (a light from behind the viewer), C moves back
// by that much as well, so the warp stays centred on the viewer (my reading of sec. 9.2.5's
// "next possible parallel plane"; the seed leaves it implicit).
#pragma once

#include <shadowlab/technique.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace shadowlab::lispsm {

// Eq. 8.13 (re-derived, see above): z0, z1 signed eye-space z (negative in front of the eye).
inline double nOpt(double d, double z0, double z1) {
    return d / (std::sqrt(z1 / z0) - 1.0);
}

// Eq. 8.11 (directional lights, the view frustum inside the scene): z_n the camera's near distance,
// d B's extent along the warp axis, sinGamma the sine of the view-light angle.
inline double nOptDirectional(double zNear, double d, double sinGamma) {
    return (zNear + std::sqrt(zNear * (zNear + d * sinGamma))) / sinGamma;
}

struct Warp {
    glm::mat4 frame{1.0f};      // world -> (a, b, c, 1)
    glm::mat4 projection{1.0f}; // (a, b, c, 1) -> clip: P with the normalisation folded in
    glm::mat4 viewProjection{1.0f};
    double n = 0.0;             // C's distance to P's near plane (n_opt times the technique's factor)
    double d = 0.0;             // B's extent along the warp axis
    double sinGamma = 0.0;
};

// The warp focused on `body` (B's vertices) for a directional light travelling along
// `lightDirection`, seen from `camera`, with `nearestDepth` the eye depth z_n' of the nearest
// visible point and n = nFactor * n_opt. No warp (nullopt) when it would be uniform anyway or
// ill-defined: view and light (anti)parallel within `minSinGamma`, an empty body, or n beyond
// 100 d (n_opt grows without bound as sin g -> 0: duelling frusta, Fig. 8.11).
inline std::optional<Warp> directionalWarp(const std::vector<glm::vec3>& body, glm::vec3 lightDirection,
                                           const CameraInfo& camera, float nearestDepth, double nFactor,
                                           double minSinGamma = 0.05) {
    if (body.empty()) return std::nullopt;
    const glm::vec3 l = glm::normalize(lightDirection);
    // The camera looks down its view space's -z: that axis in world space.
    const glm::vec3 view = -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    const glm::vec3 across = view - glm::dot(view, l) * l;
    const double sinGamma = glm::length(across);   // |v x l| for unit v and l
    if (sinGamma < minSinGamma) return std::nullopt;
    const glm::vec3 u = across / float(sinGamma);
    const glm::vec3 s = glm::cross(l, u);
    const glm::vec3 eye = camera.position;
    Warp w;
    w.sinGamma = sinGamma;
    // Rows s, u, l (glm: m[column][row]), then the eye moved to the origin.
    glm::mat4 frame(1.0f);
    for (int col = 0; col < 3; ++col) {
        frame[col][0] = s[col];
        frame[col][1] = u[col];
        frame[col][2] = l[col];
    }
    frame[3] = glm::vec4(-glm::dot(s, eye), -glm::dot(u, eye), -glm::dot(l, eye), 1.0f);
    w.frame = frame;

    double bMin = 1e300, bMax = -1e300;
    std::vector<glm::dvec3> local;
    for (const glm::vec3& p : body) {
        const glm::dvec3 q(frame * glm::vec4(p, 1.0f));
        local.push_back(q);
        bMin = std::min(bMin, q.y);
        bMax = std::max(bMax, q.y);
    }
    w.d = std::max(bMax - bMin, 1e-6);
    // Eq. 8.13 with z0 = -z_n', z1 = z0 - d sin g (see the top of this file).
    const double zNear = std::max(double(nearestDepth), 1e-4);
    const double z0 = -zNear, z1 = z0 - w.d * sinGamma;
    const double nearestAlongU = zNear * sinGamma;   // b of the nearest visible point on the view axis
    w.n = nFactor * nOpt(w.d, z0, z1) + std::max(0.0, nearestAlongU - bMin);
    if (!(w.n > 0.0) || !std::isfinite(w.n) || w.n > 100.0 * w.d) return std::nullopt;

    const double n = w.n, f = n + w.d, offset = n - bMin;   // t = b + offset
    double aMin = 1e300, aMax = -1e300, cMin = 1e300, cMax = -1e300;
    for (const glm::dvec3& q : local) {
        const double t = q.y + offset;
        aMin = std::min(aMin, q.x / t);
        aMax = std::max(aMax, q.x / t);
        cMin = std::min(cMin, q.z / t);
        cMax = std::max(cMax, q.z / t);
    }
    const double sa = 2.0 / std::max(aMax - aMin, 1e-12), oa = -(sa * aMin + 1.0);
    const double sc = 2.0 / std::max(cMax - cMin, 1e-12), oc = -(sc * cMin + 1.0);
    const double sy = (f + n) / (f - n), oy = -2.0 * f * n / (f - n);
    // Rows of (a, b, c, 1) -> clip, from x_clip = sa a + oa t, y_clip = sy t + oy, z_clip = sc c + oc t,
    // w_clip = t, with t = b + offset.
    const double rows[4][4] = {{sa, oa, 0.0, oa * offset},
                               {0.0, sy, 0.0, sy * offset + oy},
                               {0.0, oc, sc, oc * offset},
                               {0.0, 1.0, 0.0, offset}};
    glm::mat4 projection(0.0f);
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) projection[col][row] = float(rows[row][col]);
    w.projection = projection;
    w.viewProjection = projection * frame;
    return w;
}

// The eye depth (-z in view space) of the nearest point of a point set, at least the camera's near
// plane: z_n' above (V n S's vertices: the seed's LVS for a directional light).
inline float nearestEyeDepth(const CameraInfo& camera, const std::vector<glm::vec3>& points) {
    float nearest = 1e30f;
    for (const glm::vec3& p : points) nearest = std::min(nearest, -(camera.view * glm::vec4(p, 1.0f)).z);
    return std::max(nearest, camera.nearPlane);
}

} // namespace shadowlab::lispsm
