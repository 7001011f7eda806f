// The filter kernel's footprint around one pixel (see kernel_probe.h). Each step mirrors the GLSL
// it names, in the same order and with the same comparisons (lit where ref <= stored depth, as
// GL_LEQUAL), so the numbers are the shader's for that pixel.
#include "render/kernel_probe.h"

#include <shadowlab/kit/jittered_disk.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace shadowlab {

namespace {

// shaders/light_depth.glsl
float lightLinearDepth(float d, glm::vec4 lightDepth) {
    const float n = lightDepth.x, f = lightDepth.y;
    return lightDepth.z > 0.5f ? n * f / (f - d * (f - n)) : d * (f - n);
}

float receiverDepthSlope(glm::vec3 normal, glm::vec3 lightAxis, float d, glm::vec4 lightDepth, glm::vec2 worldSize) {
    const float cosTheta = std::clamp(std::abs(glm::dot(normal, lightAxis)), 0.0995f, 1.0f);
    const float tanTheta = std::sqrt(1.0f - cosTheta * cosTheta) / cosTheta;
    const float n = lightDepth.x, f = lightDepth.y, resolution = lightDepth.w;
    const float texelWorld = std::max(worldSize.x, worldSize.y) / resolution;
    if (lightDepth.z > 0.5f) {
        const float z = lightLinearDepth(d, lightDepth);
        return tanTheta * texelWorld * z * n * f / ((f - n) * z * z);
    }
    return tanTheta * texelWorld / (f - n);
}

// shaders/light_space.glsl
glm::vec3 shadowMapCoord(const glm::mat4& m, glm::vec3 world) {
    const glm::vec4 clip = m * glm::vec4(world, 1.0f);
    return glm::vec3(clip) / clip.w * 0.5f + 0.5f;
}

bool insideShadowMap(glm::vec3 c) {
    return c.x >= 0.0f && c.y >= 0.0f && c.z >= 0.0f && c.x <= 1.0f && c.y <= 1.0f && c.z <= 1.0f;
}

struct Sampler {
    const DepthFetch& depth;
    int resolution;
    float stored(int x, int y) const {
        return depth(std::clamp(x, 0, resolution - 1), std::clamp(y, 0, resolution - 1));
    }
    // The texture unit's comparison at uv: nearest texel, or the 2x2 bilinear blend of comparisons.
    float compare(glm::vec2 uv, float ref, bool bilinear) const {
        const glm::vec2 p = uv * float(resolution);
        if (!bilinear) {
            const glm::ivec2 t(std::floor(p.x), std::floor(p.y));
            return ref <= stored(t.x, t.y) ? 1.0f : 0.0f;
        }
        const glm::vec2 q = p - 0.5f;
        const glm::ivec2 t(std::floor(q.x), std::floor(q.y));
        const glm::vec2 f = q - glm::vec2(t);
        auto s = [&](int dx, int dy) { return ref <= stored(t.x + dx, t.y + dy) ? 1.0f : 0.0f; };
        return glm::mix(glm::mix(s(0, 0), s(1, 0), f.x), glm::mix(s(0, 1), s(1, 1), f.x), f.y);
    }
    // textureLod of a nearest sampler2D (the search's raw depths).
    float fetch(glm::vec2 uv) const {
        const glm::vec2 p = uv * float(resolution);
        return stored(int(std::floor(p.x)), int(std::floor(p.y)));
    }
    // shaders/depth_range.glsl's depthRangeIn over the kit's depth-range mips (level 0 half the map,
    // each level's texel the min and max of 2^(k+1) x 2^(k+1) map texels): the same texels.
    glm::vec2 depthRangeIn(glm::vec2 uv, glm::vec2 radiusUv) const {
        const float radiusTexels = std::max(radiusUv.x, radiusUv.y) * float(resolution);
        const int size0 = std::max(resolution / 2, 1);
        int levels = 1;
        while ((size0 >> levels) > 0) ++levels;
        const int level = std::clamp(int(std::ceil(std::log2(std::max(radiusTexels, 1.0f)))), 0, levels - 1);
        const int size = std::max(size0 >> level, 1), span = 2 << level;
        auto cell = [&](float v) { return std::clamp(int(std::floor(v * float(resolution))) / span, 0, size - 1); };
        const glm::ivec2 lo(cell(uv.x - radiusUv.x), cell(uv.y - radiusUv.y));
        const glm::ivec2 hi(cell(uv.x + radiusUv.x), cell(uv.y + radiusUv.y));
        glm::vec2 range(1.0f, 0.0f);
        const int last = resolution - 1;
        for (int y = lo.y * span; y <= std::min((hi.y + 1) * span - 1, last); ++y)
            for (int x = lo.x * span; x <= std::min((hi.x + 1) * span - 1, last); ++x) {
                const float d = stored(x, y);
                range = {std::min(range.x, d), std::max(range.y, d)};
            }
        return range;
    }
};

// The disc set of a pixel, stored as the kit's RGBA16_SNORM texture stores it (jittered_disk.h).
std::vector<glm::vec2> discSet(int n, int m, uint32_t seed, glm::ivec2 pixel) {
    const std::vector<glm::vec4> texels = jittered_disk::makeOffsetTexture(n, m, seed);
    const int depth = jittered_disk::texelsPerSet(n);
    const glm::ivec2 set(((pixel.x % m) + m) % m, ((pixel.y % m) + m) % m);
    auto snorm = [](float v) { return std::round(std::clamp(v, -1.0f, 1.0f) * 32767.0f) / 32767.0f; };
    std::vector<glm::vec2> samples;
    for (int z = 0; z < depth; ++z) {
        const glm::vec4 t = texels[(size_t(z) * size_t(m) + size_t(set.y)) * size_t(m) + size_t(set.x)];
        samples.push_back({snorm(t.x), snorm(t.y)});
        if (2 * z + 1 < n * n) samples.push_back({snorm(t.z), snorm(t.w)});
    }
    return samples;
}

// Whether the outer ring of the pixel's set agrees (disc_sampling.glsl: lit == 0 or all taken).
bool ringAgrees(const Sampler& sampler, const std::vector<glm::vec2>& set, int n, glm::vec3 coord, glm::vec2 radiusUv,
                float rimBias, bool bilinear) {
    const int ringSamples = std::min(2 * ((n + 1) / 2), n * n);
    float lit = 0.0f;
    for (int k = 0; k < ringSamples; ++k)
        lit += sampler.compare(glm::vec2(coord) + set[size_t(k)] * radiusUv, coord.z - rimBias * glm::length(set[size_t(k)]),
                               bilinear);
    return lit == 0.0f || lit == float(ringSamples);
}

// adaptiveDiscPcf: the ring, then (unless it stops) the rest; every sample recorded.
void adaptiveDisc(KernelProbe& probe, const Sampler& sampler, const std::vector<glm::vec2>& set, int n, glm::vec3 coord,
                  glm::vec2 radiusUv, float rimBias, bool bilinear, bool quadStops) {
    const int count = n * n, ringSamples = std::min(2 * ((n + 1) / 2), count);
    const int texels = (count + 1) / 2, ringTexels = (n + 1) / 2;
    float lit = 0.0f;
    int taken = 0;
    for (int k = 0; k < count; ++k) {
        KernelTap tap;
        tap.stage = k < ringSamples ? KernelTap::Stage::Ring : KernelTap::Stage::Inner;
        tap.uv = glm::vec2(coord) + set[size_t(k)] * radiusUv;
        tap.lit = sampler.compare(tap.uv, coord.z - rimBias * glm::length(set[size_t(k)]), bilinear);
        probe.taps.push_back(tap);
    }
    for (int k = 0; k < ringSamples; ++k) lit += probe.taps[probe.taps.size() - size_t(count) + size_t(k)].lit;
    taken = ringSamples;
    const bool agree = lit == 0.0f || lit == float(taken);
    if (ringTexels < texels && agree && quadStops) {
        probe.earlyOut = true;
        for (size_t k = probe.taps.size() - size_t(count) + size_t(ringSamples); k < probe.taps.size(); ++k)
            probe.taps[k].taken = false;
    } else {
        for (size_t k = probe.taps.size() - size_t(count) + size_t(ringSamples); k < probe.taps.size(); ++k)
            lit += probe.taps[k].lit;
        taken = count;
    }
    probe.samplesTaken += taken;
    probe.lit = lit / float(taken);
}

} // namespace

