// Percentage-closer filtering (Reeves, Salesin and Cook 1987; seed 000 sections 2.2.7, 3.2.4 and
// 4.3.2). A shadow map as in `shadowmap`; the main pass averages the binary depth test over an
// n x n box of texel-aligned offsets around the shaded point (offset scale spreads them), which
// turns the hard edge into a ramp, optionally with the texture unit's bilinear comparison on every
// tap (seed 000 Fig. 3.11b without, 3.11c with). The taps are either looked up one by one or their
// texels fetched four at a time with textureGather and weighted as the taps weight them (Castano
// 2013, "Shadow Mapping Summary - Part 1"; derived in pcf.glsl), or each block of four read by one
// bilinear comparison the texture unit weights (`folded`, Castano's own form): the same filter for
// about a quarter of the lookups (with the cone bias, per 2 x 2 block of texels).
// Known artefacts: banding (only n^2 + 1 shades without bilinear taps), visible texel steps, the
// same penumbra width everywhere (not a soft shadow: the light's size plays no part), cost growing
// with n^2, and acne that grows with the kernel: far taps see the receiver's own tilted surface
// closer to the light. The cone bias (a receiver bias proportional to the tap's distance from
// the centre and to the receiver's slope, sec. 3.2.4 last paragraph) removes that acne at the
// price of some peter panning under large kernels.
// Point lights: the kit's cube map (kit/cube_depth_map.h), the n x n taps laid across the ray from
// the light (shaders/cube_shadow.glsl), with the cone bias; `sampling = gather | folded` use the taps there.
// classify = depth-range: the kit's depth-range mips (kit/depth_range_mips.h: min and max depth
// mips built after the shadow pass, as pcss and adaptive-pcf use them) bound every depth the
// kernel can read, and a pixel whose every comparison they decide skips the kernel, with the same
// image (pcf.glsl, classifyByDepthRange). 2D maps only: point lights always run the kernel.
#include <shadowlab/kit/filtered_depth_maps.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "pcf_shared.h"

