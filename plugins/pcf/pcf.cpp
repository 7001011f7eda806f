// Percentage-closer filtering (Reeves, Salesin and Cook 1987; seed 000 sections 2.2.7, 3.2.4 and
// 4.3.2). A shadow map as in `shadowmap`; the main pass averages the binary depth test over an
// n x n box of texel-aligned offsets around the shaded point (offset scale spreads them), which
// turns the hard edge into a ramp, optionally with the texture unit's bilinear comparison on every
// tap (seed 000 Fig. 3.11b without, 3.11c with).
// Known artefacts: banding (only n^2 + 1 shades without bilinear taps), visible texel steps, the
// same penumbra width everywhere (not a soft shadow: the light's size plays no part), cost growing
// with n^2, and acne that grows with the kernel: far taps see the receiver's own tilted surface
// closer to the light. The cone bias (a receiver bias proportional to the tap's distance from
// the centre and to the receiver's slope, sec. 3.2.4 last paragraph) removes that acne at the
// price of some peter panning under large kernels.
// Shares its shadow-map code with adaptive-pcf and pcss through kernel_shadow_map.h.
#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "kernel_shadow_map.h"

namespace {

using namespace shadowlab;

enum Param : uint32_t {
    kResolution,
    kKernel,
    kOffsetScale,
    kHardwareFilter,
    kConeBias,
    kConstantBias,
    kSlopeBias,
    kParamCount
};

const ParamDesc kParams[] = {
    kernel_filtering::kResolutionParam,
    {"kernel", "kernel size n", ParamType::Int, 1, 15, 5, "taps",
     "n x n box of shadow tests averaged per pixel. 1 is plain shadow mapping; larger kernels widen and "
     "smooth the ramp but cost n^2 lookups (15 x 15 = 225 per pixel) and need more bias (see cone bias).",
     nullptr},
    {"offset_scale", "offset scale", ParamType::Float, 0.25, 8, 1, "texels",
     "Spacing between neighbouring taps. Below 1 the taps overlap and the ramp is narrow but smooth; "
     "above 1 the penumbra widens without extra cost but breaks into visible bands and copies of the edge.",
     nullptr},
    {"hardware_filter", "bilinear taps", ParamType::Bool, 0, 1, 0, "",
     "Each tap is the texture unit's 2x2 bilinear comparison, which removes the banding of the plain box "
     "at almost no cost (seed 000 figure 3.11c against 3.11b). Off shows the n^2 + 1 discrete shades and "
     "the texel steps.", nullptr},
    kernel_filtering::kConeBiasParam,
    kernel_filtering::kConstantBiasParam,
    kernel_filtering::kSlopeBiasParam,
};

const TechniqueDesc kDescriptor{
    "pcf",
    "Percentage-closer filtering",
    "filtered",
    "Shadow mapping whose depth test is repeated over an n x n box of neighbouring texels and averaged, "
    "so edges become ramps instead of staircases. The kernel size sets the number of tests (cost grows "
    "with n^2), the offset scale their spacing; bilinear taps remove the banding. The ramp has the same "
    "width everywhere: this is anti-aliasing, not a physically soft shadow. Turn the cone bias off with "
    "a large kernel to see the acne that wide filters cause.",
    "pcf.glsl",
    kParams,
    kParamCount,
};

class PercentageCloserFiltering final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        return shadowMap_.init(host, true, error);
    }

    void renderShadows(const ParamValues& params) override {
        shadowMap_.render(params.asInt(kResolution), params.asFloat(kConstantBias), params.asFloat(kSlopeBias));
    }

    void bindMainPass(uint32_t program, const ParamValues& params) override {
        (void)program;
        shadowMap_.bindMainPass(4, params.asBool(kHardwareFilter));
        glUniform1i(23, params.asInt(kKernel));
        glUniform1f(24, params.asFloat(kOffsetScale));
        glUniform1f(25, params.asBool(kConeBias) ? 1.0f : 0.0f);
    }

    void shutdown() override { shadowMap_.shutdown(); }

private:
    kernel_filtering::KernelShadowMap shadowMap_;
};

} // namespace

SHADOWLAB_PLUGIN(PercentageCloserFiltering, kDescriptor)
