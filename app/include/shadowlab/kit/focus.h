// Focusing a single shadow map on what the camera can see (seed 002 sec. 4.2 and 9.2.2; seed 000
// sec. 2.2.5 and 3.2.3). Pure maths, no GL: tests/test_focus.cpp checks it against hand-computed
// bodies and the closed form of the crop.
//
// Every technique's map starts from the host's fit around the whole scene (IHost::fitLightSpace,
// P_L V_L). A crop matrix F (seed 000 eq. 3.9-3.10) then narrows it, in x and y only, to the
// light-NDC bounding box of
//   Fit::Frustum    the camera frustum's corners, clamped to the scene fit's NDC (seed 000 3.2.3);
//   Fit::FocusBody  the focus body B = ((V n S) + l) n S n L (seed 002 eq. 4.2): the visible part
//                   of the scene, swept towards the light to the scene's bounds (everything that
//                   can cast into the view), cut to the light's frustum for spot and point lights.
// The map becomes F P_L V_L: depth keeps the scene fit's range, so casters outside the crop's
// rectangle but in front of it still land in the map, and the light's frame stays the scene fit's
// (fixed while scene and light are), which is what lets snap() hold the texel grid still.
//
// This is not IHost::fitLightSpaceToPoints / fitLightSpaceToFrustumSlice: those fit a new light
// space around points (cascades), with a frame that moves with them and no clamp to the scene; a
// frustum reaching beyond the scene (forest: far = 400 m, scene 210 m) would get a map larger
// than the scene fit's. The crop can only shrink the scene fit.
//
// Snapping (seed 000 sec. 2.2.5): under camera translation the crop slides continuously, so the
// texel grid slides over the scene and shadow edges crawl. snap() quantises the crop's size to
// whole texels of a grid anchored to the scene fit's NDC and its offset to whole texels of that
// grid: a fixed world point then keeps its position within its texel.
//
// The convex bodies are small (tens of faces), so special-purpose operations are used, as the
// seed recommends: clip by a plane (Sutherland-Hodgman on every face, the hole closed by one new
// face), hull with a point (faces facing it removed, the hole closed by a fan of triangles) and
// extrusion along a direction (faces facing it moved, the hole closed with quads).
#pragma once

#include <shadowlab/technique.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace shadowlab::kit {

// The `fit` parameter's values (kit::fitParam()).
enum class Fit : int { Scene = 0, Frustum = 1, FocusBody = 2 };

struct FitConfig {
    Fit fit = Fit::Scene;
    bool snap = false;   // texel snapping of the crop (frustum and focus-body fits)
};

// The values of kit::fitParam() and kit::snapParam() at their indices.
inline FitConfig readFit(const ParamValues& params, uint32_t fitIndex, uint32_t snapIndex) {
    return {Fit(std::clamp(params.asInt(fitIndex), 0, 2)), params.asBool(snapIndex)};
}
// The same from a technique's values (kit/params.h) holding SHADOWLAB_FIT_PARAMS.
template <class Values>
FitConfig fitConfig(const Values& values) {
    return {Fit(std::clamp(int(values.fit), 0, 2)), bool(values.snap)};
}

// The 8 corners of a box in CameraInfo::frustumCorners' order: bit 0 = +x, bit 1 = +y, bit 2 = +z.
inline void boundsCorners(const Bounds& box, glm::vec3 corners[8]) {
    for (int i = 0; i < 8; ++i)
        corners[i] = {i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z};
}

// ---------------------------------------------------------------------------------------------
// Convex bodies

// A closed convex polyhedron as its faces: convex polygons, counter-clockwise seen from outside.
// Empty when a clip removed everything.
struct ConvexBody {
    std::vector<std::vector<glm::vec3>> faces;

    bool empty() const { return faces.empty(); }

    // Distinct corners (duplicates within `tolerance` of each other merged).
    std::vector<glm::vec3> vertices(float tolerance = 1e-5f) const {
        std::vector<glm::vec3> unique;
        for (const auto& face : faces)
            for (const glm::vec3& p : face)
                if (std::none_of(unique.begin(), unique.end(),
                                 [&](const glm::vec3& q) { return glm::distance(p, q) <= tolerance; }))
                    unique.push_back(p);
        return unique;
    }