// The box kernel (shaders/box_pcf.glsl's boxPcfDepth): n x n taps `spacing` texels apart, each a
// comparison with the cone bias growing with its offset.
static void probeBox(KernelProbe& probe, const FilterFootprint& footprint, const Sampler& sampler, glm::vec3 coord, int res,
                     bool bilinear, float slope, int n) {
    // shaders/box_pcf.glsl's boxPcfDepth.
    const glm::vec2 u = glm::vec2(coord) * float(res);
    float lit = 0.0f;
    glm::vec2 lo(1e30f), hi(-1e30f);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const glm::vec2 offset = (glm::vec2(i, j) - 0.5f * float(n - 1)) * footprint.spacing;
            const glm::vec2 position = bilinear ? u + offset : glm::floor(u + offset) + 0.5f;
            KernelTap tap;
            tap.uv = position / float(res);
            tap.lit = sampler.compare(tap.uv, coord.z - slope * glm::length(offset), bilinear);
            lit += tap.lit;
            probe.taps.push_back(tap);
            // The texels this tap reads: its own, or the 2x2 around a bilinear tap.
            const glm::vec2 first = bilinear ? glm::floor(position - 0.5f) : glm::floor(position);
            lo = glm::min(lo, first);
            hi = glm::max(hi, first + (bilinear ? 2.0f : 1.0f));
        }
    probe.boxMin = lo / float(res);
    probe.boxMax = hi / float(res);
    probe.kernelTexels = std::max(hi.x - lo.x, hi.y - lo.y);
    probe.samplesTaken = n * n;
    probe.lit = lit / float(n * n);
}

