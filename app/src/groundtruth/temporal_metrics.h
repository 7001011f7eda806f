// Temporal accuracy along a camera or light path (issue 12): how a technique's shadow term changes
// from one frame to the next, against how the ray-traced reference changes at the same surface
// points. Pure CPU, no Embree; the per-frame images are those of App::evaluate (metrics.h).
//
// Two ways to bring the previous frame to the current pixels. Exact (compareAtSamePoints): the
// previous frame's maps and light evaluated at the current pixels' world positions. Reprojected
// (compareConsecutiveFrames), for terms that exist only per pixel of their own view: the current
// pixel's world position p goes through the previous view-projection to a point of the previous
// image, whose technique and reference values are interpolated bilinearly from its 4 nearest
// pixels. A pixel counts as visible in both frames when it is compared now (metrics.h
// compareMask) and all 4 previous pixels were compared and hold world positions within 5% of the
// view distance of p (else it was hidden, off screen or on another surface: a disocclusion).
// Bilinear rather than nearest: at a shadow edge under sub-pixel motion the nearest previous
// pixel shows another surface point, and both the technique and the reference would change there.
//
//   flicker (temporal error)  E_t = mean |(v_t - v'_{t-1}) - (r_t - r'_{t-1})| over pixels visible
//                             in both (v technique, r reference, ' reprojected; scalar visibility
//                             = mean of r, g, b). Zero when the technique changes exactly as the
//                             truth does: shimmer, crawling edges and noise raise it, a shadow
//                             moving with a moving light does not.
//   popping                   the largest single-frame jump of E along a path, max_t (E_t - E_{t-1}):
//                             a fit that changes, a cascade that switches.
//   noise (temporal variance) mean of (v_t - v'_{t-1})^2 / 2 over pixels visible in both where the
//                             reference is constant (|r_t - r'_{t-1}| < 1e-4): for a technique whose
//                             value at a point is the truth plus independent noise of variance s^2 each
//                             frame, the expectation is s^2 (exact under a still camera, where the
//                             reprojection lands on pixel centres).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace shadowlab {

// What one frame of a path leaves for the next. Images are width * height, rows bottom-up as the
// G-buffer is read (row 0 is NDC y = -1).
struct TemporalFrame {
    int width = 0, height = 0;
    std::vector<glm::vec4> positions;     // world; w = 1 where geometry was drawn
    std::vector<glm::vec3> technique, reference;
    std::vector<uint8_t> mask;            // compared pixels (metrics.h compareMask)
    glm::mat4 viewProjection{1.0f};
    glm::vec3 eye{0.0f};
};

struct TemporalFrameMetrics {
    double flicker = 0.0;         // E_t
    double noiseVariance = 0.0;
    size_t pixels = 0;            // visible in both frames
    size_t constantPixels = 0;    // of those, where the reference did not change
};

// Per-pixel changes of one comparison (for images of the worst frame): at pixels visible in both,
// deltaTechnique = v_t - v'_{t-1} and deltaReference = r_t - r'_{t-1}; 0 and valid = 0 elsewhere.
struct TemporalChanges {
    std::vector<float> deltaTechnique, deltaReference;
    std::vector<uint8_t> valid;
};

// E_t and the noise of `current` against `previous` (which may differ in camera and light, not in
// size). Throws std::invalid_argument when the sizes differ or an image is not width * height.
// `region` (optional, width * height): only pixels where it is 1 are counted.
TemporalFrameMetrics compareConsecutiveFrames(const TemporalFrame& previous, const TemporalFrame& current,
                                              TemporalChanges* changes = nullptr, const std::vector<uint8_t>* region = nullptr);

// The exact form, without resampling: the previous frame's technique and reference evaluated at
// the current frame's own pixels (its shadow maps and light applied to the current world
// positions, App::renderAccuracyTargetsFrom), so each pixel compares the same surface point in
// both frames and no pixel is lost to disocclusion. Same definitions as above, over the pixels
// of `mask` (and `region` when given).
TemporalFrameMetrics compareAtSamePoints(const std::vector<glm::vec3>& previousTechnique,
                                         const std::vector<glm::vec3>& previousReference, const TemporalFrame& current,
                                         TemporalChanges* changes = nullptr, const std::vector<uint8_t>* region = nullptr);

struct TemporalSummary {
    double meanFlicker = 0.0;     // mean of E_t over the path's comparisons
    double maxFlicker = 0.0;
    int worstFrame = -1;          // index of the frame (t) with the largest E_t
    double popping = 0.0;         // max_t (E_t - E_{t-1}), 0 when E never rises
    int poppingFrame = -1;
    double meanNoise = 0.0;       // mean temporal variance over the comparisons
    int comparisons = 0;
};

// `frames[k]` is the comparison of frame k + 1 with frame k.
TemporalSummary summarizeTemporal(const std::vector<TemporalFrameMetrics>& frames);

} // namespace shadowlab
