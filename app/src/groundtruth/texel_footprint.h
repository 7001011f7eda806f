// The shadow map's texel footprint on the screen, per pixel: how many pixels one texel covers
// along the worst direction, from the maps the technique reported (SHADOWLAB_EXT_SHADOW_MAPS)
// and the G-buffer. This is seed 002 eq. 8.1's dp/ds with real units (Lloyd et al. 2006's
// aliasing measure m): m > 1 is undersampling (one texel spread over m pixels: jagged,
// perspective-aliased shadow edges), m < 1 spends 1/m texels on one pixel. It is measured
// exactly, not by finite differences across pixels: each pixel's two neighbouring camera rays
// meet the pixel's tangent plane, and the three points go through the map's matrix to texels.
// Pure CPU; host measurement code only.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "groundtruth/groundtruth.h"
#include "shadowlab/technique.h"
#include "util/image.h"

namespace shadowlab {

struct TexelFootprint {
    int width = 0;
    int height = 0;
    // Per pixel (G-buffer order): m, and seed 002 eq. 6.1's projection term cos(alpha) /
    // cos(beta) (alpha between view vector and normal, beta between light vector and normal;
    // > 1 is projection aliasing). 0 where not measured (excluded by the mask, no map serves
    // the pixel, or the tangent plane is seen edge-on).
    std::vector<float> m;
    std::vector<float> projection;
    // Per pixel: seed 002's one-dimensional error of sec. 8.2 (eq. 8.2-8.9): pixels per texel along
    // the screen direction in which the receiver recedes from the viewer (where view depth grows
    // fastest), with eq. 6.1's projection term cos(alpha) / cos(beta) divided out, as eq. 8.2-8.9
    // assume it 1. 0 where not measured.
    std::vector<float> depthError;
    // Over measured pixels: percentiles of m, the fraction undersampled (m > 1), and the
    // median of m in the near, mid and far thirds of the camera's [near, far] view depth.
    double median = 0.0;
    double p95 = 0.0;
    double max = 0.0;
    double undersampledFraction = 0.0;
    std::array<double, 3> medianByViewDepth{};
    double projectionMedian = 0.0;
    double projectionP95 = 0.0;
    size_t measuredPixels = 0;
    // Compared pixels that no reported map covers (a cascade that misses its slice shows here).
    size_t uncoveredPixels = 0;
    size_t maps = 0;
    // The error against view depth (seed 002 Figs. 8.7 and 9.3): measured pixels in
    // kFootprintDepthBins bins, log-spaced over the camera's [near, far]; empty bins kept (pixels 0).
    struct DepthBin {
        double begin = 0.0, end = 0.0;   // view-depth range of the bin
        double depth = 0.0;              // median view depth of its pixels
        double m = 0.0;                  // median m
        double depthError = 0.0;         // median depthError
        size_t pixels = 0;
    };
    std::vector<DepthBin> byViewDepth;
};

inline constexpr int kFootprintDepthBins = 48;

// The map that serves a world point at camera view distance `viewDistance`: the first in order
// whose view-distance range holds it and whose clip volume holds the point; -1 when none does.
int servingShadowMap(const std::vector<ShadowMapInfo>& maps, const glm::vec3& world, float viewDistance);

// m at one surface point p with normal n, seen by `camera` on a viewport of camera.viewport
// pixels, in `map`; 0 when the point is behind the map's projection or the plane is edge-on.
float texelFootprintAt(const CameraInfo& camera, const ShadowMapInfo& map, const glm::vec3& p, const glm::vec3& n);

// Measures every pixel where mask is 1 (compareMask). No maps: measuredPixels = 0, all zero.
// Throws std::invalid_argument when the mask or the G-buffer is not width * height.
TexelFootprint measureTexelFootprint(const GBufferView& gbuffer, const std::vector<uint8_t>& mask,
                                     const CameraInfo& camera, const LightInfo& light,
                                     const std::vector<ShadowMapInfo>& maps);

// RGBA heat map of log2 m (the footprint debug view): blue m <= 1/16 (texels wasted), grey-green
// m = 1, red m >= 16 (texels far too large); dark grey where not measured.
Image footprintHeatmap(const TexelFootprint& footprint);

// One JSON object of the summary fields (with "byViewDepth": an array of {begin, end, depth, m,
// depthError, pixels}); indent < 0: one line.
std::string footprintToJson(const TexelFootprint& footprint, int indent = -1);

} // namespace shadowlab
