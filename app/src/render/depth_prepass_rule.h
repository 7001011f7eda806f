// When the host's depth pre-pass runs (host.depth_prepass = off | on | auto; issue 32).
//
// The pre-pass costs one more geometry pass; it saves the main pass's shading of every fragment
// that a nearer one later hides. So `auto` decides from the frame's depth complexity: the
// fragments of the opaque surfaces that pass the depth test (GL_SAMPLES_PASSED around the pass
// that draws them with depth test LESS: the main pass without a pre-pass, the pre-pass itself
// with one, the same count either way) per sample of the target. The counter is read a few frames
// late (render/overdraw_counter.h), so no frame waits for it.
//
// The rule: on at or above kOnAbove fragments per sample, off at or below kOffBelow; between
// them, and for fewer than kConfirmations consecutive measurements beyond a threshold, the
// decision stands (hysteresis: a camera moving around a threshold does not make it flip-flop).
// The first measurement after a scene load decides at once (against the midpoint), so a
// benchmark's warm-up settles it. Before any measurement the pre-pass is off.
#pragma once

#include <cstdint>
#include <optional>

namespace shadowlab {

// host.depth_prepass's values, in the order of its enum labels: 0 and 1 keep meaning off and
// on, as in specs and sweeps written before `auto` existed.
enum class DepthPrepassMode : int { Off = 0, On = 1, Auto = 2 };
const char* depthPrepassModeName(DepthPrepassMode mode);

class DepthPrepassRule {
public:
    // Between the built-in scenes that gain and those that do not (docs/benchmarks.md "Depth
    // pre-pass"; 640x360, their own cameras): the test scenes, dense and the translucent ones
    // shade 0.28 to 0.93 fragments per sample, cubes-on-hills 1.9, forest-002 2.3, forest 2.8
    // (where an H200 ran pcss in 10.4 ms with the pre-pass, 37.5 ms without).
    static constexpr double kOnAbove = 1.6;
    static constexpr double kOffBelow = 1.3;
    static constexpr int kConfirmations = 3;

    // A new measurement (fragments per sample). Returns true when the auto decision changed.
    bool update(double complexity);
    // Forgets what was measured (a new scene): off until the next measurement.
    void reset() { *this = {}; }

    // What `auto` has decided (false before any measurement).
    bool autoDecision() const { return on_; }
    // Whether a frame with `mode` runs the pre-pass.
    bool active(DepthPrepassMode mode) const {
        return mode == DepthPrepassMode::On || (mode == DepthPrepassMode::Auto && on_);
    }
    bool measured() const { return complexity_.has_value(); }
    std::optional<double> complexity() const { return complexity_; }
    uint64_t measurements() const { return measurements_; }

private:
    bool on_ = false;
    int beyond_ = 0;                    // consecutive measurements on the other side of a threshold
    std::optional<double> complexity_;  // the latest measurement
    uint64_t measurements_ = 0;
};

} // namespace shadowlab
