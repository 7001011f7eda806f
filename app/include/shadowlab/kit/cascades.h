// Cascaded shadow maps: the camera frustum cut into slices along the view depth, one map per slice
// (seed 002 sec. 7.1: "a partitioning of the view frustum into subsets and each subset is rendered
// into its own shadow map"; seed 000 sec. 2.2.6 names shadow-map partitioning beside warping).
// Pure maths, no GL: tests/test_cascades.cpp checks it against closed forms. plugins/csm renders
// the maps; docs/cascades.md explains the choices.
//
// Splits, the practical scheme (Zhang, Sun, Xu and Lo 2006, "Parallel-split shadow maps for
// large-scale virtual environments"; GPU Gems 3 ch. 10, eq. 10.1-10.3): with N slices over view
// depths [n, f], split i (0 <= i <= N) is
//     C_i = lambda C_log_i + (1 - lambda) C_uni_i,
//     C_log_i = n (f / n)^(i / N),   C_uni_i = n + (f - n) i / N.
// C_log is the ideal distribution of perspective aliasing: seed 002 eq. 8.4 derives that the
// parameterisation s ~ ln z makes dp/ds constant, and a slice boundary at C_log_i gives every slice
// the same ratio f_i / n_i, so the same error at both of its ends. It crowds the slices near the
// viewer when n is small, so C_uni is blended in (lambda = 1: logarithmic, 0: uniform).
//
// Fitting a slice (directional lights). Every cascade shares one light view anchored at the
// world origin (stableLightView), so a world point's light-space x and y never depend on the
// camera. Two fits of a slice's points in that view:
//   tight       the bounding rectangle of the points (slice corners, or the slice clipped to the
//               scene's bounds); as small as can be, but its size and position follow every
//               camera motion continuously, so the texel grid slides and edges shimmer.
//   stabilised  the bounding sphere of the slice (centre and radius from the slice's shape in view
//               space, so camera translation cannot change the radius by a single bit, and rotation
//               cannot change it at all), padded so snapping stays inside it, and the centre moved
//               to a whole number of texels (Valient 2008, "Stable rendering of cascaded shadow
//               maps", ShaderX6; the o3de / QGIS fix): a world point keeps its place in its texel
//               while the camera moves, at the price of the square around the sphere (about twice
//               the texels of the tight fit).
// Depth always reaches back to the scene's casters on the light's side, so casters outside the
// slice still cast into it.
#pragma once

#include <shadowlab/technique.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "shadowlab/kit/focus.h"

namespace shadowlab::kit {

constexpr int kMaxCascades = 8;

// C_i of the practical split scheme (GPU Gems 3 eq. 10.3), i in [0, count]. C_0 = n and
// C_N = f exactly, whatever rounding says.
inline float practicalSplit(float nearDistance, float farDistance, int i, int count, float lambda) {
    if (i <= 0) return nearDistance;
    if (i >= count) return farDistance;
    const double n = nearDistance, f = farDistance, s = double(i) / double(count);
    const double logarithmic = n * std::pow(f / n, s);
    const double uniform = n + (f - n) * s;
    return float(double(lambda) * logarithmic + (1.0 - double(lambda)) * uniform);
}

// The count + 1 split distances from n to f.
inline std::vector<float> practicalSplits(float nearDistance, float farDistance, int count, float lambda) {
    count = std::clamp(count, 1, kMaxCascades);
    nearDistance = std::max(nearDistance, 1e-4f);
    farDistance = std::max(farDistance, nearDistance * 1.0001f);
    std::vector<float> splits(size_t(count) + 1);
    for (int i = 0; i <= count; ++i) splits[size_t(i)] = practicalSplit(nearDistance, farDistance, i, count, lambda);
    return splits;
}

// The camera frustum between two view depths, as 8 view-space points (boundsCorners' order: bit
// 0 = +x, bit 1 = +y, bit 2 = far). From the inverse projection alone, so camera translation leaves
// them bit for bit the same (what keeps the stabilised radius fixed).
inline std::array<glm::vec3, 8> sliceCornersInView(const CameraInfo& camera, float nearDistance, float farDistance) {
    const glm::mat4 inverseProjection = glm::inverse(camera.projection);
    std::array<glm::vec3, 8> corners;
    for (int i = 0; i < 4; ++i) {
        // The ray through the near-plane corner, scaled to view depth d (view space looks down -z).
        const glm::vec4 p = inverseProjection * glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, -1.0f, 1.0f);
        const glm::vec3 ray = glm::vec3(p) / p.w / std::max(-p.z / p.w, 1e-9f);
        corners[size_t(i)] = ray * nearDistance;
        corners[size_t(i) + 4] = ray * farDistance;
    }
    return corners;
}

inline std::array<glm::vec3, 8> sliceCorners(const CameraInfo& camera, float nearDistance, float farDistance) {
    const glm::mat4 inverseView = glm::inverse(camera.view);
    std::array<glm::vec3, 8> corners = sliceCornersInView(camera, nearDistance, farDistance);
    for (glm::vec3& c : corners) c = glm::vec3(inverseView * glm::vec4(c, 1.0f));
    return corners;
}