// The disc kernel (plugins/adaptive-pcf/adaptive-pcf.glsl, 2D map, classify = ring): the outer
// ring first, the early out decided per pixel or per 2x2 quad.
static void probeDisc(KernelProbe& probe, const FilterFootprint& footprint, const Sampler& sampler, const ProbeQuad& quad,
                      glm::ivec2 pixel, glm::vec3 coord, int res, bool bilinear, float slope, int n, const glm::vec3& axis,
                      glm::vec2 worldSize, const glm::mat4& worldToClip) {
    // plugins/adaptive-pcf/adaptive-pcf.glsl (2D map, classify = ring).
    const int m = std::max(footprint.sets, 1);
    const glm::vec2 radiusUv(footprint.spacing / float(res));
    probe.filterRadiusTexels = footprint.spacing;
    probe.kernelTexels = 2.0f * footprint.spacing;
    bool quadStops = true;
    if (footprint.coherent) {
        // Every pixel of the quad must agree (pixels without geometry or outside the map count as agreeing).
        for (int q = 0; q < 4; ++q) {
            if (quad.position[q].w < 0.5f) continue;
            const glm::vec3 c = shadowMapCoord(worldToClip, glm::vec3(quad.position[q]));
            if (!insideShadowMap(c)) continue;
            const float s = footprint.coneBias *
                            receiverDepthSlope(glm::normalize(quad.normal[q]), axis, c.z, footprint.lightDepth, worldSize);
            const glm::ivec2 p = quad.origin + glm::ivec2(q % 2, q / 2);
            if (!ringAgrees(sampler, discSet(n, m, footprint.discSeed, p), n, c, radiusUv, s * footprint.spacing, bilinear))
                quadStops = false;
        }
    }
    adaptiveDisc(probe, sampler, discSet(n, m, footprint.discSeed, pixel), n, coord, radiusUv, slope * footprint.spacing,
                 bilinear, quadStops);
}

// PCSS's blocker search (seed 000 eq. 3.18; pcss.glsl's step 1): n_s x n_s disc samples over the
// search region, each with the cone bias; returns the sum of the blockers' linear depths.
static float blockerSearch(KernelProbe& probe, const FilterFootprint& footprint, const Sampler& sampler, glm::ivec2 pixel,
                           glm::vec3 coord, glm::vec2 searchUv, float slope, int res, int m) {
    const int ns = std::max(footprint.searchTaps, 1);
    const std::vector<glm::vec2> search = discSet(ns, m, footprint.searchSeed, pixel);
    const float searchRim = slope * std::max(searchUv.x, searchUv.y) * float(res);
    float depthSum = 0.0f;
    for (int k = 0; k < ns * ns; ++k) {
        KernelTap tap;
        tap.stage = KernelTap::Stage::Search;
        tap.uv = glm::vec2(coord) + search[size_t(k)] * searchUv;
        const float d = sampler.fetch(tap.uv);
        const bool blocker = d < coord.z - searchRim * glm::length(search[size_t(k)]);
        tap.lit = blocker ? 0.0f : 1.0f;
        if (blocker) {
            depthSum += lightLinearDepth(d, footprint.lightDepth);
            ++probe.blockers;
        }
        probe.taps.push_back(tap);
    }
    probe.searchSamples = ns * ns;
    probe.samplesTaken = ns * ns;
    return depthSum;
}

