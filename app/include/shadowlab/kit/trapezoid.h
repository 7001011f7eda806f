// Trapezoidal shadow maps' matrix (Martin and Tan 2004, "Anti-aliasing and continuity with
// trapezoidal shadow maps"; seed 002 sec. 7.3), without GL so that tests can check it
// (tests/test_tsm.cpp). Seed 002 describes TSM in words only (the trapezoid approximating the eye
// frustum in the light's view, maximised in the map, a 2D perspective redistributing the
// resolution) and gives no equation; the steps and the formula for eta below are the paper's,
// derived again here.
//
// In the light's post-perspective space L = P_L V_L (x and y of its NDC; for a directional light
// an orthographic view, for a spot light its perspective, so spot rays are parallel there too):
//   1. the centre line runs from the image n_c of the nearest visible point on the view axis to
//      the image f_c of the farthest (the eye frustum's near and far centres, focused on the
//      visible scene as lispsm focuses B);
//   2. the top line (near) and the base line (far) are perpendicular to it, touching the hull of
//      the focus body's image; lambda is their distance;
//   3. the focus point p (at a fraction `focus` of the visible depth range along the view axis)
//      lies delta' beyond the top line; the projection centre q lies eta before the top line on the
//      centre line, chosen so that p maps to the `line` (80%) line of the map: with t the distance
//      from q, the map's y is s(t) = (f + n)/(f - n) - 2 f n / ((f - n) t), n = eta, f = eta + lambda
//      (s = -1 on the top line, +1 on the base line), and s(eta + delta') = xi' = 2 line - 1 gives
//        eta = lambda delta' (1 - xi') / (lambda (1 + xi') - 2 delta'),
//      the paper's eta = (lambda delta' + lambda delta' xi) / (lambda - 2 delta' - lambda xi) with its
//      sign convention xi = -xi' (-0.6 for the 80% line);
//   4. the trapezoid's sides are the two lines from q touching the hull (the extreme slopes x/t);
//   5. N_T maps the trapezoid onto the square: x/t normalised between the sides, y = s(t); one
//      projective 4x4 with w = t (the paper's T1 R T2 H S1 N S2 composed), so rasterisation stays
//      perspective-correct.
// z: the paper's fix for the polygon-offset problem is to keep depth out of the warp: its depth
// is the light's, interpolated without the trapezoid's w. Here N_T's z row is 0 (z/w = 0) and the
// map stores linear depth along the light, written per fragment (kit::LayeredDepthMap): for a
// directional light exactly the light's post-perspective z up to scale; for a spot light linear
// rather than the perspective's hyperbolic z (my choice: even depth steps, the same order).
// Degenerate cases (view along the light: n_c and f_c closer than a thousandth of the hull, the
// duelling frusta) give no trapezoid: the technique keeps the focused uniform map, as the paper does.
#pragma once

#include <shadowlab/technique.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace shadowlab::tsm {

struct Trapezoid {
    glm::mat4 nt{1.0f};              // light NDC (x, y, z, 1) -> the map's clip space: N_T
    glm::mat4 viewProjection{1.0f};  // N_T P_L V_L: world -> the map's clip space
    double lambda = 0.0;             // distance between top and base lines (light NDC units)
    double deltaPrime = 0.0;         // the focus point's distance beyond the top line
    double eta = 0.0;                // q's distance before the top line
    glm::vec2 corners[4]{};          // top left, top right, base right, base left (light NDC)
};

struct TrapezoidInput {
    std::vector<glm::vec3> body;   // world points whose image the map must hold (the focus body B)
    glm::vec3 nearCentre{0.0f};    // world: nearest visible point on the view axis
    glm::vec3 farCentre{0.0f};     // world: farthest visible point on the view axis
    glm::vec3 focusPoint{0.0f};    // world: the point the `line` line must hold
    double line = 0.8;             // the 80% line (fraction of the map from the top)
};

