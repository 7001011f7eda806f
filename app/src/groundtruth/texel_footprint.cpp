// Texel footprint on the screen (see texel_footprint.h).
#include "groundtruth/texel_footprint.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "util/parallel.h"
#include "util/stats.h"

namespace shadowlab {

namespace {

// A point's texel coordinates in `map` (x, y in texels), false behind a perspective map's eye.
bool texelOf(const glm::dmat4& worldToClip, const glm::dvec2& size, const glm::dvec3& p, glm::dvec2& texel) {
    const glm::dvec4 clip = worldToClip * glm::dvec4(p, 1.0);
    if (clip.w <= 1e-12) return false;
    texel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * size;
    return true;
}

// Where the camera ray through `ndc` meets the plane through p with normal n.
bool rayOnPlane(const glm::dmat4& inverseViewProjection, const glm::dvec2& ndc, const glm::dvec3& p,
                const glm::dvec3& n, glm::dvec3& hit) {
    const glm::dvec4 a = inverseViewProjection * glm::dvec4(ndc, -1.0, 1.0);
    const glm::dvec4 b = inverseViewProjection * glm::dvec4(ndc, 1.0, 1.0);
    if (std::abs(a.w) < 1e-300 || std::abs(b.w) < 1e-300) return false;
    const glm::dvec3 origin = glm::dvec3(a) / a.w;
    const glm::dvec3 direction = glm::dvec3(b) / b.w - origin;
    const double denominator = glm::dot(n, direction);
    // Edge-on (the ray runs along the plane, under about 0.06 degrees): no footprint to speak of.
    if (std::abs(denominator) <= 1e-3 * glm::length(direction)) return false;
    hit = origin + direction * (glm::dot(n, p - origin) / denominator);
    return true;
}

// Takes the values (callers move them in: percentile reorders its own copy).
double medianOf(std::vector<double> values) { return values.empty() ? 0.0 : percentile(std::move(values), 0.5); }

} // namespace

int servingShadowMap(const std::vector<ShadowMapInfo>& maps, const glm::vec3& world, float viewDistance) {
    for (size_t i = 0; i < maps.size(); ++i) {
        const ShadowMapInfo& map = maps[i];
        if (viewDistance < map.viewDistanceBegin || viewDistance >= map.viewDistanceEnd) continue;
        const glm::vec4 clip = map.worldToClip * glm::vec4(world, 1.0f);
        if (clip.w <= 0.0f) continue;
        if (std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w) return int(i);
    }
    return -1;
}

namespace {

struct CameraMatrices {
    glm::dmat4 view, viewProjection, inverse;
    glm::dvec2 pixel;   // one pixel in NDC
    explicit CameraMatrices(const CameraInfo& camera)
        : view(camera.view), viewProjection(camera.viewProjection), inverse(glm::inverse(viewProjection)),
          pixel(2.0 / glm::dvec2(glm::max(camera.viewport, glm::ivec2(1)))) {}
    double depth(const glm::dvec3& p) const { return -(view * glm::dvec4(p, 1.0)).z; }
};

// m, and (where `alongDepth` is given) pixels per texel along the screen direction in which the
// view depth grows fastest (0 where the plane is seen head-on and depth does not change).
float footprint(const CameraMatrices& camera, const ShadowMapInfo& map, const glm::vec3& point, const glm::vec3& normal,
                float* alongDepth = nullptr) {
    if (alongDepth) *alongDepth = 0.0f;
    const glm::dvec3 p(point), n(glm::normalize(glm::dvec3(normal)));
    const glm::dvec4 clip = camera.viewProjection * glm::dvec4(p, 1.0);
    if (clip.w <= 0.0) return 0.0f;
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    glm::dvec3 px, py;
    if (!rayOnPlane(camera.inverse, ndc + glm::dvec2(camera.pixel.x, 0.0), p, n, px)) return 0.0f;
    if (!rayOnPlane(camera.inverse, ndc + glm::dvec2(0.0, camera.pixel.y), p, n, py)) return 0.0f;
    const glm::dmat4 toClip(map.worldToClip);
    const glm::dvec2 size(map.size);
    glm::dvec2 t0, tx, ty;
    if (!texelOf(toClip, size, p, t0) || !texelOf(toClip, size, px, tx) || !texelOf(toClip, size, py, ty)) return 0.0f;
    // A maps a step in pixels to a step in texels; the worst direction has the fewest texels per
    // pixel, A's smallest singular value, so m = 1 / sigma_min pixels per texel.
    const glm::dvec2 c1 = tx - t0, c2 = ty - t0;
    if (alongDepth) {
        // A step of one pixel along the view-depth gradient g moves J g / |g| texels, J the
        // derivative of texels by pixels: from rays 1/64 pixel away, since across a whole pixel
        // of a receiver seen at a grazing angle the depth changes by a good part of itself.
        constexpr double kStep = 1.0 / 64.0;
        glm::dvec3 qx, qy;
        glm::dvec2 ux, uy;
        if (rayOnPlane(camera.inverse, ndc + glm::dvec2(kStep * camera.pixel.x, 0.0), p, n, qx) &&
            rayOnPlane(camera.inverse, ndc + glm::dvec2(0.0, kStep * camera.pixel.y), p, n, qy) &&
            texelOf(toClip, size, qx, ux) && texelOf(toClip, size, qy, uy)) {
            const glm::dvec2 g(camera.depth(qx) - camera.depth(p), camera.depth(qy) - camera.depth(p));
            const double length = glm::length(g);
            if (length > 1e-12 * kStep * std::max(camera.depth(p), 1e-12)) {
                const double texels = glm::length((ux - t0) * (g.x / length) + (uy - t0) * (g.y / length)) / kStep;
                if (texels > 0.0) *alongDepth = float(std::min(1.0 / texels, 1e6));
            }
        }
    }
    const double a = glm::dot(c1, c1), b = glm::dot(c1, c2), c = glm::dot(c2, c2);
    const double half = 0.5 * (a - c);
    const double lambdaMin = 0.5 * (a + c) - std::sqrt(half * half + b * b);
    constexpr double kLargest = 1e6;   // a plane edge-on to the light: no texel for it at all
    if (lambdaMin <= 1.0 / (kLargest * kLargest)) return float(kLargest);
    return float(std::min(1.0 / std::sqrt(lambdaMin), kLargest));
}

} // namespace

float texelFootprintAt(const CameraInfo& camera, const ShadowMapInfo& map, const glm::vec3& point, const glm::vec3& normal) {
    return footprint(CameraMatrices(camera), map, point, normal);
}

TexelFootprint measureTexelFootprint(const GBufferView& gbuffer, const std::vector<uint8_t>& mask, const CameraInfo& camera,
                                     const LightInfo& light, const std::vector<ShadowMapInfo>& maps) {
    const size_t count = size_t(std::max(gbuffer.width, 0)) * size_t(std::max(gbuffer.height, 0));
    if (mask.size() != count || !gbuffer.positions || !gbuffer.normals)
        throw std::invalid_argument("texel footprint: the mask and the G-buffer must both be width * height");
    TexelFootprint out;
    out.width = gbuffer.width;
    out.height = gbuffer.height;
    out.maps = maps.size();
    out.m.assign(count, 0.0f);
    out.projection.assign(count, 0.0f);
    out.depthError.assign(count, 0.0f);
    if (maps.empty()) return out;
    out.byViewDepth.assign(size_t(kFootprintDepthBins), {});
    std::vector<std::vector<size_t>> binned(static_cast<size_t>(kFootprintDepthBins));
    const double logRange = std::log(std::max(double(camera.farPlane) / std::max(double(camera.nearPlane), 1e-9), 1.0 + 1e-9));
    CameraInfo view = camera;
    view.viewport = {gbuffer.width, gbuffer.height};
    const CameraMatrices matrices(view);
    // Per pixel on every core (util/parallel.h): m, the projection term and the depth error;
    // then, in pixel order, the lists the medians and bins are taken from.
    const float depthRange = std::max(camera.farPlane - camera.nearPlane, 1e-6f);
    enum : uint8_t { kNotMeasured = 0, kUncovered = 1, kMeasured = 2 };
    std::vector<uint8_t> state(count, kNotMeasured);
    std::vector<float> viewDistances(count, 0.0f);
    forEachChunk(count, 8192, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            if (!mask[i]) continue;
            const glm::vec3 p(gbuffer.positions[i]), n(gbuffer.normals[i]);
            const float viewDistance = -(camera.view * glm::vec4(p, 1.0f)).z;
            viewDistances[i] = viewDistance;
            const int serving = servingShadowMap(maps, p, viewDistance);
            if (serving < 0) {
                state[i] = kUncovered;
                continue;
            }
            float alongDepth = 0.0f;
            const float m = footprint(matrices, maps[size_t(serving)], p, n, &alongDepth);
            if (m <= 0.0f) continue;
            state[i] = kMeasured;
            out.m[i] = m;
            // Eq. 6.1: alpha between the view vector and the normal, beta between the light vector
            // and the normal (the mask keeps only pixels facing the light, so cos(beta) > 0).
            const glm::vec3 toLight = light.type == LightType::Directional ? -light.direction : light.position - p;
            const float cosAlpha = std::abs(glm::dot(glm::normalize(n), glm::normalize(camera.position - p)));
            const float cosBeta = std::max(glm::dot(glm::normalize(n), glm::normalize(toLight)), 1e-6f);
            out.projection[i] = cosAlpha / cosBeta;
            if (alongDepth > 0.0f && out.projection[i] > 0.0f && viewDistance > 0.0f)
                out.depthError[i] = alongDepth / out.projection[i];
        }
    });
    // Sized once (a 1080p frame grew them by copying about 40 MB an evaluation): pages untouched
    // by the pixels measured are never faulted in.
    const size_t measured = size_t(std::count(state.begin(), state.end(), uint8_t(kMeasured)));
    std::vector<double> all, projection;
    all.reserve(measured);
    projection.reserve(measured);
    std::array<std::vector<double>, 3> thirds;
    for (std::vector<double>& third : thirds) third.reserve(measured / 3);
    size_t undersampled = 0;
    for (size_t i = 0; i < count; ++i) {
        if (state[i] == kUncovered) ++out.uncoveredPixels;
        if (state[i] != kMeasured) continue;
        const float m = out.m[i], viewDistance = viewDistances[i];
        all.push_back(m);
        undersampled += m > 1.0f ? 1 : 0;
        const int third = std::clamp(int(3.0f * (viewDistance - camera.nearPlane) / depthRange), 0, 2);
        thirds[size_t(third)].push_back(m);
        projection.push_back(out.projection[i]);
        if (out.depthError[i] > 0.0f) {
            const int bin = int(std::floor(double(kFootprintDepthBins) * std::log(viewDistance / camera.nearPlane) / logRange));
            if (bin >= 0 && bin < kFootprintDepthBins) binned[size_t(bin)].push_back(i);
        }
    }
    for (int b = 0; b < kFootprintDepthBins; ++b) {
        TexelFootprint::DepthBin& bin = out.byViewDepth[size_t(b)];
        bin.begin = camera.nearPlane * std::exp(logRange * b / kFootprintDepthBins);
        bin.end = camera.nearPlane * std::exp(logRange * (b + 1) / kFootprintDepthBins);
        const std::vector<size_t>& pixels = binned[size_t(b)];
        bin.pixels = pixels.size();
        if (pixels.empty()) continue;
        std::vector<double> depths, ms, errors;
        depths.reserve(pixels.size());
        ms.reserve(pixels.size());
        errors.reserve(pixels.size());
        for (const size_t i : pixels) {
            depths.push_back(-(camera.view * glm::vec4(glm::vec3(gbuffer.positions[i]), 1.0f)).z);
            ms.push_back(out.m[i]);
            errors.push_back(out.depthError[i]);
        }
        bin.depth = medianOf(std::move(depths));
        bin.m = medianOf(std::move(ms));
        bin.depthError = medianOf(std::move(errors));
    }
    out.measuredPixels = all.size();
    if (all.empty()) return out;
    out.median = percentile(all, 0.5);
    out.max = *std::max_element(all.begin(), all.end());
    out.undersampledFraction = double(undersampled) / double(all.size());
    out.p95 = percentile(std::move(all), 0.95);
    for (size_t t = 0; t < 3; ++t) out.medianByViewDepth[t] = medianOf(std::move(thirds[t]));
    out.projectionMedian = percentile(projection, 0.5);
    out.projectionP95 = percentile(std::move(projection), 0.95);
    return out;
}

