// No shadows: the baseline. The direct light reaches every surface that faces it, so the frame
// time of this technique is the host's cost alone and the overhead of every other technique is
// measured against it.
#include <shadowlab/technique.h>

namespace {

class NoShadows final : public shadowlab::IShadowTechnique {
public:
    bool init(shadowlab::IHost&, std::string&) override { return true; }
    void renderShadows(const shadowlab::ParamValues&) override {}
    void bindMainPass(uint32_t, const shadowlab::ParamValues&) override {}
    void shutdown() override {}
};

const shadowlab::TechniqueDesc kDescriptor{
    "none",
    "No shadows",
    "baseline",
    "Direct light without any occlusion test: every surface facing the light is lit. It is the "
    "baseline for overhead measurements and shows how much shadows add to the reading of a scene "
    "(contact, height above the ground, shape).",
    "none.glsl",
    nullptr,
    0,
};

} // namespace

SHADOWLAB_PLUGIN(NoShadows, kDescriptor)
