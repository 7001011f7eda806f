// The view-depth range a warped single map spreads its texels over (lispsm, tsm): where the camera
// can see the scene at all (the frustum clipped to the scene's bounds: kit::visibleDepthRange), or
// with `range = receivers` narrowed to the nearest and farthest depth of the visible receivers, the
// camera pre-pass reduced on the GPU and read back a few frames late without waiting
// (kit::ViewDepthBounds, as csm's fit = sdsm). The remedy seed 002 names for a warp whose far end
// lies beyond every receiver (sec. 9.2.5's virtual far plane, measured instead of set).
#pragma once

#include <shadowlab/kit/cascade_maps.h>
#include <shadowlab/kit/params.h>

namespace shadowlab::kit {

constexpr ParamDesc warpRangeParam() {
    return enumParam("range", "warp range", 0, "scene|receivers",
            "The view depths the warp is fitted to (its near distance z_n and the far end of eq. 8.13's d). "
            "scene: the camera frustum clipped to the scene's bounds. receivers: the nearest and farthest depth "
            "of what the camera really sees, measured from the camera pre-pass on the GPU (a few frames late, "
            "never waited for), so a view ending at a hillside or a wall warps for that distance instead of "
            "the scene's far corner. Costs the pre-pass and a reduction.");
}

// The flag condition of a technique with warpRangeParam(): the depth-only pre-pass only when it is measured.
inline constexpr FlagCondition kReceiverRangeNeedsDepth{kTechniqueNeedsCameraDepth, "range", "receivers"};

class ReceiverRange {
public:
    bool create(IHost& host, std::string& error) {
        host_ = &host;
        bounds_.create(host);
        return program_.build(host, {.computeFile = "view_depth_bounds.comp"}, error);
    }
    void destroy() { bounds_.destroy(); }

    // This frame's range: the visible one, narrowed to the receivers' when asked (the reduction of
    // this frame's pre-pass dispatched, the newest finished one used).
    DepthRange range(const FrameContext& frame, bool receivers) {
        const DepthRange visible = visibleDepthRange(frame.camera, host_->bounds(DrawSet::All));
        if (!receivers) return visible;
        bounds_.reduce(program_);
        return narrowToMeasured(visible, bounds_.latest());
    }

private:
    IHost* host_ = nullptr;
    ViewDepthBounds bounds_;
    Program program_;
};

} // namespace shadowlab::kit