    // The body's true corners: vertices where three faces of independent orientation meet. The
    // operations below leave extra vertices on edges (where a face and a coplanar quad or
    // triangle join); they bound the same body, so fitting may use vertices() as they are.
    std::vector<glm::vec3> corners(float tolerance = 1e-5f) const;
};

namespace focus_detail {

// Newell's normal: robust for any planar polygon; its length is twice the polygon's area.
inline glm::vec3 areaNormal(const std::vector<glm::vec3>& polygon) {
    glm::vec3 n(0.0f);
    for (size_t i = 0; i < polygon.size(); ++i) {
        const glm::vec3& a = polygon[i];
        const glm::vec3& b = polygon[(i + 1) % polygon.size()];
        n += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    return n;
}

inline glm::vec3 centroid(const std::vector<glm::vec3>& points) {
    glm::vec3 c(0.0f);
    for (const glm::vec3& p : points) c += p;
    return points.empty() ? c : c / float(points.size());
}

// The operations' tolerance: a millionth of the body's size (world units), at least 1e-6.
inline float toleranceFor(const ConvexBody& body) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const auto& face : body.faces)
        for (const glm::vec3& p : face) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    return body.empty() ? 1e-6f : std::max(1e-6f * glm::length(hi - lo), 1e-6f);
}

// Drops repeated corners (the last against the first too) and faces left with less than 3.
inline void tidy(std::vector<glm::vec3>& polygon, float tolerance) {
    std::vector<glm::vec3> out;
    for (const glm::vec3& p : polygon)
        if (out.empty() || glm::distance(out.back(), p) > tolerance) out.push_back(p);
    while (out.size() > 1 && glm::distance(out.front(), out.back()) <= tolerance) out.pop_back();
    polygon = out.size() >= 3 ? std::move(out) : std::vector<glm::vec3>{};
}

// Orders points lying in one plane around their centroid, counter-clockwise seen from `normal`.
inline void orderAround(std::vector<glm::vec3>& points, glm::vec3 normal) {
    const glm::vec3 c = centroid(points);
    const glm::vec3 n = glm::normalize(normal);
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, n));
    const glm::vec3 w = glm::cross(n, u);
    std::sort(points.begin(), points.end(), [&](const glm::vec3& a, const glm::vec3& b) {
        return std::atan2(glm::dot(a - c, w), glm::dot(a - c, u)) < std::atan2(glm::dot(b - c, w), glm::dot(b - c, u));
    });
}

// Distance from p to the segment ab.
inline float segmentDistance(glm::vec3 p, glm::vec3 a, glm::vec3 b) {
    const glm::vec3 ab = b - a;
    const float length2 = glm::dot(ab, ab);
    const float t = length2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / length2, 0.0f, 1.0f) : 0.0f;
    return glm::distance(p, a + t * ab);
}

// Whether edge (a, b) of a face is on the outline between the faces that `selected` marks and the
// others: its midpoint lies on an edge of an unselected face. Midpoints rather than matching
// corners, so an edge that a neighbour splits in two (a T-junction left by clipping) still counts.
inline bool onOutline(const ConvexBody& body, const std::vector<bool>& selected, glm::vec3 a, glm::vec3 b,
                      float tolerance) {
    const glm::vec3 mid = 0.5f * (a + b);
    for (size_t f = 0; f < body.faces.size(); ++f) {
        if (selected[f]) continue;
        const auto& face = body.faces[f];
        for (size_t i = 0; i < face.size(); ++i)
            if (segmentDistance(mid, face[i], face[(i + 1) % face.size()]) <= tolerance) return true;
    }
    return false;
}

// Builds a face from 4 corners in cyclic order, turned to face away from `inside`.
inline std::vector<glm::vec3> outwardQuad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 inside) {
    std::vector<glm::vec3> quad{a, b, c, d};
    if (glm::dot(areaNormal(quad), centroid(quad) - inside) < 0.0f) std::reverse(quad.begin(), quad.end());
    return quad;
}

