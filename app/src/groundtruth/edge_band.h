// The edge band (issue 28; docs/anti-aliased-edges.md): where anti-aliased hard-shadow techniques
// (rbsm, edtsm) claim to win. Against the HARD reference, a compared pixel is in the band when it
// lies within kEdgeBandRadius pixels (Chebyshev distance) of a boundary pixel: a compared pixel
// with a compared 4-neighbour of the other class (reference visibility >= 0.5 or not). A shadow
// map's staircase, a filter's blur and a revectorized edge all put their error there; the rest of
// the compared pixels ("off the band") show what a technique does away from edges (acne, leaks, or
// a staircase wider than the band where a texel covers many pixels). Pure CPU, no GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace shadowlab {

// Three pixels on either side: a 1 to 2 pixel hard edge, plus the half texel a staircase strays
// from it where a map texel covers up to about 5 pixels (512 maps on the test scenes' ground).
constexpr int kEdgeBandRadius = 3;

struct EdgeBandMetrics {
    size_t bandPixels = 0;   // compared pixels in the band
    double mae = 0.0;        // mean |technique - reference| of the scalar visibility over them (0 when none)
    size_t offPixels = 0;    // compared pixels outside the band
    double maeOff = 0.0;     // mean error over those
};

// 1 for compared pixels (mask) in the band around the reference's boundaries, else 0. Throws
// std::invalid_argument when a size is not width * height.
std::vector<uint8_t> edgeBand(const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask, int width,
                              int height, int radius = kEdgeBandRadius);

// The band's and the rest's mean error from edgeBand()'s classes.
EdgeBandMetrics edgeBandMetrics(const std::vector<uint8_t>& band, const std::vector<glm::vec3>& technique,
                                const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask);

} // namespace shadowlab