namespace {

using namespace shadowlab;

constexpr ParamDesc kKernel{"kernel", "kernel size n", ParamType::Int, 1, 15, 5, "taps",
     "n x n box of shadow tests averaged per pixel. 1 is plain shadow mapping; larger kernels widen and "
     "smooth the ramp but cost n^2 lookups (15 x 15 = 225 per pixel; 64 with sampling = gather) and need "
     "more bias (see cone bias).",
     nullptr};
constexpr ParamDesc kOffsetScale{"offset_scale", "offset scale", ParamType::Float, 0.25, 8, 1, "texels",
     "Spacing between neighbouring taps. Below 1 the taps overlap and the ramp is narrow but smooth; "
     "above 1 the penumbra widens without extra cost but breaks into visible bands and copies of the edge.",
     nullptr};
constexpr ParamDesc kSampling = kit::enumParam("sampling", "sampling", 0, "taps|gather|folded",
     "How the n x n taps are evaluated. taps: n^2 texture lookups. gather: the texels the taps read, "
     "fetched and compared four at a time with textureGather and weighted in the shader as the taps weight "
     "them, (n + 1)^2 / 4 lookups rounded up (36 instead of 121 at 11 x 11). folded: the same blocks of four "
     "texels, each one bilinear comparison placed so that the texture unit weights them (Castano 2013's "
     "optimised PCF): as many lookups as gather, less arithmetic. Both give the taps' shadow without the cone "
     "bias; with it each 2 x 2 block compares against its farthest tap's reference, so contacts may be a "
     "little lighter (never darker) than with the taps. Both need offset scale 1 (neighbouring taps sharing "
     "texels); at other spacings, and for point lights, the taps are used.");
constexpr ParamDesc kClassify = kit::enumParam("classify", "decide lit and shadowed by", 0, "none|depth-range",
     "none: every pixel in the map runs the kernel. depth-range: first the nearest and farthest depth "
     "stored anywhere the kernel reads (depth-range mips: one extra pass after the shadow map, then at most "
     "four fetches per pixel): nearest at or behind the receiver means every tap is lit, farthest in front "
     "of the most cone-biased tap's depth every tap shadowed, and the kernel is skipped. Exactly the same "
     "image as none, for every sampling. It saves the kernel on surfaces facing the light and under "
     "casters well above the receiver. It cannot decide a receiver tilted against the light (the texels on "
     "its near side are closer to the light than it is; the cone bias is what keeps its taps lit) once the "
     "region, rounded up to the mips' power-of-two blocks, spans more than the depth bias covers: at 11 x 11 "
     "that is nearly all of the lit ground in cube and contact, and penumbra-heavy views (forest's foliage) "
     "decide little at any size. Those pixels pay the mips and the test and still run the kernel. Point "
     "lights ignore it.");

#define PCF_PARAMS(X)                                  \
    X(int, resolution, kit::resolutionParam())         \
    X(int, kernel, kKernel)                            \
    X(float, offset_scale, kOffsetScale)               \
    X(bool, hardware_filter, kit::bilinearTapsParam()) \
    X(int, sampling, kSampling)                        \
    X(int, classify, kClassify)                        \
    SHADOWLAB_PCF_COMMON_PARAMS(X)
SHADOWLAB_PARAMS(Params, PCF_PARAMS);

class PercentageCloserFiltering final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        uniforms_.create(host(), "pcf uniforms");
        return maps_.create(host(), error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        if (!maps_.render(frame, kit::depthMapConfig(p), kit::layeredDepthConfig(p))) return;   // the cube: no kernel report, no mips
        // The n x n box pcf.glsl filters over, for the host's kernel view (--probe).
        maps_.map().reportFilter({.kernel = FilterKernel::Box,
                                  .taps = p.kernel,
                                  .spacing = p.offset_scale,
                                  .bilinear = p.hardware_filter ? 1u : 0u,
                                  .coneBias = p.cone_bias ? 1.0f : 0.0f});
        // classify = depth-range bounds the kernel with mips of the 2D map.
        maps_.updateDepthRange(p.classify == 1);
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const bool bilinear = p.hardware_filter;
        // Gather and folded read the texels of taps one texel apart; other spacings use the taps.
        const int sampling = p.offset_scale == 1.0f ? p.sampling : 0;
        // Folded lookups are bilinear comparisons whatever the taps are (nearest taps: on texel corners).
        const bool linearSampler = bilinear || sampling == 2;
        maps_.bindMainPass(frame, linearSampler ? SamplerKind::CompareLinear : SamplerKind::CompareNearest,
                           bilinear ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
        const bool coneBias = p.cone_bias;
        const int classify = frame.light.type == LightType::Point ? 0 : p.classify;
        uniforms_.set({{}, p.kernel, p.offset_scale, coneBias ? 1.0f : 0.0f, sampling,
                       bilinear ? 1 : 0, classify, 0, 0});
    }

    kit::FilteredDepthMaps maps_;
    kit::UniformBlock<shared::pcf::PcfUniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFilteredMap,
    {.id = "pcf",
     .displayName = "Percentage-closer filtering",
     .category = "filtered",
     .explanation = "Shadow mapping whose depth test is repeated over an n x n box of neighbouring texels and "
                    "averaged, so edges become ramps instead of staircases. The kernel size sets the number of "
                    "tests (cost grows with n^2), the offset scale their spacing; bilinear taps remove the "
                    "banding. Sampling by gather or folded reads the same texels four at a time (Castano 2013) for the "
                    "same result (with the cone bias, a little lighter at contacts) at about a quarter of the lookups. The ramp has the same width everywhere: this is anti-aliasing, not a physically soft "
                    "shadow. Turn the cone bias off with a large kernel to see the acne that wide filters cause. Classify = depth-range skips the kernel where min/max depth mips prove every tap lit or every tap shadowed, with the same image.",
     .shadowGlsl = "pcf.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(PercentageCloserFiltering, kDescriptor)
