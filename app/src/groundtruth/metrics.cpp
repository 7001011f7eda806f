// Per-pixel accuracy of a technique against the ray-traced reference (see metrics.h for every
// definition). Sums are in double, per fixed band of pixels on every core, and the bands are added
// in order, so equal inputs give equal numbers on any machine.
#include "groundtruth/metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "util/parallel.h"

namespace shadowlab {

namespace {

constexpr float kLitThreshold = 0.5f;   // reference >= 0.5: lit; technique < 0.5: shadowed
constexpr float kPenumbraLow = 0.02f;   // reference strictly between these: partial visibility
constexpr float kPenumbraHigh = 0.98f;

constexpr size_t kPixelChunk = 16384;   // pixels a chunk of per-pixel work (util/parallel.h)

float scalarVisibility(const glm::vec3& rgb) { return (rgb.r + rgb.g + rgb.b) / 3.0f; }

void checkSizes(size_t technique, size_t reference, size_t mask, int width, int height, const char* what) {
    if (width < 0 || height < 0)
        throw std::invalid_argument(std::string(what) + ": negative image size");
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (technique != pixels || reference != pixels || mask != pixels)
        throw std::invalid_argument(std::string(what) + ": technique (" + std::to_string(technique) +
                                    "), reference (" + std::to_string(reference) + ") and mask (" +
                                    std::to_string(mask) + ") must each have " + std::to_string(width) + " x " +
                                    std::to_string(height) + " pixels");
}

// The penumbra class of metrics.h: compared pixel (x, y) with 0.02 < reference < 0.98, or with a
// compared 8-neighbour on the other side of 0.5.
bool inPenumbra(const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask, int x, int y, int width,
                int height) {
    const float ref = scalarVisibility(reference[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]);
    if (ref > kPenumbraLow && ref < kPenumbraHigh) return true;
    const bool refLit = ref >= kLitThreshold;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
            const size_t j = static_cast<size_t>(ny) * static_cast<size_t>(width) + static_cast<size_t>(nx);
            // Excluded neighbours hold no visibility (0 by convention): not a shadow edge.
            if (mask[j] && (scalarVisibility(reference[j]) >= kLitThreshold) != refLit) return true;
        }
    }
    return false;
}

} // namespace

std::vector<uint8_t> compareMask(const GBufferView& gbuffer, const LightInfo& light) {
    const size_t pixels = static_cast<size_t>(std::max(gbuffer.width, 0)) * static_cast<size_t>(std::max(gbuffer.height, 0));
    std::vector<uint8_t> mask(pixels, 0);
    if (pixels > 0 && (!gbuffer.positions || !gbuffer.normals))
        throw std::invalid_argument("compareMask: G-buffer without positions or normals");
    forEachChunk(pixels, kPixelChunk, [&](size_t, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) mask[i] = facesLight(gbuffer.positions[i], gbuffer.normals[i], light) ? 1 : 0;
    });
    return mask;
}

namespace {

// One band of rows' share of compareVisibility's sums, combined in band order (util/parallel.h).
struct VisibilitySums {
    double abs = 0.0, squared = 0.0, penumbra = 0.0, outside = 0.0, noise = 0.0;
    glm::dvec3 channels{0.0};
    size_t compared = 0, penumbraPixels = 0, falseShadow = 0, falseLight = 0, techniquePenumbra = 0, noiseSamples = 0;

