// Accuracy of a shadow technique against the ray-traced reference (groundtruth.h), per pixel of
// one view: how wrong it is, and in which way (acne, leaks, blur, noise). Pure CPU, no Embree.
//
// Images are width * height linear RGB visibilities in [0, 1], in the G-buffer's row order. The
// scalar visibility of a pixel is the plain mean of r, g and b (not luminance: a coloured
// shadow's error should count every channel alike; per-channel errors are reported separately).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "groundtruth/groundtruth.h"

namespace shadowlab {

// 1 where a pixel is compared: drawn geometry facing the light (N.L > 0 with the G-buffer
// normal) and inside a spot light's cone; 0 for background and everything else, where the
// visibility of a shadow is not defined (facesLight() in groundtruth.h).
std::vector<uint8_t> compareMask(const GBufferView& gbuffer, const LightInfo& light);

// All rates and means are over compared pixels (0 when none is compared).
struct AccuracyMetrics {
    double mae = 0.0;                 // mean |technique - reference| of the scalar visibility
    double rmse = 0.0;                // root mean square of the same; weighs large errors (acne, leaks) up
    double falseShadowRate = 0.0;     // reference lit (>= 0.5), technique < 0.5: acne, over-darkening
    double falseLightRate = 0.0;      // reference shadowed (< 0.5), technique > 0.5: leaks, peter-panning, light bleeding
    double maePenumbra = 0.0;         // mean error over penumbra pixels (see below): blur, noise, banding
    double maeOutsidePenumbra = 0.0;  // mean error over the rest: acne, leaks, aliasing far from edges
    glm::dvec3 maePerChannel{0.0};    // mean |error| of r, g, b: coloured techniques
    double comparedFraction = 0.0;    // compared pixels / all pixels of the image
    // Fraction of compared pixels where the technique itself is between 0.02 and 0.98: how much
    // penumbra it draws (contact hardening compares this across caster heights).
    double techniquePenumbraFraction = 0.0;
    // High-frequency error: mean |e - mean of e over the 4 neighbours| with e = technique -
    // reference, over compared pixels whose 4 neighbours are compared. Noise, dithering and
    // banding raise it; a smooth bias or blur barely does.
    double noiseEnergy = 0.0;
    size_t comparedPixels = 0;
    size_t penumbraPixels = 0;
    // By view depth (addViewDepthThirds): mean |error| and compared pixels in the near, mid and far
    // thirds of the camera's depth range [near, far]. Perspective aliasing (seed 002 sec. 3.1) shows
    // as a large near-third error; focusing and warping the map should lower it. Zero until added.
    std::array<double, 3> maeByViewDepth{};
    std::array<size_t, 3> pixelsByViewDepth{};
    // Issue 30, against the hard reference only (groundtruth/contact_band.h): the false-light rate
    // over the contact band's compared pixels, and how many there are. Zero until added.
    double contactFalseLightRate = 0.0;
    size_t contactBandPixels = 0;
    // Issue 28, against the hard reference only (groundtruth/edge_band.h): mean error within
    // kEdgeBandRadius pixels of the reference's shadow boundaries and over the other compared
    // pixels, and how many are in the band. Zero until added.
    double maeEdgeBand = 0.0;
    double maeOffEdgeBand = 0.0;
    size_t edgeBandPixels = 0;
};

// Penumbra (reference side only): compared pixels with 0.02 < reference < 0.98, plus compared
// pixels within one pixel (8-neighbourhood) of a compared pixel whose lit/shadowed class
// (reference >= 0.5) differs, so a hard reference has a one-to-two-pixel boundary class too.
// Throws std::invalid_argument when an image or the mask is not width * height.
AccuracyMetrics compareVisibility(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                                  const std::vector<uint8_t>& mask, int width, int height);

// Fills maeByViewDepth and pixelsByViewDepth: each compared pixel's world position (`positions`,
// width * height, as the G-buffer holds them) goes to the third of [nearPlane, farPlane] its view
// depth -(view * p).z falls in (clamped into the first or last). Throws std::invalid_argument when
// a size is not width * height, or the range is empty.
void addViewDepthThirds(AccuracyMetrics& metrics, const std::vector<glm::vec3>& technique,
                        const std::vector<glm::vec3>& reference, const std::vector<uint8_t>& mask,
                        const glm::vec4* positions, int width, int height, const glm::mat4& view, float nearPlane,
                        float farPlane);

// Mean of `values` (one per pixel) over the penumbra pixels of `reference`, the same pixels
// maePenumbra averages over; 0 when there are none. With ReferenceStats::sampleError: the soft
// reference's own penumbra MAE, the floor below which a soft maePenumbra (or a difference
// between two) means nothing. Throws std::invalid_argument when a size is not width * height.
double penumbraMean(const std::vector<float>& values, const std::vector<glm::vec3>& reference,
                    const std::vector<uint8_t>& mask, int width, int height);

// RGB8 error image, width * height * 3 bytes, same row order as the input. With e = technique -
// reference (scalar visibility) and a = sqrt(min(|e|, 1)) (square root: a 0.1 error is already a
// third of the way to full colour):
//   excluded pixels (mask 0):        dark grey        (24, 24, 24)
//   compared pixels, base colour:    grey g = 56 + 72 * reference (56..128), the scene stays readable
//   technique darker (e < 0):        mix(g, magenta (255, 0, 255), a)   false shadow: acne, over-darkening
//   technique brighter (e > 0):      mix(g, green (0, 255, 0), a)       false light: leaks, bleeding
// Magenta and green stay apart for the common colour-vision deficiencies.
std::vector<uint8_t> errorHeatmap(const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                                  const std::vector<uint8_t>& mask, int width, int height);

// One JSON object with the fields above (maePerChannel as [r, g, b]); indent < 0: one line.
std::string metricsToJson(const AccuracyMetrics& metrics, int indent = -1);

} // namespace shadowlab
