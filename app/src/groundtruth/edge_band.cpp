// The edge band around the hard reference's shadow boundaries (see edge_band.h).
#include "groundtruth/edge_band.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shadowlab {
namespace {

float edgeBandScalar(glm::vec3 v) { return (v.r + v.g + v.b) / 3.0f; }

// Max filter of `in` over [-radius, radius] along one axis (stride 1: rows, width: columns).
std::vector<uint8_t> dilateAxis(const std::vector<uint8_t>& in, int width, int height, int radius, bool alongRows) {
    std::vector<uint8_t> out(in.size(), 0);
    const int length = alongRows ? width : height, lines = alongRows ? height : width;
    for (int line = 0; line < lines; ++line)
        for (int i = 0; i < length; ++i) {
            const auto at = [&](int k) { return alongRows ? size_t(line) * size_t(width) + size_t(k)
                                                          : size_t(k) * size_t(width) + size_t(line); };
            if (!in[at(i)]) continue;
            for (int k = std::max(i - radius, 0); k <= std::min(i + radius, length - 1); ++k) out[at(k)] = 1;
        }
    return out;
}

} // namespace

std::vector<uint8_t> edgeBand(const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask, int width,
                              int height, int radius) {
    const size_t count = size_t(width) * size_t(height);
    if (reference.size() != count || mask.size() != count)
        throw std::invalid_argument("edgeBand: the reference and the mask must be width * height");
    std::vector<uint8_t> boundary(count, 0);
    const auto lit = [&](size_t i) { return edgeBandScalar(reference[i]) >= 0.5f; };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            if (!mask[i]) continue;
            // Right and upper neighbours: each differing pair marks both of its pixels.
            for (const size_t j : {x + 1 < width ? i + 1 : i, y + 1 < height ? i + size_t(width) : i}) {
                if (j == i || !mask[j] || lit(i) == lit(j)) continue;
                boundary[i] = boundary[j] = 1;
            }
        }
    std::vector<uint8_t> band = dilateAxis(dilateAxis(boundary, width, height, radius, true), width, height, radius, false);
    for (size_t i = 0; i < count; ++i) band[i] = band[i] && mask[i] ? 1 : 0;
    return band;
}

EdgeBandMetrics edgeBandMetrics(const std::vector<uint8_t>& band, const std::vector<glm::vec3>& technique,
                                const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask) {
    EdgeBandMetrics m;
    if (band.size() != mask.size() || technique.size() != mask.size() || reference.size() != mask.size())
        throw std::invalid_argument("edgeBandMetrics: the band, images and mask must be the same size");
    double inSum = 0.0, offSum = 0.0;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const double error = std::abs(double(edgeBandScalar(technique[i])) - double(edgeBandScalar(reference[i])));
        if (band[i]) {
            inSum += error;
            ++m.bandPixels;
        } else {
            offSum += error;
            ++m.offPixels;
        }
    }
    m.mae = m.bandPixels ? inSum / double(m.bandPixels) : 0.0;
    m.maeOff = m.offPixels ? offSum / double(m.offPixels) : 0.0;
    return m;
}

} // namespace shadowlab