KernelProbe probeKernel(const FilterFootprint& footprint, const ShadowMapInfo& map, const ProbeQuad& quad,
                        glm::ivec2 pixel, const DepthFetch& depth) {
    KernelProbe probe;
    probe.kernel = footprint.kernel;
    const glm::ivec2 local = pixel - quad.origin;
    if (local.x < 0 || local.y < 0 || local.x > 1 || local.y > 1) {
        probe.problem = "the pixel is not in its quad";
        return probe;
    }
    const int self = local.y * 2 + local.x;
    if (footprint.kernel == FilterKernel::None) {
        probe.problem = "the technique reports no filter kernel";
        return probe;
    }
    if (!footprint.depthTexture || footprint.lightDepth.w < 1.0f) {
        probe.problem = "the technique reports no depth map to probe";
        return probe;
    }
    if (quad.position[self].w < 0.5f) {
        probe.problem = "no geometry under the pixel";
        return probe;
    }
    probe.world = glm::vec3(quad.position[self]);
    probe.normal = glm::normalize(quad.normal[self]);
    probe.resolution = footprint.lightDepth.w;
    const int res = int(footprint.lightDepth.w);
    const Sampler sampler{depth, res};
    const glm::vec2 worldSize(footprint.lightWorldSize);
    const glm::vec3 axis(footprint.lightAxis);
    const bool bilinear = footprint.bilinear != 0;
    auto coordOf = [&](glm::vec3 world) { return shadowMapCoord(map.worldToClip, world); };
    probe.coord = coordOf(probe.world);
    if (!insideShadowMap(probe.coord)) {
        probe.problem = "the point is outside the shadow map";
        return probe;
    }
    const glm::vec3 coord = probe.coord;
    const float slope = footprint.coneBias * receiverDepthSlope(probe.normal, axis, coord.z, footprint.lightDepth, worldSize);
    probe.valid = true;
    probe.n = footprint.taps;
    const int n = std::max(footprint.taps, 1);

    if (footprint.kernel == FilterKernel::Box) {
        probeBox(probe, footprint, sampler, coord, res, bilinear, slope, n);
        return probe;
    }

    if (footprint.kernel == FilterKernel::Disc) {
        probeDisc(probe, footprint, sampler, quad, pixel, coord, res, bilinear, slope, n, axis, worldSize, map.worldToClip);
        return probe;
    }

    // Pcss: plugins/pcss/pcss.glsl's shadowTerm, 2D map.
    const bool perspective = footprint.lightDepth.z > 0.5f;
    const float lightSize = footprint.lightSize;
    const float zReceiver = lightLinearDepth(coord.z, footprint.lightDepth);
    probe.receiverDepth = zReceiver;
    auto searchRadius = [&](float zr, float zn) {
        return perspective ? lightSize / (worldSize * zn) * (zr - zn) / zr : lightSize * (zr - zn) / worldSize;
    };
    float zNear = perspective ? footprint.lightDepth.x : 0.0f;
    glm::vec2 searchUv = searchRadius(zReceiver, zNear);
    probe.searchNear = zNear;
    probe.searchRadiusTexels = std::max(searchUv.x, searchUv.y) * float(res);
    if (footprint.searchBound >= 1) {
        for (int i = 0; i < 2; ++i) {
            zNear = std::max(zNear, lightLinearDepth(sampler.depthRangeIn(glm::vec2(coord), searchUv).x, footprint.lightDepth));
            probe.searchNear = zNear;
            if (zNear >= zReceiver) {
                probe.decision = "nothing nearer the light";
                probe.lit = 1.0f;
                return probe;
            }
            searchUv = searchRadius(zReceiver, zNear);
            probe.searchRadiusTexels = std::max(searchUv.x, searchUv.y) * float(res);
        }
    }
    if (footprint.searchBound == 2) {
        const float searchTexels = std::max(std::max(searchUv.x, searchUv.y) * float(res), 1.0f);
        const glm::vec2 regionUv((searchTexels + 1.0f) / float(res));
        if (sampler.depthRangeIn(glm::vec2(coord), regionUv).y < coord.z - slope * searchTexels) {
            probe.decision = "fully blocked";
            probe.lit = 0.0f;
            return probe;
        }
    }
    const int m = std::max(footprint.sets, 1);
    const float depthSum = blockerSearch(probe, footprint, sampler, pixel, coord, searchUv, slope, res, m);
    if (probe.blockers == 0) {
        probe.decision = "no blocker";
        probe.lit = 1.0f;
        return probe;
    }
    probe.decision = "searched";
    const float zBlocker = depthSum / float(probe.blockers);
    probe.averageBlockerDepth = zBlocker;
    // eq. 3.19-3.20 (pcss.glsl's step 2), at least one texel.
    glm::vec2 filterUv = perspective ? (zReceiver - zBlocker) / zBlocker * lightSize / (worldSize * zReceiver)
                                     : (zReceiver - zBlocker) * lightSize / worldSize;
    filterUv = glm::max(filterUv, glm::vec2(1.0f / float(res)));
    probe.filterRadiusTexels = std::max(filterUv.x, filterUv.y) * float(res);
    probe.kernelTexels = 2.0f * probe.filterRadiusTexels;
    // The penumbra's world width at the receiver: the filter disc's diameter in world units there.
    const float texelWorld = std::max(worldSize.x, worldSize.y) / float(res) * (perspective ? zReceiver : 1.0f);
    probe.penumbraWorld = probe.kernelTexels * texelWorld;
    const int nf = std::max(footprint.taps, 1);
    probe.n = nf;
    adaptiveDisc(probe, sampler, discSet(nf, m, footprint.discSeed, pixel), nf, coord, filterUv,
                 slope * std::max(filterUv.x, filterUv.y) * float(res), bilinear, true);
    return probe;
}