// What hull and extrusion share: the faces `facing` marks are dropped, or with `moveBy` moved by it;
// each of their edges on the outline to the other faces gets the face bridge(a, b).
template <class Bridge>
void replaceFacingFaces(ConvexBody& body, const std::vector<bool>& facing, float tolerance, Bridge bridge,
                        std::optional<glm::vec3> moveBy = std::nullopt) {
    ConvexBody result;
    for (size_t f = 0; f < body.faces.size(); ++f) {
        const auto& face = body.faces[f];
        if (!facing[f]) {
            result.faces.push_back(face);
            continue;
        }
        for (size_t i = 0; i < face.size(); ++i) {
            const glm::vec3 a = face[i], b = face[(i + 1) % face.size()];
            if (onOutline(body, facing, a, b, tolerance)) result.faces.push_back(bridge(a, b));
        }
        if (moveBy) {
            std::vector<glm::vec3> moved;
            for (const glm::vec3& p : face) moved.push_back(p + *moveBy);
            result.faces.push_back(std::move(moved));
        }
    }
    body = std::move(result);
}

// A hexahedron from its 8 corners in boundsCorners() order (a box, or a frustum's corners).
inline ConvexBody hexahedron(const glm::vec3 c[8]) {
    const glm::vec3 inside = 0.125f * (c[0] + c[1] + c[2] + c[3] + c[4] + c[5] + c[6] + c[7]);
    ConvexBody body;
    // For each axis, the face where its bit is 0 and the one where it is 1; the other two bits
    // run 00, 01, 11, 10 around the face.
    for (int axis = 0; axis < 3; ++axis) {
        const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3);
        for (int side = 0; side < 2; ++side) {
            const int base = side << axis;
            body.faces.push_back(outwardQuad(c[base], c[base | u], c[base | u | v], c[base | v], inside));
        }
    }
    return body;
}

} // namespace focus_detail

inline std::vector<glm::vec3> ConvexBody::corners(float tolerance) const {
    std::vector<glm::vec3> normals;
    for (const auto& face : faces) normals.push_back(glm::normalize(focus_detail::areaNormal(face)));
    std::vector<glm::vec3> result;
    for (const glm::vec3& p : vertices(tolerance)) {
        std::vector<glm::vec3> meeting;   // normals of the faces whose plane passes through p
        for (size_t f = 0; f < faces.size(); ++f)
            if (std::abs(glm::dot(normals[f], p - faces[f][0])) <= 10.0f * tolerance) meeting.push_back(normals[f]);
        bool corner = false;
        for (size_t a = 0; a < meeting.size() && !corner; ++a)
            for (size_t b = a + 1; b < meeting.size() && !corner; ++b)
                for (size_t c = b + 1; c < meeting.size() && !corner; ++c)
                    corner = std::abs(glm::dot(meeting[a], glm::cross(meeting[b], meeting[c]))) > 1e-4f;
        if (corner) result.push_back(p);
    }
    return result;
}

inline ConvexBody boxBody(const Bounds& box) {
    glm::vec3 corners[8];
    boundsCorners(box, corners);
    return focus_detail::hexahedron(corners);
}

// calcFrustum (seed 002 sec. 9.2.2): the 8 corners of the 2-unit NDC cube through the inverse of
// a view-projection (a camera's, or a light's for L).
inline ConvexBody frustumBody(const glm::mat4& inverseViewProjection) {
    glm::vec3 corners[8];
    for (int i = 0; i < 8; ++i) {
        const glm::vec4 p = inverseViewProjection *
                            glm::vec4(i & 1 ? 1.0f : -1.0f, i & 2 ? 1.0f : -1.0f, i & 4 ? 1.0f : -1.0f, 1.0f);
        corners[i] = glm::vec3(p) / p.w;
    }
    return focus_detail::hexahedron(corners);
}

// The planes of a body's faces, facing inwards: dot(plane.xyz, p) + plane.w >= 0 inside, the
// convention of DrawRequest::cullPlanes. `margin` (world units) moves them outwards, so objects
// that only touch the body (a ground plane on the scene's bottom face) are kept despite rounding.
inline std::vector<glm::vec4> inwardPlanes(const ConvexBody& body, float margin = 0.0f) {
    std::vector<glm::vec4> planes;
    for (const auto& face : body.faces) {
        const glm::vec3 n = focus_detail::areaNormal(face);
        if (glm::length(n) <= 0.0f) continue;
        const glm::vec3 inward = -glm::normalize(n);
        planes.emplace_back(inward, -glm::dot(inward, focus_detail::centroid(face)) + margin);
    }
    return planes;
}

