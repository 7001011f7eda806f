// Temporal accuracy along a path (see temporal_metrics.h for every definition). Sums in double
// and in a fixed pixel order, so equal inputs give equal numbers.
#include "groundtruth/temporal_metrics.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace shadowlab {

namespace {

constexpr double kSurfaceTolerance = 0.05;    // of the view distance: farther is another surface
constexpr double kConstantReference = 1e-4;

float scalar(const glm::vec3& rgb) { return (rgb.r + rgb.g + rgb.b) / 3.0f; }

void checkFrame(const TemporalFrame& f, const char* which) {
    const size_t pixels = size_t(std::max(f.width, 0)) * size_t(std::max(f.height, 0));
    if (f.positions.size() != pixels || f.technique.size() != pixels || f.reference.size() != pixels || f.mask.size() != pixels)
        throw std::invalid_argument(std::string("compareConsecutiveFrames: the ") + which + " frame's images are not " +
                                    std::to_string(f.width) + " x " + std::to_string(f.height));
}

// The per-pixel sums both comparisons share: the technique's change dv against the reference's
// change dr at one pixel, and the frame's means from them.
class ChangeAccumulator {
public:
    ChangeAccumulator(size_t pixels, TemporalChanges* changes) : changes_(changes) {
        if (!changes_) return;
        changes_->deltaTechnique.assign(pixels, 0.0f);
        changes_->deltaReference.assign(pixels, 0.0f);
        changes_->valid.assign(pixels, 0);
    }
    void add(size_t i, double dv, double dr) {
        ++m_.pixels;
        sumFlicker_ += std::abs(dv - dr);
        if (std::abs(dr) < kConstantReference) {
            ++m_.constantPixels;
            sumNoise_ += 0.5 * dv * dv;
        }
        if (changes_) {
            changes_->deltaTechnique[i] = float(dv);
            changes_->deltaReference[i] = float(dr);
            changes_->valid[i] = 1;
        }
    }
    TemporalFrameMetrics result() const {
        TemporalFrameMetrics m = m_;
        m.flicker = m.pixels ? sumFlicker_ / double(m.pixels) : 0.0;
        m.noiseVariance = m.constantPixels ? sumNoise_ / double(m.constantPixels) : 0.0;
        return m;
    }

private:
    TemporalChanges* changes_;
    TemporalFrameMetrics m_;
    double sumFlicker_ = 0.0, sumNoise_ = 0.0;
};

} // namespace

TemporalFrameMetrics compareConsecutiveFrames(const TemporalFrame& previous, const TemporalFrame& current,
                                              TemporalChanges* changes, const std::vector<uint8_t>* region) {
    checkFrame(previous, "previous");
    checkFrame(current, "current");
    if (previous.width != current.width || previous.height != current.height)
        throw std::invalid_argument("compareConsecutiveFrames: the two frames differ in size");
    const int w = current.width, h = current.height;
    const size_t pixels = size_t(w) * size_t(h);
    if (region && region->size() != pixels) throw std::invalid_argument("compareConsecutiveFrames: the region is not width x height");
    ChangeAccumulator sums(pixels, changes);
    for (size_t i = 0; i < pixels; ++i) {
        if (!current.mask[i] || (region && !(*region)[i])) continue;
        const glm::vec3 p = glm::vec3(current.positions[i]);
        const glm::vec4 clip = previous.viewProjection * glm::vec4(p, 1.0f);
        if (!(clip.w > 1e-9f)) continue;
        // Pixel coordinates of the previous image, pixel centres at integers.
        const double px = (double(clip.x) / clip.w * 0.5 + 0.5) * w - 0.5;
        const double py = (double(clip.y) / clip.w * 0.5 + 0.5) * h - 0.5;
        const double x0 = std::floor(px), y0 = std::floor(py);
        if (!(x0 >= 0.0 && y0 >= 0.0 && x0 + 1.0 <= w - 1 && y0 + 1.0 <= h - 1)) continue;
        const double fx = px - x0, fy = py - y0;
        const double tolerance = kSurfaceTolerance * double(glm::length(p - current.eye));
        double v = 0.0, r = 0.0;
        bool visible = true;
        for (int k = 0; k < 4 && visible; ++k) {
            const size_t j = size_t(y0 + (k >> 1)) * size_t(w) + size_t(x0 + (k & 1));
            const double weight = ((k & 1) ? fx : 1.0 - fx) * ((k >> 1) ? fy : 1.0 - fy);
            visible = previous.mask[j] && glm::length(glm::vec3(previous.positions[j]) - p) <= tolerance;
            v += weight * scalar(previous.technique[j]);
            r += weight * scalar(previous.reference[j]);
        }
        if (!visible) continue;
        const double dv = double(scalar(current.technique[i])) - v;
        const double dr = double(scalar(current.reference[i])) - r;
        sums.add(i, dv, dr);
    }
    return sums.result();
}

TemporalFrameMetrics compareAtSamePoints(const std::vector<glm::vec3>& previousTechnique,
                                         const std::vector<glm::vec3>& previousReference, const TemporalFrame& current,
                                         TemporalChanges* changes, const std::vector<uint8_t>* region) {
    checkFrame(current, "current");
    const size_t pixels = current.mask.size();
    if (previousTechnique.size() != pixels || previousReference.size() != pixels || (region && region->size() != pixels))
        throw std::invalid_argument("compareAtSamePoints: the previous images or the region are not width x height");
    ChangeAccumulator sums(pixels, changes);
    for (size_t i = 0; i < pixels; ++i) {
        if (!current.mask[i] || (region && !(*region)[i])) continue;
        const double dv = double(scalar(current.technique[i])) - double(scalar(previousTechnique[i]));
        const double dr = double(scalar(current.reference[i])) - double(scalar(previousReference[i]));
        sums.add(i, dv, dr);
    }
    return sums.result();
}

TemporalSummary summarizeTemporal(const std::vector<TemporalFrameMetrics>& frames) {
    TemporalSummary s;
    s.comparisons = int(frames.size());
    if (frames.empty()) return s;
    double sumFlicker = 0.0, sumNoise = 0.0;
    for (size_t k = 0; k < frames.size(); ++k) {
        sumFlicker += frames[k].flicker;
        sumNoise += frames[k].noiseVariance;
        if (s.worstFrame < 0 || frames[k].flicker > s.maxFlicker) {
            s.maxFlicker = frames[k].flicker;
            s.worstFrame = int(k) + 1;
        }
        if (k > 0 && frames[k].flicker - frames[k - 1].flicker > s.popping) {
            s.popping = frames[k].flicker - frames[k - 1].flicker;
            s.poppingFrame = int(k) + 1;
        }
    }
    s.meanFlicker = sumFlicker / double(frames.size());
    s.meanNoise = sumNoise / double(frames.size());
    return s;
}

} // namespace shadowlab