    void add(const VisibilitySums& o) {
        abs += o.abs, squared += o.squared, penumbra += o.penumbra, outside += o.outside, noise += o.noise;
        channels += o.channels;
        compared += o.compared, penumbraPixels += o.penumbraPixels, falseShadow += o.falseShadow;
        falseLight += o.falseLight, techniquePenumbra += o.techniquePenumbra, noiseSamples += o.noiseSamples;
    }
};

constexpr size_t kRowChunk = 8;

VisibilitySums visibilitySumsOfRows(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                                    const std::vector<uint8_t>& mask, int width, int height, int rowBegin, int rowEnd) {
    VisibilitySums s;
    auto signedError = [&](size_t i) {
        return static_cast<double>(scalarVisibility(technique[i])) - static_cast<double>(scalarVisibility(reference[i]));
    };
    for (int y = rowBegin; y < rowEnd; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
            if (!mask[i]) continue;
            const float ref = scalarVisibility(reference[i]);
            const float tech = scalarVisibility(technique[i]);
            const double error = std::abs(static_cast<double>(tech) - static_cast<double>(ref));
            ++s.compared;
            s.abs += error;
            s.squared += error * error;
            s.channels += glm::abs(glm::dvec3(technique[i]) - glm::dvec3(reference[i]));
            const bool refLit = ref >= kLitThreshold;
            if (refLit && tech < kLitThreshold) ++s.falseShadow;
            if (!refLit && tech > kLitThreshold) ++s.falseLight;
            if (inPenumbra(reference, mask, x, y, width, height)) {
                ++s.penumbraPixels;
                s.penumbra += error;
            } else {
                s.outside += error;
            }
            if (tech > kPenumbraLow && tech < kPenumbraHigh) ++s.techniquePenumbra;
            // Noise: the error against the mean of its four neighbours' errors, interior pixels
            // whose neighbours are all compared.
            if (x == 0 || y == 0 || x + 1 == width || y + 1 == height) continue;
            const size_t neighbours[4] = {i - 1, i + 1, i - static_cast<size_t>(width), i + static_cast<size_t>(width)};
            double mean = 0.0;
            bool all = true;
            for (size_t j : neighbours) {
                all = all && mask[j];
                mean += signedError(j);
            }
            if (!all) continue;
            s.noise += std::abs(signedError(i) - 0.25 * mean);
            ++s.noiseSamples;
        }
    }
    return s;
}

} // namespace

AccuracyMetrics compareVisibility(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                                  const std::vector<uint8_t>& mask, int width, int height) {
    checkSizes(technique.size(), reference.size(), mask.size(), width, height, "compareVisibility");
    AccuracyMetrics m;
    const size_t pixels = reference.size();
    if (pixels == 0) return m;

    std::vector<VisibilitySums> bands(chunkCount(size_t(height), kRowChunk));
    forEachChunk(size_t(height), kRowChunk, [&](size_t band, size_t begin, size_t end) {
        bands[band] = visibilitySumsOfRows(technique, reference, mask, width, height, int(begin), int(end));
    });
    VisibilitySums s;
    for (const VisibilitySums& band : bands) s.add(band);

    m.comparedPixels = s.compared;
    m.penumbraPixels = s.penumbraPixels;
    m.comparedFraction = static_cast<double>(m.comparedPixels) / static_cast<double>(pixels);
    if (m.comparedPixels == 0) return m;
    const auto compared = static_cast<double>(m.comparedPixels);
    m.mae = s.abs / compared;
    m.rmse = std::sqrt(s.squared / compared);
    m.maePerChannel = s.channels / compared;
    m.falseShadowRate = static_cast<double>(s.falseShadow) / compared;
    m.falseLightRate = static_cast<double>(s.falseLight) / compared;
    const size_t outside = m.comparedPixels - m.penumbraPixels;
    m.maePenumbra = m.penumbraPixels ? s.penumbra / static_cast<double>(m.penumbraPixels) : 0.0;
    m.maeOutsidePenumbra = outside ? s.outside / static_cast<double>(outside) : 0.0;
    m.techniquePenumbraFraction = static_cast<double>(s.techniquePenumbra) / compared;
    m.noiseEnergy = s.noiseSamples ? s.noise / static_cast<double>(s.noiseSamples) : 0.0;
    return m;
}

void addViewDepthThirds(AccuracyMetrics& metrics, const std::vector<glm::vec3>& technique,
                        const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask,
                        const glm::vec4* positions, int width, int height, const glm::mat4& view, float nearPlane,
                        float farPlane) {
    checkSizes(technique.size(), reference.size(), mask.size(), width, height, "addViewDepthThirds");
    if (!(farPlane > nearPlane)) throw std::invalid_argument("addViewDepthThirds: empty depth range");
    if (!positions && !mask.empty()) throw std::invalid_argument("addViewDepthThirds: no positions");
    struct Thirds {
        std::array<double, 3> sums{};
        std::array<size_t, 3> pixels{};
    };
    std::vector<Thirds> chunks(chunkCount(mask.size(), kPixelChunk));
    forEachChunk(mask.size(), kPixelChunk, [&](size_t chunk, size_t begin, size_t end) {
        Thirds& t = chunks[chunk];
        for (size_t i = begin; i < end; ++i) {
            if (!mask[i]) continue;
            const float depth = -(view * glm::vec4(glm::vec3(positions[i]), 1.0f)).z;
            const int third = std::clamp(int(3.0f * (depth - nearPlane) / (farPlane - nearPlane)), 0, 2);
            t.sums[size_t(third)] += std::abs(static_cast<double>(scalarVisibility(technique[i])) -
                                              static_cast<double>(scalarVisibility(reference[i])));
            ++t.pixels[size_t(third)];
        }
    });
    std::array<double, 3> sums{};
    metrics.pixelsByViewDepth = {};
    for (const Thirds& t : chunks)
        for (size_t k = 0; k < 3; ++k) sums[k] += t.sums[k], metrics.pixelsByViewDepth[k] += t.pixels[k];
    for (size_t k = 0; k < 3; ++k)
        metrics.maeByViewDepth[k] = metrics.pixelsByViewDepth[k] ? sums[k] / double(metrics.pixelsByViewDepth[k]) : 0.0;
}

