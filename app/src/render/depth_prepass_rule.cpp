// The depth pre-pass's auto rule (see depth_prepass_rule.h).
#include "render/depth_prepass_rule.h"

namespace shadowlab {

const char* depthPrepassModeName(DepthPrepassMode mode) {
    switch (mode) {
    case DepthPrepassMode::Off: return "off";
    case DepthPrepassMode::On: return "on";
    case DepthPrepassMode::Auto: return "auto";
    }
    return "auto";
}

bool DepthPrepassRule::update(double complexity) {
    const bool first = !complexity_;
    complexity_ = complexity;
    ++measurements_;
    const bool before = on_;
    if (first) {
        on_ = complexity >= 0.5 * (kOnAbove + kOffBelow);
        beyond_ = 0;
        return on_ != before;
    }
    const bool wantsFlip = on_ ? complexity <= kOffBelow : complexity >= kOnAbove;
    beyond_ = wantsFlip ? beyond_ + 1 : 0;
    if (beyond_ >= kConfirmations) {
        on_ = !on_;
        beyond_ = 0;
    }
    return on_ != before;
}

} // namespace shadowlab
