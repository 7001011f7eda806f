// The perspective shadow map's light space (Stamminger and Drettakis 2002; seed 002 ch. 7),
// without GL so that tests can check it (tests/test_psm.cpp). The shadow map is built in the
// camera's post-perspective space PP = P' V': there the view frustum is the unit cube, so texels
// spread evenly over the screen rather than over the world (Fig. 7.4).
//
// Post-perspective z (sec. 7.2.1): GL's projection row 3 gives z_clip = (f+n)/(n-f) z + 2fn/(n-f)
// and w = -z, so z_pp = z_clip / w = f/(f-n) [(f+n)/f + 2n/z], eq. 7.1 as the seed prints it
// (z < 0 in front of the eye: z_pp(-n) = -1, z_pp(-f) = 1), and for f -> infinity
// z_pp = 1 + 2n/z (eq. 7.2). Table 7.1 (n = 1, f = inf), re-derived since the extracted table
// is empty: z = -1 -> -1, -2 -> 0, -4 -> 0.5, -10 -> 0.8, -100 -> 0.98: half of the post-
// perspective range goes to the first unit in front of the near plane, so n decides everything.
// Here n is pushed as far as it goes, by geometry ("later geometrical methods", sec. 7.2.1) rather
// than the original depth read-back: to the nearest receiver the camera can see
// (nearestReceiverDepth: the nearest point of any receiver's bounds inside the view frustum),
// and B is built for the view from there on (receiverCamera), so the empty air between the
// camera and the first receiver gets no texels. Casters in that air still shadow what lies
// beyond: they are in the extrusion of the shortened view towards the light.
//
// Shadows from behind (sec. 7.2.2): points behind the camera plane change their order in PP, so
// the camera is moved back virtually by `moveBack` until every point of B is in front of its
// near plane; casters outside B cannot shadow anything visible, and the depth pass clips them at
// the virtual camera plane (clipPlane) so that no triangle wraps through infinity. The move-back
// weakens the warp (infinite move-back = a uniform map) and jumps when B's extent changes: the
// discontinuity the seed warns of.
//
// Light types (sec. 7.2.3, Fig. 7.8): the light's homogeneous position L (directional lights:
// (-direction, 0)) becomes PP L. w > 0: a point light on the near side; w ~ 0: a directional light
// (a light parallel to the near plane, e.g. straight above a level camera); w < 0: an "inverted"
// point light (light from behind the viewer), whose rays converge on PP L: along each of them the
// depth order is reversed (the occluder lies farther from PP L than the receiver, because its
// world ray crossed the camera plane), so its light projection stores -depth (z row negated) and
// the ordinary LESS test and comparison then keep and test the point nearest the real light.
#pragma once

#include <shadowlab/technique.h>
#include <shadowlab/kit/focus.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace shadowlab::psm {

enum class PostPerspectiveLight { Point = 0, Directional = 1, InvertedPoint = 2 };

struct PsmSpace {
    glm::mat4 postPerspective{1.0f};   // PP = P' V' (the virtual camera)
    glm::mat4 lightView{1.0f};         // in PP space
    glm::mat4 lightProjection{1.0f};   // z row negated for an inverted light
    glm::mat4 viewProjection{1.0f};    // world -> map clip: lightProjection lightView PP
    glm::vec4 clipPlane{0.0f};         // world plane: >= 0 in front of the virtual camera
    PostPerspectiveLight lightType = PostPerspectiveLight::Point;
    float moveBack = 0.0f;             // world units the virtual camera moved back
    float virtualNear = 0.0f, virtualFar = 0.0f;
};

// Eq. 7.1 (re-derived above): post-perspective z of eye-space z for near n and far f.
inline double postPerspectiveZ(double z, double n, double f) { return f / (f - n) * ((f + n) / f + 2.0 * n / z); }

inline glm::vec3 anyPerpendicular(glm::vec3 v) {
    return std::abs(v.y) < 0.9f * glm::length(v) ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
}