std::string describeProbe(const KernelProbe& probe) {
    if (!probe.valid) return "kernel: " + probe.problem;
    char text[512];
    switch (probe.kernel) {
    case FilterKernel::Box:
        std::snprintf(text, sizeof(text), "PCF box %d x %d taps, %.3g texels wide, %d samples, lit %.3f", probe.n, probe.n,
                      double(probe.kernelTexels), probe.samplesTaken, double(probe.lit));
        break;
    case FilterKernel::Disc:
        std::snprintf(text, sizeof(text), "adaptive disc %d x %d samples, radius %.3g texels (%.3g wide), %d samples taken%s, lit %.3f",
                      probe.n, probe.n, double(probe.filterRadiusTexels), double(probe.kernelTexels), probe.samplesTaken,
                      probe.earlyOut ? " (early out after the outer ring)" : "", double(probe.lit));
        break;
    default:
        std::snprintf(text, sizeof(text),
                      "PCSS %s: search radius %.3g texels (cone at depth %.4g), blockers in %d of %d search samples, average blocker depth "
                      "%.4g (receiver %.4g), penumbra %.3g texels wide (%.4g world), filter %d x %d, %d samples taken%s, lit %.3f",
                      probe.decision.c_str(), double(probe.searchRadiusTexels), double(probe.searchNear), probe.blockers,
                      probe.searchSamples, double(probe.averageBlockerDepth), double(probe.receiverDepth),
                      double(probe.kernelTexels), double(probe.penumbraWorld), probe.n, probe.n, probe.samplesTaken,
                      probe.earlyOut ? " (filter stopped after the outer ring)" : "", double(probe.lit));
        break;
    }
    return text;
}

glm::vec3 onReceiverPlane(const ShadowMapInfo& map, const KernelProbe& probe, glm::vec2 uv) {
    const glm::mat4 inverse = glm::inverse(map.worldToClip);
    const glm::vec2 ndc = uv * 2.0f - 1.0f;
    const glm::vec4 a = inverse * glm::vec4(ndc, -1.0f, 1.0f), b = inverse * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(a) / a.w, direction = glm::vec3(b) / b.w - origin;
    const float denominator = glm::dot(probe.normal, direction);
    if (std::abs(denominator) < 1e-8f) return probe.world;
    return origin + direction * (glm::dot(probe.normal, probe.world - origin) / denominator);
}

} // namespace shadowlab

namespace shadowlab {

float kernelPixelRadius(const ShadowMapInfo& map, const KernelProbe& probe, const glm::mat4& viewProjection, glm::ivec2 viewport) {
    auto pixel = [&](glm::vec3 world) {
        const glm::vec4 clip = viewProjection * glm::vec4(world, 1.0f);
        return clip.w > 1e-6f ? (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(viewport) : glm::vec2(1e9f);
    };
    const glm::vec2 centre(probe.coord);
    std::vector<glm::vec2> rim;
    if (probe.kernel == FilterKernel::Box) {
        rim = {probe.boxMin, probe.boxMax, {probe.boxMin.x, probe.boxMax.y}, {probe.boxMax.x, probe.boxMin.y}};
    } else {
        const float r = std::max(probe.searchRadiusTexels, probe.filterRadiusTexels) / std::max(probe.resolution, 1.0f);
        for (int i = 0; i < 8; ++i) rim.push_back(centre + r * glm::vec2(std::cos(0.785398f * float(i)), std::sin(0.785398f * float(i))));
    }
    const glm::vec2 at = pixel(onReceiverPlane(map, probe, centre));
    float radius = 0.0f;
    for (const glm::vec2 uv : rim) radius = std::max(radius, glm::distance(at, pixel(onReceiverPlane(map, probe, uv))));
    return std::min(radius, 1e6f);
}

} // namespace shadowlab