// clip() by one plane: keeps the side where dot(plane.xyz, p) + plane.w >= 0. Every face is cut
// (Sutherland-Hodgman) and the hole closed by one new face through the cut points. A cut point is
// computed from the inside corner towards the outside one, so the two faces sharing an edge get
// the same point bit for bit.
inline void clip(ConvexBody& body, glm::vec4 plane) {
    using namespace focus_detail;
    const float length = glm::length(glm::vec3(plane));
    if (body.empty() || !(length > 0.0f)) return;
    plane /= length;
    const float tolerance = toleranceFor(body);
    auto distance = [&](glm::vec3 p) { return glm::dot(glm::vec3(plane), p) + plane.w; };
    bool anyInside = false, anyOutside = false;
    for (const auto& face : body.faces)
        for (const glm::vec3& p : face) (distance(p) < -tolerance ? anyOutside : anyInside) = true;
    if (!anyOutside) return;
    if (!anyInside) {
        body.faces.clear();
        return;
    }
    ConvexBody result;
    std::vector<glm::vec3> cap;
    for (const auto& face : body.faces) {
        std::vector<glm::vec3> kept;
        for (size_t i = 0; i < face.size(); ++i) {
            const glm::vec3 a = face[i], b = face[(i + 1) % face.size()];
            const float da = distance(a), db = distance(b);
            const bool aIn = da >= -tolerance, bIn = db >= -tolerance;
            if (aIn) {
                kept.push_back(a);
                if (std::abs(da) <= tolerance) cap.push_back(a);
            }
            if (aIn != bIn) {
                const glm::vec3 in = aIn ? a : b, out = aIn ? b : a;
                const float dIn = aIn ? da : db, dOut = aIn ? db : da;
                const glm::vec3 cut = in + (out - in) * (dIn / (dIn - dOut));
                kept.push_back(cut);
                cap.push_back(cut);
            }
        }
        tidy(kept, tolerance);
        if (!kept.empty()) result.faces.push_back(std::move(kept));
    }
    // The new face: the distinct cut points, in order around the plane's outward normal (-n).
    std::vector<glm::vec3> unique;
    for (const glm::vec3& p : cap)
        if (std::none_of(unique.begin(), unique.end(), [&](const glm::vec3& q) { return glm::distance(p, q) <= tolerance; }))
            unique.push_back(p);
    if (unique.size() >= 3) {
        orderAround(unique, -glm::vec3(plane));
        tidy(unique, tolerance);
        if (!unique.empty() && glm::length(areaNormal(unique)) > tolerance * tolerance) result.faces.push_back(std::move(unique));
    }
    body = std::move(result);
    if (body.faces.size() < 4) body.faces.clear();   // flattened to nothing
}

// clip() by a convex body or a box: by each of its face planes.
inline void clip(ConvexBody& body, const ConvexBody& convex) {
    for (const glm::vec4& plane : inwardPlanes(convex)) clip(body, plane);
}
inline void clip(ConvexBody& body, const Bounds& box) {
    const glm::vec4 planes[6] = {{1, 0, 0, -box.min.x}, {-1, 0, 0, box.max.x}, {0, 1, 0, -box.min.y},
                                 {0, -1, 0, box.max.y}, {0, 0, 1, -box.min.z}, {0, 0, -1, box.max.z}};
    for (const glm::vec4& plane : planes) clip(body, plane);
}

// convexHullWithPoint (seed 002 sec. 9.2.2): the convex hull of the body and a point. The faces
// facing the point are removed; the loop of edges around the hole is joined to the point by a fan
// of triangles. A point inside the body leaves it as it is.
inline void hullWithPoint(ConvexBody& body, glm::vec3 point) {
    using namespace focus_detail;
    if (body.empty()) return;
    const float tolerance = toleranceFor(body);
    std::vector<bool> facing(body.faces.size());
    bool any = false;
    for (size_t f = 0; f < body.faces.size(); ++f) {
        const glm::vec3 n = glm::normalize(areaNormal(body.faces[f]));
        facing[f] = glm::dot(n, point - centroid(body.faces[f])) > tolerance;
        any = any || facing[f];
    }
    if (!any) return;
    // The neighbour across the outline keeps (b, a); the triangle runs (a, b, point).
    replaceFacingFaces(body, facing, tolerance, [&](glm::vec3 a, glm::vec3 b) {
        return std::vector<glm::vec3>{a, b, point};
    });
}