// A receiver's bounds as nearestReceiverDepth clips them: grown by `pad` on every side. A plane's
// bounds are flat (zero height), and the frustum clipped by a flat box has no volume: kit::clip
// drops it as "flattened to nothing", so without the pad a ground plane never counted as a
// receiver and the near plane went past it (to the first box in view, or to the far plane when
// there was none: on `aliasing-plane` every visible pixel then lay outside the map, and on the
// stress scene `perspective-near` the near plane jumped from the ground at 0.12 m to the wall at
// 2.05 m, so the whole nearest shadow fell outside the map and read as lit). Growing the box only
// moves the found depth nearer, which keeps every receiver inside the map.
inline Bounds paddedReceiverBounds(const Bounds& bounds, float pad) {
    return {bounds.min - glm::vec3(pad), bounds.max + glm::vec3(pad)};
}

// The view depth of the nearest point of any receiving object's bounds inside the camera's
// frustum (at least the near plane); the far plane when nothing receives in view. Objects are
// taken in order of their bounds' nearest corner depth, and only those that could still beat the
// best so far are clipped exactly, so a forest costs a few clips a frame. The bounds are padded by
// 1e-5 of the far distance (paddedReceiverBounds: planes have flat bounds), so the depth found can
// be up to about that much nearer than the receiver.
inline float nearestReceiverDepth(const CameraInfo& camera, const ObjectInfo* objects, uint32_t count) {
    const kit::ConvexBody frustum = kit::frustumBody(camera.inverseViewProjection);
    const std::vector<glm::vec4> planes = kit::inwardPlanes(frustum);
    const float pad = 1e-5f * std::max(camera.farPlane, 1.0f);   // the slab stays thicker than kit::clip's tolerance (1e-6 of the body)
    std::vector<std::pair<float, uint32_t>> candidates;
    for (uint32_t i = 0; i < count; ++i) {
        if (!objects[i].receivesShadow()) continue;
        glm::vec3 corners[8];
        kit::boundsCorners(paddedReceiverBounds(objects[i].bounds, pad), corners);
        bool outside = false;
        for (const glm::vec4& plane : planes) {
            bool anyInside = false;
            for (const glm::vec3& c : corners) anyInside = anyInside || glm::dot(glm::vec3(plane), c) + plane.w >= 0.0f;
            if (!anyInside) {
                outside = true;
                break;
            }
        }
        if (outside) continue;
        float nearestCorner = INFINITY;
        for (const glm::vec3& c : corners) nearestCorner = std::min(nearestCorner, -(camera.view * glm::vec4(c, 1.0f)).z);
        candidates.emplace_back(std::max(nearestCorner, camera.nearPlane), i);
    }
    std::sort(candidates.begin(), candidates.end());
    float best = camera.farPlane;
    for (const auto& [lowerBound, index] : candidates) {
        if (lowerBound >= best) break;
        kit::ConvexBody part = frustum;
        kit::clip(part, paddedReceiverBounds(objects[index].bounds, pad));
        for (const glm::vec3& v : part.vertices()) best = std::min(best, -(camera.view * glm::vec4(v, 1.0f)).z);
    }
    return std::clamp(best, camera.nearPlane, camera.farPlane);
}

// The camera with its near plane moved to `nearDistance` (same view, field of view and far plane).
inline CameraInfo receiverCamera(const CameraInfo& camera, float nearDistance) {
    CameraInfo c = camera;
    c.nearPlane = std::min(std::max(nearDistance, camera.nearPlane), camera.farPlane * 0.999f);
    c.projection = glm::perspective(c.fovY, c.aspect, c.nearPlane, c.farPlane);
    c.viewProjection = c.projection * c.view;
    c.inverseViewProjection = glm::inverse(c.viewProjection);
    return c;
}