// The trapezoid around `input` in the post-perspective space of `lightViewProjection`; nullopt in
// the degenerate cases above or where a point is behind a spot light.
inline std::optional<Trapezoid> fitTrapezoid(const glm::mat4& lightViewProjection, const TrapezoidInput& input) {
    auto project = [&](glm::vec3 p, glm::dvec2& out) {
        const glm::vec4 clip = lightViewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 1e-7f)) return false;
        out = glm::dvec2(clip.x / clip.w, clip.y / clip.w);
        return true;
    };
    glm::dvec2 nc, fc, focus;
    std::vector<glm::dvec2> points(input.body.size());
    if (input.body.empty() || !project(input.nearCentre, nc) || !project(input.farCentre, fc) ||
        !project(input.focusPoint, focus))
        return std::nullopt;
    glm::dvec2 lo(1e300), hi(-1e300);
    for (size_t i = 0; i < points.size(); ++i) {
        if (!project(input.body[i], points[i])) return std::nullopt;
        lo = glm::min(lo, points[i]);
        hi = glm::max(hi, points[i]);
    }
    if (glm::length(fc - nc) < 1e-3 * glm::length(hi - lo)) return std::nullopt;   // duelling frusta
    // Step 1-2: the centre line's frame (x across, y along, origin n_c); top and base lines.
    const glm::dvec2 yAxis = glm::normalize(fc - nc), xAxis(yAxis.y, -yAxis.x);
    double top = 1e300, base = -1e300;
    for (const glm::dvec2& p : points) {
        top = std::min(top, glm::dot(p - nc, yAxis));
        base = std::max(base, glm::dot(p - nc, yAxis));
    }
    Trapezoid t;
    t.lambda = base - top;
    if (!(t.lambda > 1e-9)) return std::nullopt;
    // Step 3: eta from the focus point (clamped into the trapezoid's depth: the 80% rule needs
    // delta' below line * lambda, else q goes to infinity and the map is uniform).
    const double xi = 2.0 * std::clamp(input.line, 0.05, 0.95) - 1.0;
    t.deltaPrime = std::clamp(glm::dot(focus - nc, yAxis) - top, 1e-4 * t.lambda, 0.999 * t.lambda);
    const double denominator = t.lambda * (1.0 + xi) - 2.0 * t.deltaPrime;
    t.eta = denominator > 1e-3 * t.lambda ? t.lambda * t.deltaPrime * (1.0 - xi) / denominator : 1e3 * t.lambda;
    t.eta = std::min(t.eta, 1e3 * t.lambda);
    // Step 4: the sides, the extreme slopes x / t seen from q (t = y - top + eta > 0 everywhere).
    const double offset = t.eta - top;   // t = y + offset
    double kMin = 1e300, kMax = -1e300;
    for (const glm::dvec2& p : points) {
        const double k = glm::dot(p - nc, xAxis) / (glm::dot(p - nc, yAxis) + offset);
        kMin = std::min(kMin, k);
        kMax = std::max(kMax, k);
    }
    const double kMid = 0.5 * (kMin + kMax), kHalf = std::max(0.5 * (kMax - kMin), 1e-12);
    const double n = t.eta, f = t.eta + t.lambda;
    const double sy = (f + n) / (f - n), oy = -2.0 * f * n / (f - n);
    // Step 5, rows over (X, Y, Z, 1) of light NDC: x = xAxis . (P - n_c), t = yAxis . (P - n_c) + offset,
    // x_clip = (x - kMid t) / kHalf, y_clip = sy t + oy, z_clip = 0, w_clip = t.
    const double tRow[3] = {yAxis.x, yAxis.y, -glm::dot(nc, yAxis) + offset};
    const double xRow[3] = {xAxis.x, xAxis.y, -glm::dot(nc, xAxis)};
    double rows[4][3];
    for (int c = 0; c < 3; ++c) {
        rows[0][c] = (xRow[c] - kMid * tRow[c]) / kHalf;
        rows[1][c] = sy * tRow[c] + (c == 2 ? oy : 0.0);
        rows[2][c] = 0.0;
        rows[3][c] = tRow[c];
    }
    glm::mat4 nt(0.0f);   // glm: m[column][row]; column 2 (light NDC z) stays 0
    for (int row = 0; row < 4; ++row) {
        nt[0][row] = float(rows[row][0]);
        nt[1][row] = float(rows[row][1]);
        nt[3][row] = float(rows[row][2]);
    }
    t.nt = nt;
    t.viewProjection = nt * lightViewProjection;
    const double tTop = t.eta, tBase = t.eta + t.lambda;
    auto corner = [&](double k, double tt) { return glm::vec2(nc + xAxis * (k * tt) + yAxis * (tt - offset)); };
    t.corners[0] = corner(kMin, tTop);
    t.corners[1] = corner(kMax, tTop);
    t.corners[2] = corner(kMax, tBase);
    t.corners[3] = corner(kMin, tBase);
    return t;
}

} // namespace shadowlab::tsm