// convexHullWithDirection (seed 002 sec. 9.2.2): the body swept along `direction` (towards the
// light: -l) by `distance`. The faces facing that way are moved along it; the outline between
// them and the rest is bridged with quads. With a distance that leaves the scene's bounds and a
// clip to them afterwards, this is the hull with a point at infinity.
inline void extrude(ConvexBody& body, glm::vec3 direction, float distance) {
    using namespace focus_detail;
    if (body.empty() || !(glm::length(direction) > 0.0f)) return;
    const glm::vec3 offset = glm::normalize(direction) * distance;
    const float tolerance = toleranceFor(body);
    std::vector<bool> facing(body.faces.size());
    for (size_t f = 0; f < body.faces.size(); ++f)
        facing[f] = glm::dot(glm::normalize(areaNormal(body.faces[f])), offset) > 1e-6f * distance;
    // The neighbour keeps (b, a), the moved face has (a', b'): the quad runs a, b, b', a'.
    replaceFacingFaces(
        body, facing, tolerance,
        [&](glm::vec3 a, glm::vec3 b) { return std::vector<glm::vec3>{a, b, b + offset, a + offset}; }, offset);
}

// Whether p lies in the body (within `tolerance` of it).
inline bool contains(const ConvexBody& body, glm::vec3 p, float tolerance = 1e-4f) {
    if (body.empty()) return false;
    for (const glm::vec4& plane : inwardPlanes(body))
        if (glm::dot(glm::vec3(plane), p) + plane.w < -tolerance) return false;
    return true;
}

// The focus body B = ((V n S) + l) n S n L (seed 002 eq. 4.2), by the recipe of sec. 9.2.2:
// V from the camera's inverse view-projection (its far plane included: seed 002 sec. 9.2.5 warns
// against a nearer, virtual far plane here), clipped to the scene's bounds S; joined with the light
// (point and spot lights: hull with the light's position; directional lights: swept towards the
// light across S); clipped to S again, and for point and spot lights to the light's frustum L
// (`lightSpace`, the map being focused). Empty when the camera sees nothing of S.
// This form takes any view body in place of V (seed 002 sec. 9.2.5: LiSPSM's virtual frustum V_v);
// the next takes the camera's frustum.
inline ConvexBody focusBody(ConvexBody body, const LightInfo& light, const Bounds& scene, const LightSpace& lightSpace) {
    clip(body, scene);
    if (body.empty()) return body;
    if (light.type == LightType::Directional) {
        // Any point of S leaves S after moving the length of its diagonal (plus one unit for a flat S).
        extrude(body, -light.direction, glm::length(scene.max - scene.min) + 1.0f);
    } else {
        hullWithPoint(body, light.position);
    }
    clip(body, scene);
    if (light.type != LightType::Directional) clip(body, frustumBody(glm::inverse(lightSpace.viewProjection)));
    return body;
}

inline ConvexBody focusBody(const CameraInfo& camera, const LightInfo& light, const Bounds& scene,
                            const LightSpace& lightSpace) {
    return focusBody(frustumBody(camera.inverseViewProjection), light, scene, lightSpace);
}

// ---------------------------------------------------------------------------------------------
// The crop of seed 000 sec. 3.2.3

// A rectangle of the light's NDC (x and y), inside [-1, 1]^2.
struct CropWindow {
    glm::vec2 min{-1.0f};
    glm::vec2 max{1.0f};
};

// The light-NDC bounding box of points, clamped to the scene fit's [-1, 1] ("to not move the
// contents of the shadow map beyond the original extent specified for the light source"). The
// points must be in front of a perspective light (w > 0): clip them to its frustum first. No
// points, or none inside: the whole map.
inline CropWindow cropWindow(const glm::mat4& lightViewProjection, const std::vector<glm::vec3>& points) {
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : points) {
        const glm::vec4 clipPos = lightViewProjection * glm::vec4(p, 1.0f);
        if (!(clipPos.w > 0.0f)) continue;
        const glm::vec2 ndc = glm::vec2(clipPos) / clipPos.w;
        lo = glm::min(lo, ndc);
        hi = glm::max(hi, ndc);
    }
    CropWindow window{glm::clamp(lo, glm::vec2(-1.0f), glm::vec2(1.0f)), glm::clamp(hi, glm::vec2(-1.0f), glm::vec2(1.0f))};
    if (!(window.max.x > window.min.x) || !(window.max.y > window.min.y)) return {};
    return window;
}