// PSM's light space for `light` focused on `body` (B's vertices, world), seen by `camera`.
// nullopt where one map cannot hold B: an empty body, or a post-perspective point light inside
// or beside B's image (a light in front of the viewer shining back at it: duelling frusta, where
// PSM needs a cube map, sec. 7.3), or a field of view over `maxHalfAngle`.
inline std::optional<PsmSpace> psmSpace(const CameraInfo& camera, const LightInfo& light, const std::vector<glm::vec3>& body,
                                        float maxHalfAngle = glm::radians(80.0f)) {
    if (body.empty()) return std::nullopt;
    PsmSpace out;
    // Virtual move-back: every point of B at least the camera's near distance in front.
    float nearest = INFINITY, farthest = 0.0f;
    for (const glm::vec3& p : body) nearest = std::min(nearest, -(camera.view * glm::vec4(p, 1.0f)).z);
    out.moveBack = std::max(0.0f, camera.nearPlane - nearest);
    const glm::mat4 virtualView = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -out.moveBack)) * camera.view;
    nearest = INFINITY;
    for (const glm::vec3& p : body) {
        const float depth = -(virtualView * glm::vec4(p, 1.0f)).z;
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    out.virtualNear = std::max(nearest, 1e-4f);
    out.virtualFar = std::max(farthest, out.virtualNear * 1.001f + 1e-4f);
    out.postPerspective = glm::perspective(camera.fovY, camera.aspect, out.virtualNear, out.virtualFar) * virtualView;
    // The virtual camera plane, a hair behind it: the depth pass clips casters there.
    const glm::vec3 forward = -glm::vec3(virtualView[0][2], virtualView[1][2], virtualView[2][2]);
    const glm::vec3 eye = glm::vec3(glm::inverse(virtualView)[3]);
    const float margin = 0.01f * out.virtualNear;
    out.clipPlane = glm::vec4(forward, -glm::dot(forward, eye) + margin);

    std::vector<glm::vec3> image;   // B in PP (NDC), finite: all of it is in front of the camera
    image.reserve(body.size());
    glm::vec3 centre(0.0f);
    for (const glm::vec3& p : body) {
        const glm::vec4 q = out.postPerspective * glm::vec4(p, 1.0f);
        image.push_back(glm::vec3(q) / q.w);
        centre += image.back();
    }
    centre /= float(image.size());
    float radius = 0.0f;
    for (const glm::vec3& q : image) radius = std::max(radius, glm::length(q - centre));
    radius = std::max(radius, 1e-4f);

    const glm::vec4 worldLight = light.type == LightType::Directional ? glm::vec4(-glm::normalize(light.direction), 0.0f)
                                                                      : glm::vec4(light.position, 1.0f);
    const glm::vec4 ppLight = out.postPerspective * worldLight;
    // |w| small against |xyz| (relative to B's size in PP): the light is at (near) infinity.
    if (std::abs(ppLight.w) * 1e3f * radius <= glm::length(glm::vec3(ppLight))) {
        out.lightType = PostPerspectiveLight::Directional;
        const glm::vec3 toLight = glm::normalize(glm::vec3(ppLight) * (ppLight.w < 0.0f ? -1.0f : 1.0f));
        out.lightView = glm::lookAt(centre + 2.0f * radius * toLight, centre, anyPerpendicular(toLight));
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const glm::vec3& q : image) {
            const glm::vec3 v(out.lightView * glm::vec4(q, 1.0f));
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        out.lightProjection = glm::ortho(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z);
    } else {
        const glm::vec3 position = glm::vec3(ppLight) / ppLight.w;
        out.lightType = ppLight.w > 0.0f ? PostPerspectiveLight::Point : PostPerspectiveLight::InvertedPoint;
        const glm::vec3 axis = centre - position;
        if (glm::length(axis) <= 1e-6f) return std::nullopt;
        out.lightView = glm::lookAt(position, centre, anyPerpendicular(axis));
        glm::vec2 lo(INFINITY), hi(-INFINITY);
        float zNear = INFINITY, zFar = 0.0f;
        for (const glm::vec3& q : image) {
            const glm::vec3 v(out.lightView * glm::vec4(q, 1.0f));
            const float depth = -v.z;
            if (depth <= 1e-5f * radius) return std::nullopt;   // B reaches around the light
            const glm::vec2 slope = glm::vec2(v) / depth;
            lo = glm::min(lo, slope);
            hi = glm::max(hi, slope);
            zNear = std::min(zNear, depth);
            zFar = std::max(zFar, depth);
        }
        const float limit = std::tan(maxHalfAngle);
        if (std::max({-lo.x, hi.x, -lo.y, hi.y}) > limit) return std::nullopt;
        zNear *= 0.999f;
        zFar = std::max(zFar * 1.001f, zNear * 1.01f);
        out.lightProjection = glm::frustum(lo.x * zNear, hi.x * zNear, lo.y * zNear, hi.y * zNear, zNear, zFar);
        if (out.lightType == PostPerspectiveLight::InvertedPoint) {
            // Negate z_clip (row 2 of the matrix, glm's column-major [c][2]).
            for (int c = 0; c < 4; ++c) out.lightProjection[c][2] = -out.lightProjection[c][2];
        }
    }
    out.viewProjection = out.lightProjection * out.lightView * out.postPerspective;
    return out;
}

} // namespace shadowlab::psm
