// The light pass of the stochastic techniques (stochastic-sm, cssm2; seed 001 sec. 2.1.2, 2.1.3):
// one target from the light (kit/light_target.h), fitted with `fit` and `snap` (kit/focus.h) and
// reported to the host; the depth-map block that the caster shaders (depth_only.vert,
// translucent_caster.vert) and the main pass read; the block of the frame's random numbers
// (stochastic_shared.h); the casters drawn culled to the map's volume. What a technique keeps to
// itself: the target's formats, its clears and blend states between the draws, and its programs.
#pragma once

#include <string>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/focus.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/light_target.h"
#include "shadowlab/kit/shadow_map_report.h"
#include "shadowlab/kit/stochastic_shared.h"

namespace shadowlab::kit {

class StochasticLightPass {
public:
    // `label` (a string that outlives the pass) names the target; its blocks are "<label>: light
    // space" and "<label>: light pass".
    void create(IHost& host, const char* label) {
        host_ = &host;
        target_.create(host, label);
        mapUniforms_.create(host, (std::string(label) + ": light space").c_str());
        passUniforms_.create(host, (std::string(label) + ": light pass").c_str());
    }

    // The target in `format`, reallocated only when that changes; true when its textures are new
    // (register debug images then).
    bool ensure(const LightTargetFormat& format) { return target_.ensure(format); }

    // The frame's map, inside the technique's "shadow map" GpuPass: fitted and reported, the light
    // space block set, `pass` set with this frame's seed, the target bound. The technique clears it
    // and draws the casters (draw()).
    void begin(const FrameContext& frame, const FitConfig& fit, shared::stochastic::StochasticPassUniforms pass) {
        const int resolution = target_.resolution();
        focused_ = focusLightSpace(*host_, frame, fit, resolution);
        mapUniforms_.set(lightSpaceUniforms(focused_.light, resolution));
        reportShadowMap(*host_, focused_.light.viewProjection, {resolution, resolution});
        pass.uFrameSeed = frame.randomSeed;
        passUniforms_.set(pass);
        target_.bind();
    }

    // `set` culled to the map's volume of this frame (after begin()), drawn with `program`.
    void draw(DrawSet set, const Program& program) const {
        host_->drawScene(culledDraw(set, focused_.cullPlanes), program.use());
    }

    // The light space block, for the main pass's light_space.glsl.
    void bindMainPass() const { mapUniforms_.bind(); }

    const LightTarget& target() const { return target_; }

private:
    IHost* host_ = nullptr;
    LightTarget target_;
    FocusedLightSpace focused_;
    UniformBlock<DepthMapUniforms> mapUniforms_;
    UniformBlock<shared::stochastic::StochasticPassUniforms> passUniforms_;
};

} // namespace shadowlab::kit
