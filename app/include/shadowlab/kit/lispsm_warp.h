// The LiSPSM matrix (seed 002 ch. 8 and sec. 9.2.1-9.2.6), without GL so that tests can check it
// (tests/test_focus.cpp): a perspective warp P in light space whose projection axis is the view
// direction projected onto the shadow-map plane, so light rays stay parallel (light direction and
// type unchanged) while texels are redistributed towards the viewer.
//
// Frame (sec. 9.2.3, with the axes named for what they do here rather than the seed's swapped y/z):
//   side   s = l x u                          map x (as a look-at along l with up u)
//   up     u = v projected off l, normalised  map y, the warp's axis (v: the view direction, or
//                                             the body vector of sec. 9.2.6)
//   depth  l (the light's travel direction)   map depth
// rooted at the eye (directional lights; a spot light's warp is the same in its post-perspective
// space, spotWarp() below). A point's frame coordinates are (a, b, c) = (s, u, l) .
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
// With sec. 9.2.5's construction taken literally (z1's point lies d along u from z0's), z1 =
// z0 - d (v . u): v . u = sin g when u comes from the view direction v, less when the body vector
// (sec. 9.2.6) turns u away from v.
//
// Sec. 9.2.5's virtual far plane: d, z0 and z1 for n are taken from B_v, the focus body of the view
// frustum cut at a nearer far plane z_f (virtualViewBody()), while P's frustum and the casters still
// span B (the seed: invisible casters in the real frustum must still cast). A smaller z_f means a
// smaller n_opt: a stronger warp, the error equalised between z_n and z_f instead of the real far.
//
// Sec. 9.2.6's body vector: for a directional light the warp axis comes from the sum of the vectors
// from the eye to B's corners (bodyVector()) rather than from the view direction, so that it points
// into the middle of B where B differs from V (the view frustum clipped by the scene). The seed sums
// B "as a point cloud"; its true corners are used here (corners()), since the clipping leaves extra
// vertices on edges that would weigh some parts twice (the failure the seed itself warns of).
//
// Where B reaches behind that nearest point along u (a light from behind the viewer), C moves back
// by that much as well, so the warp stays centred on the viewer (my reading of sec. 9.2.5's
// "next possible parallel plane"; the seed leaves it implicit).
#pragma once

#include <shadowlab/kit/focus.h>
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
    glm::vec3 up{0.0f};         // u, the warp axis in world space
    double n = 0.0;             // C's distance to P's near plane (n_opt times the technique's factor)
    double d = 0.0;             // B's extent along the warp axis
    double dForN = 0.0;         // the extent eq. 8.13 was given: B_v's under a virtual far plane, else d
    double sinGamma = 0.0;      // sine of the angle between the axis' source direction and the light
    double viewAlongUp = 0.0;   // v . u: eye depth gained per unit along u (sin g without the body vector)
};

struct WarpOptions {
    double nFactor = 1.0;       // n = nFactor * n_opt
    // Sec. 9.2.5's virtual frustum: the vertices of B_v, the focus body of the view frustum cut at the
    // virtual far plane z_f, from which eq. 8.13 takes d (and so z1) for n alone; P still spans B.
    // Empty: B itself.
    std::vector<glm::vec3> bodyForN;
    // The direction whose projection off the light is the warp axis u: zero for the view direction
    // (sec. 9.2.3), or sec. 9.2.6's body vector (bodyVector() of B's corners).
    glm::vec3 axisSource{0.0f};
    double minSinGamma = 0.05;
};

// Sec. 9.2.6's body vector: the sum of the vectors from the eye to the body's points, normalised
// (points far from the eye weigh more, as the seed intends). Zero for no points.
inline glm::vec3 bodyVector(const std::vector<glm::vec3>& points, glm::vec3 eye) {
    glm::dvec3 sum(0.0);
    for (const glm::vec3& p : points) sum += glm::dvec3(p - eye);
    const double length = glm::length(sum);
    return length > 0.0 ? glm::vec3(sum / length) : glm::vec3(0.0f);
}

// Where the warp is built (sec. 8.1, 9.2.3): world space for a directional light; for a spot light
// its post-perspective space, where it is a directional light along +z (the general case of sec.
// 8.2.4: "a spot light is transformed into a directional light and can be handled the same way").
struct WarpSpace {
    glm::mat4 toSpace{1.0f};    // world -> the space (homogeneous: divide by w)
    glm::vec3 light{0.0f};      // the light's travel direction there
    glm::vec3 eye{0.0f};        // the frame's origin (the warp's centre line runs through it)
    glm::vec3 view{0.0f};       // the view direction there, at the nearest visible point
    glm::vec3 nearest{0.0f};    // the nearest visible point on the view axis (eye depth z_n'), there
};