// F of seed 000 eq. 3.9-3.10: s = 2 / (max - min), o = -s (max + min) / 2 in x and y; z and w
// untouched. F P_L V_L maps the window onto the whole map.
inline glm::mat4 cropMatrix(const CropWindow& window) {
    const glm::vec2 s = 2.0f / (window.max - window.min);
    const glm::vec2 o = -s * (window.max + window.min) * 0.5f;
    glm::mat4 f(1.0f);   // glm is column-major: f[column][row]
    f[0][0] = s.x;
    f[1][1] = s.y;
    f[3][0] = o.x;
    f[3][1] = o.y;
    return f;
}

// Texel snapping (seed 000 sec. 2.2.5), per axis. The window's size becomes res texels of a grid
// of N texels across the whole of [-1, 1] (N >= res a whole number: the size is quantised), and its
// lower edge a whole number of those texels from -1 (the offset is quantised). One texel of slack
// keeps the raw window inside. The window may then overrun [-1, 1]; it is shifted back, by whole
// texels since both -1 and 1 - size are on the grid. A window wider than (res - 1) / res of the
// map becomes the whole map.
inline CropWindow snapToTexels(const CropWindow& window, int resolution) {
    CropWindow snapped;
    const double res = std::max(resolution, 2);
    for (int axis = 0; axis < 2; ++axis) {
        const double lo = window.min[axis], width = std::max(double(window.max[axis]) - lo, 1e-7);
        const double texels = std::floor(2.0 * (res - 1.0) / width);   // N
        if (texels <= res) {
            snapped.min[axis] = -1.0f;
            snapped.max[axis] = 1.0f;
            continue;
        }
        const double texel = 2.0 / texels, size = res * texel;
        double start = -1.0 + std::floor((lo + 1.0) / texel) * texel;
        start = std::clamp(start, -1.0, 1.0 - size);
        snapped.min[axis] = float(start);
        snapped.max[axis] = float(start + size);
    }
    return snapped;
}

// F P_L V_L as a LightSpace: the same view and depth range, the map's extent scaled with the window.
inline LightSpace cropLightSpace(const LightSpace& base, const CropWindow& window) {
    const glm::mat4 f = cropMatrix(window);
    LightSpace cropped = base;
    cropped.projection = f * base.projection;
    cropped.viewProjection = f * base.viewProjection;
    cropped.worldSizeAtUnitDepth = base.worldSizeAtUnitDepth * (window.max - window.min) * 0.5f;
    return cropped;
}

// The four side planes of a light space's map (x and y of NDC in [-1, 1]), facing inwards
// (Gribb and Hartmann: row 3 plus or minus row 0 or 1 of the view-projection), normalised.
inline std::vector<glm::vec4> mapSidePlanes(const LightSpace& lightSpace, float margin = 0.0f) {
    const glm::mat4& m = lightSpace.viewProjection;
    auto row = [&](int r) { return glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]); };
    std::vector<glm::vec4> planes{row(3) + row(0), row(3) - row(0), row(3) + row(1), row(3) - row(1)};
    for (glm::vec4& plane : planes) {
        plane /= glm::length(glm::vec3(plane));
        plane.w += margin;
    }
    return planes;
}