// The view depths of the camera frustum clipped to the scene's bounds: where the camera can see
// anything at all (forest: far = 400 m, but the 210 m scene ends sooner). The camera's own range
// where it sees nothing of the scene.
struct DepthRange {
    float nearDistance;
    float farDistance;
};
inline DepthRange visibleDepthRange(const CameraInfo& camera, const Bounds& scene) {
    ConvexBody visible = frustumBody(camera.inverseViewProjection);
    clip(visible, scene);
    if (visible.empty()) return {camera.nearPlane, camera.farPlane};
    float lo = 1e30f, hi = 0.0f;
    for (const glm::vec3& p : visible.vertices()) {
        const float depth = -(camera.view * glm::vec4(p, 1.0f)).z;
        lo = std::min(lo, depth);
        hi = std::max(hi, depth);
    }
    lo = std::clamp(lo, camera.nearPlane, camera.farPlane);
    hi = std::clamp(hi, lo, camera.farPlane);
    if (!(hi > lo * 1.0001f)) return {camera.nearPlane, camera.farPlane};
    return {lo, hi};
}

// The light's view for every cascade of a directional light: the eye at the world origin looking
// along the light, the up vector fixed (as the host's fit chooses it).
inline glm::mat4 stableLightView(const LightInfo& light) {
    const glm::vec3 dir = glm::normalize(light.direction);
    const glm::vec3 up = std::abs(dir.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    return glm::lookAt(glm::vec3(0.0f), dir, up);
}

// The smallest sphere around a frustum slice given in view space: its centre lies on the line
// through the near and far faces' centres where the near and far corners are equally far (clamped
// to the slice), its radius the farthest corner from there.
struct Sphere {
    glm::vec3 centre;
    float radius;
};
inline Sphere sliceSphere(const std::array<glm::vec3, 8>& corners) {
    glm::vec3 nearCentre(0.0f), farCentre(0.0f);
    for (int i = 0; i < 4; ++i) {
        nearCentre += 0.25f * corners[size_t(i)];
        farCentre += 0.25f * corners[size_t(i) + 4];
    }
    float a2 = 0.0f, b2 = 0.0f;   // squared half-diagonals of the near and far faces
    for (int i = 0; i < 4; ++i) {
        a2 = std::max(a2, glm::dot(corners[size_t(i)] - nearCentre, corners[size_t(i)] - nearCentre));
        b2 = std::max(b2, glm::dot(corners[size_t(i) + 4] - farCentre, corners[size_t(i) + 4] - farCentre));
    }
    // Centre at nearCentre + t (farCentre - nearCentre): t^2 L^2 + a^2 = (1 - t)^2 L^2 + b^2.
    const float length2 = std::max(glm::dot(farCentre - nearCentre, farCentre - nearCentre), 1e-12f);
    const float t = std::clamp((length2 + b2 - a2) / (2.0f * length2), 0.0f, 1.0f);
    const glm::vec3 centre = nearCentre + t * (farCentre - nearCentre);
    float radius = 0.0f;
    for (const glm::vec3& c : corners) radius = std::max(radius, glm::distance(c, centre));
    return {centre, radius};
}

// One cascade's map: its light space and the view depths it serves.
struct Cascade {
    LightSpace light;
    float viewDistanceBegin = 0.0f;    // the split range it serves (blend band not included)
    float viewDistanceEnd = 0.0f;
    float texelWorldSize = 0.0f;       // world size of one texel (directional lights; 0 otherwise)
};

struct CascadeFitConfig {
    int resolution = 1024;
    bool stabilise = false;
    bool clipToScene = false;          // tight fit of the slice clipped to the scene's bounds
};

namespace cascade_detail {

// Orthographic light space over the light-view rectangle centre +- half and depth from the points' and the
// casters' extent in that view (reaching towards the light to every caster).
inline LightSpace orthographic(const glm::mat4& view, glm::vec2 centre, glm::vec2 half, float zLo, float zHi,
                               const Bounds& casters) {
    glm::vec3 corners[8];
    boundsCorners(casters, corners);
    for (const glm::vec3& c : corners) zHi = std::max(zHi, (view * glm::vec4(c, 1.0f)).z);
    const float margin = 1e-3f * std::max(zHi - zLo, 1e-3f) + 1e-3f;
    LightSpace ls;
    ls.view = view;
    ls.nearPlane = -zHi - margin;
    ls.farPlane = -zLo + margin;
    // glm::ortho(centre - half, centre + half, ...) with the scale from the half-size itself:
    // 2 / (hi - lo) would round differently as the rectangle moves, and the stabilised texel size
    // must not change.
    ls.projection = glm::ortho(-half.x, half.x, -half.y, half.y, ls.nearPlane, ls.farPlane);
    ls.projection[3][0] = -centre.x / half.x;
    ls.projection[3][1] = -centre.y / half.y;
    ls.viewProjection = ls.projection * ls.view;
    ls.perspective = false;
    ls.worldSizeAtUnitDepth = 2.0f * half;
    return ls;
}

} // namespace cascade_detail

// A directional light's cascade over view depths [fitBegin, fitEnd] (the served range widened by
// the blend band at its near end). `scene`: S for clipToScene; `casters`: the casters' bounds.
inline Cascade fitDirectionalCascade(const CameraInfo& camera, const glm::mat4& lightView, float fitBegin, float fitEnd,
                                     const CascadeFitConfig& config, const Bounds& scene, const Bounds& casters) {
    Cascade cascade;
    const int res = std::max(config.resolution, 4);
    if (config.stabilise) {
        const std::array<glm::vec3, 8> inView = sliceCornersInView(camera, fitBegin, fitEnd);
        const Sphere sphere = sliceSphere(inView);
        // Padded by two texels so the snapped square (moved by up to one texel) still holds it:
        // r' (1 - 2 / res) = r.
        // The radius is also rounded up to a step of 2^(1/16) (at most 4.4% of texels lost), so a
        // slice whose range moves a little (fit to the scene or to the depth bounds) keeps its
        // texel size until the range crosses a step.
        const float quantised = float(std::exp2(std::ceil(std::log2(double(std::max(sphere.radius, 1e-6f))) * 16.0) / 16.0));
        const float radius = quantised * float(res) / float(res - 2);
        const float texel = 2.0f * radius / float(res);
        const glm::vec3 centreWorld = glm::vec3(glm::inverse(camera.view) * glm::vec4(sphere.centre, 1.0f));
        const glm::vec3 centre = glm::vec3(lightView * glm::vec4(centreWorld, 1.0f));
        // Whole texels from the light view's origin (fixed in the world).
        const glm::vec2 snapped = glm::floor(glm::vec2(centre) / texel) * texel;
        cascade.light = cascade_detail::orthographic(lightView, snapped, glm::vec2(radius), centre.z - radius,
                                                     centre.z + radius, casters);
        cascade.texelWorldSize = texel;
        return cascade;
    }
    const std::array<glm::vec3, 8> corners = sliceCorners(camera, fitBegin, fitEnd);
    std::vector<glm::vec3> points(corners.begin(), corners.end());
    if (config.clipToScene) {
        ConvexBody slice = focus_detail::hexahedron(corners.data());
        clip(slice, scene);
        if (!slice.empty()) points = slice.vertices();
    }
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : points) {
        const glm::vec3 v = glm::vec3(lightView * glm::vec4(p, 1.0f));
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    // Half a texel of slack each side: the slice's silhouette lands on texels, not between them.
    const glm::vec2 pad = 0.5f * (glm::vec2(hi) - glm::vec2(lo)) / float(res) + 1e-5f;
    cascade.light = cascade_detail::orthographic(lightView, 0.5f * (glm::vec2(lo) + glm::vec2(hi)),
                                                 0.5f * (glm::vec2(hi) - glm::vec2(lo)) + pad, lo.z, hi.z, casters);
    cascade.texelWorldSize = (hi.x - lo.x + 2.0f * pad.x) / float(res);
    return cascade;
}

// A spot light's cascade: the host's perspective fit around the scene (`sceneFit`, P_L V_L)
// cropped to the slice inside the light's frustum (seed 000 eq. 3.9-3.10 per slice; cropWindow
// clamps to the scene fit), snapped with seed 000 sec. 2.2.5's grid when stabilising. The map's
// frame is the scene fit's, so the snapped grid holds still.
inline Cascade fitPerspectiveCascade(const CameraInfo& camera, const LightSpace& sceneFit, float fitBegin, float fitEnd,
                                     const CascadeFitConfig& config, const Bounds& scene) {
    Cascade cascade;
    const std::array<glm::vec3, 8> corners = sliceCorners(camera, fitBegin, fitEnd);
    ConvexBody slice = focus_detail::hexahedron(corners.data());
    if (config.clipToScene) clip(slice, scene);
    clip(slice, frustumBody(glm::inverse(sceneFit.viewProjection)));
    CropWindow window = cropWindow(sceneFit.viewProjection, slice.vertices());
    if (config.stabilise) window = snapToTexels(window, config.resolution);
    cascade.light = cropLightSpace(sceneFit, window);
    return cascade;
}

// The served ranges and fit ranges of `count` cascades over [n, f]: cascade i serves
// [C_i, C_{i+1}] and is fitted over [C_i - band (C_i - C_{i-1}), C_{i+1}], so the band at the far
// end of cascade i - 1, where the two are blended, lies inside cascade i's map too.
struct CascadeRanges {
    std::vector<float> splits;      // count + 1
    std::vector<float> fitBegin;    // count
};
inline CascadeRanges cascadeRanges(float nearDistance, float farDistance, int count, float lambda, float blendBand) {
    CascadeRanges ranges;
    ranges.splits = practicalSplits(nearDistance, farDistance, count, lambda);
    const size_t n = ranges.splits.size() - 1;
    ranges.fitBegin.resize(n);
    for (size_t i = 0; i < n; ++i)
        ranges.fitBegin[i] = i == 0 ? ranges.splits[0]
                                    : ranges.splits[i] - blendBand * (ranges.splits[i] - ranges.splits[i - 1]);
    return ranges;
}

} // namespace shadowlab::kit