inline glm::vec3 toWarpSpace(const WarpSpace& space, glm::vec3 p) {
    const glm::vec4 q = space.toSpace * glm::vec4(p, 1.0f);
    return glm::vec3(q) / q.w;
}

// The warp in `space` (body, bodyForN and axisSource given there). Eq. 8.13 in its general form:
// z0 = -z_n' (the nearest visible point p0 on the view axis), z1 the eye-space z of p0 moved d along
// the warp axis in the space, taken back to world and into the eye's view (Wimmer's general n_opt);
// for a directional light z1 = z0 - d (v . u), the formula at the top of this file.
inline std::optional<Warp> warpInSpace(const WarpSpace& space, const std::vector<glm::vec3>& body, const CameraInfo& camera,
                                       float nearestDepth, const WarpOptions& options) {
    if (body.empty()) return std::nullopt;
    const glm::vec3 l = glm::normalize(space.light), view = glm::normalize(space.view), eye = space.eye;
    const glm::vec3 source = glm::length(options.axisSource) > 0.0f ? glm::normalize(options.axisSource) : view;
    const glm::vec3 across = source - glm::dot(source, l) * l;
    const double sinGamma = glm::length(across);   // |source x l| for unit source and l
    if (sinGamma < options.minSinGamma) return std::nullopt;
    const glm::vec3 u = across / float(sinGamma);
    const glm::vec3 s = glm::cross(l, u);
    Warp w;
    w.sinGamma = sinGamma;
    w.up = u;
    w.viewAlongUp = glm::dot(view, u);
    // Rows s, u, l (glm: m[column][row]), then the origin moved to the eye.
    glm::mat4 frame(1.0f);
    for (int col = 0; col < 3; ++col) {
        frame[col][0] = s[col];
        frame[col][1] = u[col];
        frame[col][2] = l[col];
    }
    frame[3] = glm::vec4(-glm::dot(s, eye), -glm::dot(u, eye), -glm::dot(l, eye), 1.0f);
    w.frame = frame;

    auto extentAlongU = [&](const std::vector<glm::vec3>& points, double& lo, double& hi) {
        lo = 1e300;
        hi = -1e300;
        for (const glm::vec3& p : points) {
            const double b = (frame * glm::vec4(p, 1.0f)).y;
            lo = std::min(lo, b);
            hi = std::max(hi, b);
        }
    };
    double bMin, bMax;
    extentAlongU(body, bMin, bMax);
    std::vector<glm::dvec3> local;
    for (const glm::vec3& p : body) local.push_back(glm::dvec3(frame * glm::vec4(p, 1.0f)));
    w.d = std::max(bMax - bMin, 1e-6);
    w.dForN = w.d;
    if (!options.bodyForN.empty()) {
        double lo, hi;
        extentAlongU(options.bodyForN, lo, hi);
        w.dForN = std::clamp(hi - lo, 1e-6, w.d);   // B_v lies in B: never more than d
    }
    // Eq. 8.13: z0 at p0, z1 at p0 + d u taken back to the eye's view.
    const double zNear = std::max(double(nearestDepth), 1e-4);
    const glm::vec4 p1 = glm::inverse(space.toSpace) * glm::vec4(space.nearest + float(w.dForN) * u, 1.0f);
    if (!(std::abs(p1.w) > 1e-12f)) return std::nullopt;
    const double z0 = -zNear, z1 = (camera.view * glm::vec4(glm::vec3(p1) / p1.w, 1.0f)).z;
    const double nearestAlongU = (frame * glm::vec4(space.nearest, 1.0f)).y;   // b of p0
    w.n = options.nFactor * nOpt(w.dForN, z0, z1) + std::max(0.0, nearestAlongU - bMin);
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
    w.viewProjection = projection * frame * space.toSpace;
    return w;
}

// The warp focused on `body` (B's vertices) for a directional light travelling along
// `lightDirection`, seen from `camera`, with `nearestDepth` the eye depth z_n' of the nearest
// visible point. No warp (nullopt) when it would be uniform anyway or ill-defined: the axis'
// source direction (the view direction or the body vector) and the light (anti)parallel within
// `minSinGamma`, an empty body, or n beyond 100 d (n_opt grows without bound as sin g -> 0:
// duelling frusta, Fig. 8.11).
inline std::optional<Warp> directionalWarp(const std::vector<glm::vec3>& body, glm::vec3 lightDirection,
                                           const CameraInfo& camera, float nearestDepth, const WarpOptions& options) {
    const glm::vec3 view = -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    const WarpSpace space{.toSpace = glm::mat4(1.0f), .light = lightDirection, .eye = camera.position, .view = view,
                          .nearest = camera.position + view * std::max(nearestDepth, 1e-4f)};
    return warpInSpace(space, body, camera, nearestDepth, options);
}