Image footprintHeatmap(const TexelFootprint& footprint) {
    Image image{footprint.width, footprint.height, 4,
                std::vector<uint8_t>(size_t(footprint.width) * size_t(footprint.height) * 4, 255)};
    const glm::vec3 low(40, 80, 230), unit(120, 190, 120), high(230, 40, 30), none(24, 24, 24);
    for (size_t i = 0; i < footprint.m.size(); ++i) {
        glm::vec3 colour = none;
        if (footprint.m[i] > 0.0f) {
            const float t = std::clamp(std::log2(footprint.m[i]) / 4.0f, -1.0f, 1.0f);   // log2 m in [-4, 4]
            colour = t < 0.0f ? glm::mix(unit, low, -t) : glm::mix(unit, high, t);
        }
        for (int c = 0; c < 3; ++c) image.pixels[i * 4 + size_t(c)] = uint8_t(colour[c] + 0.5f);
    }
    return image;
}

std::string footprintToJson(const TexelFootprint& f, int indent) {
    nlohmann::json out = {{"median", f.median},
                                {"p95", f.p95},
                                {"max", f.max},
                                {"undersampledFraction", f.undersampledFraction},
                                {"medianByViewDepth", f.medianByViewDepth},
                                {"projectionMedian", f.projectionMedian},
                                {"projectionP95", f.projectionP95},
                                {"measuredPixels", f.measuredPixels},
                                {"uncoveredPixels", f.uncoveredPixels},
                                {"maps", f.maps}};
    nlohmann::json& bins = out["byViewDepth"] = nlohmann::json::array();
    for (const TexelFootprint::DepthBin& b : f.byViewDepth)
        bins.push_back({{"begin", b.begin}, {"end", b.end}, {"depth", b.depth}, {"m", b.m}, {"depthError", b.depthError},
                        {"pixels", b.pixels}});
    return out.dump(indent);
}

} // namespace shadowlab