// B's edges for the host's focus-body view (ShadowMapInfo::focusBodyEdges): pairs of world points,
// each edge once. Edges between two coplanar faces (left by the operations where a face and a
// coplanar quad join) are not edges of the body and are dropped.
inline std::vector<glm::vec3> bodyEdges(const ConvexBody& body) {
    std::vector<glm::vec3> edges;
    const float tolerance = 10.0f * focus_detail::toleranceFor(body);
    std::vector<glm::vec3> normals;
    for (const auto& face : body.faces) {
        const glm::vec3 n = focus_detail::areaNormal(face);
        normals.push_back(glm::length(n) > 0.0f ? glm::normalize(n) : n);
    }
    for (size_t f = 0; f < body.faces.size(); ++f) {
        const auto& face = body.faces[f];
        for (size_t i = 0; i < face.size(); ++i) {
            const glm::vec3 a = face[i], b = face[(i + 1) % face.size()];
            const glm::vec3 mid = 0.5f * (a + b);
            // The other face holding this edge: its midpoint on one of that face's edges.
            bool drop = false;
            for (size_t g = 0; g < body.faces.size() && !drop; ++g) {
                if (g == f) continue;
                const auto& other = body.faces[g];
                for (size_t j = 0; j < other.size(); ++j)
                    if (focus_detail::segmentDistance(mid, other[j], other[(j + 1) % other.size()]) <= tolerance) {
                        // Kept once (by the face of lower index), never between coplanar faces.
                        drop = g < f || glm::dot(normals[f], normals[g]) > 1.0f - 1e-4f;
                        break;
                    }
            }
            if (!drop) {
                edges.push_back(a);
                edges.push_back(b);
            }
        }
    }
    return edges;
}

// ---------------------------------------------------------------------------------------------
// The fit a technique asks for

struct FocusedLightSpace {
    LightSpace light;                   // F P_L V_L (the scene fit itself for Fit::Scene)
    std::vector<glm::vec4> cullPlanes;  // for DrawRequest: the map's volume; empty = draw everything
    ConvexBody body;                    // Fit::FocusBody: B (empty otherwise)
};

// `sceneFit`: the host's fit around the whole scene (P_L V_L); `scene`: the scene's bounds S.
// Falls back to the scene fit where the camera sees nothing of the scene.
inline FocusedLightSpace focusLightSpace(const LightSpace& sceneFit, const CameraInfo& camera, const LightInfo& light,
                                         const Bounds& scene, const FitConfig& config, int resolution) {
    FocusedLightSpace result{sceneFit, {}, {}};
    if (config.fit == Fit::Scene) return result;
    std::vector<glm::vec3> points;
    if (config.fit == Fit::Frustum) {
        if (!sceneFit.perspective) {
            points.assign(camera.frustumCorners, camera.frustumCorners + 8);   // seed 000 as written
        } else {
            // Corners behind a perspective light do not project: the part of V in its frustum.
            ConvexBody visible = frustumBody(camera.inverseViewProjection);
            clip(visible, frustumBody(glm::inverse(sceneFit.viewProjection)));
            points = visible.vertices();
        }
    } else {
        result.body = focusBody(camera, light, scene, sceneFit);
        points = result.body.vertices();
    }
    if (points.empty()) return result;
    CropWindow window = cropWindow(sceneFit.viewProjection, points);
    if (config.snap) window = snapToTexels(window, resolution);
    result.light = cropLightSpace(sceneFit, window);
    // Casters outside the map's volume cannot reach the map; for the focus body, outside B none
    // can shadow a visible point. The margin keeps objects that merely touch it.
    const float margin = 1e-4f * std::max(glm::length(scene.max - scene.min), 1.0f);
    result.cullPlanes = config.fit == Fit::FocusBody ? inwardPlanes(result.body, margin)
                                                     : mapSidePlanes(result.light, margin);
    return result;
}

// The same with the host's scene fit and bounds.
inline FocusedLightSpace focusLightSpace(const IHost& host, const FrameContext& frame, const FitConfig& config,
                                         int resolution) {
    if (config.fit == Fit::Scene) return {host.fitLightSpace(frame.light, DrawSet::All), {}, {}};
    return focusLightSpace(host.fitLightSpace(frame.light, DrawSet::All), frame.camera, frame.light,
                           host.bounds(DrawSet::All), config, resolution);
}

// A draw of `set` culled against a focused map's volume (FocusedLightSpace::cullPlanes; none: all).
inline DrawRequest culledDraw(DrawSet set, const std::vector<glm::vec4>& cullPlanes, DrawRequest request = {}) {
    request.set = set;
    request.cullPlanes = cullPlanes.data();
    request.cullPlaneCount = uint32_t(cullPlanes.size());
    return request;
}

} // namespace shadowlab::kit