// A spot light's warp (sec. 8.2.4, 9.2.3) from the orientation ray's start `p0` (eye depth
// `nearestDepth`): B and the view taken into the spot's post-perspective space
// `lightViewProjection` (P_L V_L, cropped or not), where its rays run parallel along +z, and warped
// there; the result's viewProjection is the whole W P_L V_L. B must lie in the light's frustum
// (kit::focusBody clips it there). The frame's origin is the eye where `eyeAsOrigin` and the eye is
// in front of the light, else p0 (sec. 9.2.4's C_start from e_ls). No warp where p0 is behind the
// light or the warp is ill-defined.
inline std::optional<Warp> spotWarpFrom(const std::vector<glm::vec3>& body, const glm::mat4& lightViewProjection,
                                        const CameraInfo& camera, glm::vec3 p0, float nearestDepth, bool eyeAsOrigin,
                                        WarpOptions options) {
    const glm::vec3 view = -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    const float zNear = std::max(nearestDepth, 1e-4f);
    const glm::vec4 p0Clip = lightViewProjection * glm::vec4(p0, 1.0f);
    if (!(p0Clip.w > 1e-6f)) return std::nullopt;
    WarpSpace space{.toSpace = lightViewProjection, .light = glm::vec3(0, 0, 1)};
    space.nearest = glm::vec3(p0Clip) / p0Clip.w;
    // The view direction there: the image of a short step along v from p0 (the projection's Jacobian).
    space.view = toWarpSpace(space, p0 + view * (1e-3f * zNear)) - space.nearest;
    const glm::vec4 eyeClip = lightViewProjection * glm::vec4(camera.position, 1.0f);
    space.eye = eyeAsOrigin && eyeClip.w > 1e-6f ? glm::vec3(eyeClip) / eyeClip.w : space.nearest;
    std::vector<glm::vec3> local;
    for (const glm::vec3& p : body) local.push_back(toWarpSpace(space, p));
    for (glm::vec3& p : options.bodyForN) p = toWarpSpace(space, p);
    if (glm::length(options.axisSource) > 0.0f)   // a direction: its image at p0, like v's
        options.axisSource = toWarpSpace(space, p0 + options.axisSource * (1e-3f * zNear)) - space.nearest;
    return warpInSpace(space, local, camera, nearestDepth, options);
}

// A spot light's warp with the ray starting on the view axis at `nearestDepth` (the nearest visible
// point p0) and the eye as the frame's origin where it is in front of the light (both on the view axis).
inline std::optional<Warp> spotWarp(const std::vector<glm::vec3>& body, const glm::mat4& lightViewProjection,
                                    const CameraInfo& camera, float nearestDepth, WarpOptions options) {
    const glm::vec3 view = -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    const glm::vec3 p0 = camera.position + view * std::max(nearestDepth, 1e-4f);
    return spotWarpFrom(body, lightViewProjection, camera, p0, nearestDepth, true, std::move(options));
}

// The view-direction warp with n = nFactor * n_opt from B itself (the recipe up to sec. 9.2.5).
inline std::optional<Warp> directionalWarp(const std::vector<glm::vec3>& body, glm::vec3 lightDirection,
                                           const CameraInfo& camera, float nearestDepth, double nFactor,
                                           double minSinGamma = 0.05) {
    return directionalWarp(body, lightDirection, camera, nearestDepth,
                           WarpOptions{.nFactor = nFactor, .bodyForN = {}, .axisSource = glm::vec3(0.0f), .minSinGamma = minSinGamma});
}

// Sec. 9.2.5's virtual frustum V_v: the camera's frustum cut at eye depth `farDistance` (nothing
// cut when it is at or beyond the camera's own far plane or not positive).
inline kit::ConvexBody virtualViewBody(const CameraInfo& camera, float farDistance) {
    kit::ConvexBody body = kit::frustumBody(camera.inverseViewProjection);
    if (!(farDistance > 0.0f) || farDistance >= camera.farPlane) return body;
    const glm::vec3 view = -glm::normalize(glm::vec3(camera.view[0][2], camera.view[1][2], camera.view[2][2]));
    // Inside: eye depth dot(v, p - eye) <= farDistance.
    kit::clip(body, glm::vec4(-view, glm::dot(view, camera.position) + farDistance));
    return body;
}

// The eye depth (-z in view space) of the nearest point of a point set, at least the camera's near
// plane: z_n' above (V n S's vertices: the seed's LVS for a directional light).
inline float nearestEyeDepth(const CameraInfo& camera, const std::vector<glm::vec3>& points) {
    float nearest = 1e30f;
    for (const glm::vec3& p : points) nearest = std::min(nearest, -(camera.view * glm::vec4(p, 1.0f)).z);
    return std::max(nearest, camera.nearPlane);
}

} // namespace shadowlab::lispsm
