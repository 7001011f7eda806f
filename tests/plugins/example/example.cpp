// A whole technique on the kit: a shadow map read through 3 x 3 bilinear taps, its darkness a parameter.
#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>
#include "example_shared.h"

namespace {
using namespace shadowlab;

// Each parameter once: its C++ type, its id, its descriptor (kit/params.h).
#define EXAMPLE_PARAMS(X)                             \
    X(int, resolution, kit::resolutionParam(1024))    \
    X(float, darkness, {"darkness", "darkness", ParamType::Float, 0, 1, 1, "", "How much of the light a shadow removes.", nullptr})
SHADOWLAB_PARAMS(Params, EXAMPLE_PARAMS);   // Params::table, Params::Id::darkness, Params::read(values).darkness

class Example final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        uniforms_.create(host(), "example uniforms");
        return map_.create(host(), error);
    }
    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        map_.render(frame, {.resolution = Params::read(params).resolution});
    }
    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        map_.bindMainPass(SamplerKind::CompareLinear);
        uniforms_.set({{}, Params::read(params).darkness, 0, 0, 0});
    }
    kit::DepthMap map_;
    kit::UniformBlock<shared::example::ExampleUniforms> uniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueMap,   // a map of the opaque casters
    {.id = "example", .displayName = "Example", .category = "filtered",
     .explanation = "A shadow map filtered over 3 x 3 taps.", .shadowGlsl = "example.glsl"},
    Params::table);
} // namespace

SHADOWLAB_PLUGIN(Example, kDescriptor)