double penumbraMean(const std::vector<float>& values, const std::vector<glm::vec3>& reference,
                    const std::vector<uint8_t>& mask, int width, int height) {
    checkSizes(values.size(), reference.size(), mask.size(), width, height, "penumbraMean");
    std::vector<std::pair<double, size_t>> bands(chunkCount(size_t(height), kRowChunk));
    forEachChunk(size_t(height), kRowChunk, [&](size_t band, size_t begin, size_t end) {
        double sum = 0.0;
        size_t count = 0;
        for (int y = int(begin); y < int(end); ++y) {
            for (int x = 0; x < width; ++x) {
                const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
                if (!mask[i] || !inPenumbra(reference, mask, x, y, width, height)) continue;
                sum += static_cast<double>(values[i]);
                ++count;
            }
        }
        bands[band] = {sum, count};
    });
    double sum = 0.0;
    size_t count = 0;
    for (const auto& [bandSum, bandCount] : bands) sum += bandSum, count += bandCount;
    return count ? sum / static_cast<double>(count) : 0.0;
}

std::vector<uint8_t> errorHeatmap(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                                  const std::vector<uint8_t>& mask, int width, int height) {
    checkSizes(technique.size(), reference.size(), mask.size(), width, height, "errorHeatmap");
    const glm::vec3 falseShadowHue(255.0f, 0.0f, 255.0f); // magenta: technique darker
    const glm::vec3 falseLightHue(0.0f, 255.0f, 0.0f);    // green: technique brighter
    std::vector<uint8_t> rgb(reference.size() * 3, 24);   // excluded: dark grey
    for (size_t i = 0; i < reference.size(); ++i) {
        if (!mask[i]) continue;
        const float ref = std::clamp(scalarVisibility(reference[i]), 0.0f, 1.0f);
        const float error = scalarVisibility(technique[i]) - scalarVisibility(reference[i]);
        const float a = std::sqrt(std::min(std::abs(error), 1.0f));
        const glm::vec3 grey(56.0f + 72.0f * ref);
        const glm::vec3 colour = glm::mix(grey, error < 0.0f ? falseShadowHue : falseLightHue, a);
        for (int c = 0; c < 3; ++c)
            rgb[3 * i + static_cast<size_t>(c)] = static_cast<uint8_t>(std::lround(std::clamp(colour[c], 0.0f, 255.0f)));
    }
    return rgb;
}

std::string metricsToJson(const AccuracyMetrics& m, int indent) {
    const nlohmann::json json = {
        {"mae", m.mae},
        {"rmse", m.rmse},
        {"falseShadowRate", m.falseShadowRate},
        {"falseLightRate", m.falseLightRate},
        {"maePenumbra", m.maePenumbra},
        {"maeOutsidePenumbra", m.maeOutsidePenumbra},
        {"maePerChannel", {m.maePerChannel.r, m.maePerChannel.g, m.maePerChannel.b}},
        {"comparedFraction", m.comparedFraction},
        {"comparedPixels", m.comparedPixels},
        {"penumbraPixels", m.penumbraPixels},
        {"techniquePenumbraFraction", m.techniquePenumbraFraction},
        {"noiseEnergy", m.noiseEnergy},
        {"maeByViewDepth", m.maeByViewDepth},
        {"comparedPixelsByViewDepth", m.pixelsByViewDepth},
    };
    return json.dump(indent);
}

} // namespace shadowlab
