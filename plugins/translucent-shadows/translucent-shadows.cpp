// Translucent shadows (Filion and McNaughton 2008, "StarCraft II: Effects & Techniques"; seed 001
// sec. 2.1.3 for the algorithm, sec. 4.2.1 for the modified colour and the front-to-back sort,
// sec. 5.3.1 Fig. 5.3.B for its timing with 2x2 hardware PCF, sec. 5.3.3 for its failure). Three
// passes from the light:
//   1. D_o: the depth of the opaque casters (an ordinary shadow map);
//   2. D_t: the nearest translucent caster's depth (LEQUAL, depth writes);
//   3. C: a colour buffer cleared to white, multiplied (blend DST_COLOR, ZERO) by every translucent
//      caster in front of D_o (depth-tested against it without writing), drawn front to back from
//      the light by the objects' bounds centres (seed 001 sorts per mesh by its bounding box's
//      centre). The original writes the surface colour; `modified` (1 - a) t (sec. 4.2.1).
// Lookup: visibility = o (t + (1 - t) C) with o = [z <= D_o] and t = [z <= D_t].
// Reference model: `modified` is M3, (1 - a) t per crossing, exact on opaque receivers; `original`
// has no reference model of its own (its factor is the surface colour, not a transmission), so it
// is judged against M3 as well and the difference shows.
// Known artefacts: every point behind the nearest translucent surface gets all of C, so translucent
// surfaces shadow themselves and layers far from the light tint those nearer it (Figs. 2.1.3.A,
// 5.3.3.A); the bounds sort breaks for objects of different sizes or interleaved objects (harmless
// with this commutative blend); original: a surface's own colour does not darken a receiver of that
// colour (a green plane over a green pot, Fig. 4.2.1.A); modified: (1 - a) t does not tend to 1
// as a -> 0 (it is 1 - a only where t = 1), so it differs from the physical model even under one
// layer ("only superficially corrected", sec. 2.1.3 footnote 1).
#include <shadowlab/kit/focus.h>
#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/light_target.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "translucent_shadows_shared.h"

namespace {

using namespace shadowlab;
using namespace shadowlab::shared::translucent_shadows;

constexpr ParamDesc kParams[] = {
    kit::resolutionParam(),
    {"variant", "variant", ParamType::Enum, 0, 1, kVariantModified, "",
     "What a translucent caster multiplies the shadow colour by. original: its surface colour (StarCraft "
     "II); a surface then does not darken a receiver of its own colour, and there is no reference model "
     "for it (eval judges it against the modified one). modified: (1 - alpha) t, seed 001's correction "
     "(the modified-translucent model M3), which still differs from the physical (1 - alpha) + alpha t.",
     "original|modified"},
    {"hardware_filter", "hardware 2x2 filter", ParamType::Bool, 0, 1, 1, "",
     "Bilinear comparison filtering by the texture unit on both depth maps (seed 001 timed translucent "
     "shadows with 2x2 hardware PCF). Off: plain tests, staircase edges.",
     nullptr},
    kit::constantBiasParam(),
    kit::slopeBiasParam(),
    kit::fitParam(),
    kit::snapParam(),
};
enum : uint32_t {
    kResolution = kit::paramIndex(kParams, "resolution"),
    kVariant = kit::paramIndex(kParams, "variant"),
    kHardwareFilter = kit::paramIndex(kParams, "hardware_filter"),
    kConstantBias = kit::paramIndex(kParams, "constant_bias"),
    kSlopeBias = kit::paramIndex(kParams, "slope_bias"),
    kFit = kit::paramIndex(kParams, "fit"),
    kSnap = kit::paramIndex(kParams, "snap"),
};

constexpr TechniqueDesc kDescriptor = kit::describe(
    {.id = "translucent-shadows",
     .displayName = "Translucent shadows (StarCraft II)",
     .category = "coloured",
     .explanation = "Three maps from the light: the opaque casters' depth, the nearest translucent caster's "
                    "depth, and a colour buffer, white at first, that every translucent caster in front of the "
                    "opaque depth multiplies by what it lets through. A point behind an opaque caster is dark; "
                    "behind the nearest translucent one it gets the whole colour buffer. Noise-free, cheap, and "
                    "right on opaque receivers; but translucent surfaces behind the first are tinted by every "
                    "layer, themselves and those farther from the light included. The modified variant writes "
                    "(1 - alpha) t and is judged by that model; the original writes the surface colour, which "
                    "has no reference model of its own (it is judged by the modified one). Compare the two on "
                    "teapot-glass's green pot. Debug views: footprint, texel-grid and coverage (the map and its volume), 'opaque depth D_o', 'translucent depth D_t' and 'shadow colour C'.",
     .shadowGlsl = "translucent-shadows.glsl",
     .translucencyModel = TranslucencyModel::ModifiedTranslucent},
    kParams);

class TranslucentShadows final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!depthProgram_.build(host(), {.vertexFile = "depth_only.vert"}, error)) return false;
        if (!colourProgram_.build(host(), {.vertexFile = "depth_only.vert", .fragmentFile = "shadow_colour.frag"}, error))
            return false;
        opaqueDepth_.create(host(), "opaque depth D_o");
        translucentDepth_.create(host(), "translucent depth D_t");
        shadowColour_.create(host(), "shadow colour C");
        mapUniforms_.create(host(), "translucent shadows light space");
        colourPassUniforms_.create(host(), "shadow colour pass uniforms");
        return true;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const int resolution = params.asInt(kResolution);
        const bool newOpaque = opaqueDepth_.ensure({.resolution = resolution});
        const bool newTranslucent = translucentDepth_.ensure({.resolution = resolution});
        // RGBA16F: a product of many filters keeps its precision (8 bits would band under a few layers).
        const bool newColour = shadowColour_.ensure({.resolution = resolution, .colourFormat = GL_RGBA16F, .depthFrom = &opaqueDepth_});
        if (newOpaque || newTranslucent || newColour) {
            host().registerDebugImage("opaque depth D_o", opaqueDepth_.depth(), DebugImageKind::Depth);
            host().registerDebugImage("translucent depth D_t", translucentDepth_.depth(), DebugImageKind::Depth);
            host().registerDebugImage("shadow colour C", shadowColour_.colour(), DebugImageKind::Color);
        }
        const kit::FocusedLightSpace focused = kit::focusLightSpace(host(), frame, kit::readFit(params, kFit, kSnap), resolution);
        const LightSpace& lightSpace = focused.light;
        mapUniforms_.set(kit::lightSpaceUniforms(lightSpace, resolution));
        kit::reportShadowMap(host(), lightSpace.viewProjection, {resolution, resolution});
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(params.asFloat(kSlopeBias), params.asFloat(kConstantBias));
        {
            GpuPass pass(host(), "opaque depth");
            opaqueDepth_.bind();
            glClear(GL_DEPTH_BUFFER_BIT);
            host().drawScene(kit::culledDraw(DrawSet::OpaqueCasters, focused.cullPlanes), depthProgram_.use());
        }
        {
            GpuPass pass(host(), "translucent depth");
            translucentDepth_.bind();
            glClear(GL_DEPTH_BUFFER_BIT);
            glDepthFunc(GL_LEQUAL);
            host().drawScene(kit::culledDraw(DrawSet::TranslucentCasters, focused.cullPlanes), depthProgram_.use());
        }
        {
            GpuPass pass(host(), "shadow colour");
            shadowColour_.bind();
            const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
            glClearBufferfv(GL_COLOR, 0, white);
            glDisable(GL_POLYGON_OFFSET_FILL);
            glDepthFunc(GL_LESS);     // in front of the opaque depth
            glDepthMask(GL_FALSE);    // which stays D_o
            glEnable(GL_BLEND);
            glBlendFunc(GL_DST_COLOR, GL_ZERO);
            colourPassUniforms_.set({{}, params.asInt(kVariant), 0, 0, 0});
            host().drawScene(kit::culledDraw(DrawSet::TranslucentCasters, focused.cullPlanes,
                                             kit::frontToBackFromLight(DrawSet::TranslucentCasters, frame.light)),
                             colourProgram_.use());
        }
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const GLuint comparison =
            host().sampler(params.asBool(kHardwareFilter) ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
        glBindTextureUnit(kit::kDepthMapUnit, opaqueDepth_.depth());
        glBindSampler(kit::kDepthMapUnit, comparison);
        glBindTextureUnit(kTranslucentDepthUnit, translucentDepth_.depth());
        glBindSampler(kTranslucentDepthUnit, comparison);
        glBindTextureUnit(kShadowColourUnit, shadowColour_.colour());
        glBindSampler(kShadowColourUnit, host().sampler(SamplerKind::Linear));
        mapUniforms_.bind();
    }

    kit::Program depthProgram_;
    kit::Program colourProgram_;
    kit::LightTarget opaqueDepth_;
    kit::LightTarget translucentDepth_;
    kit::LightTarget shadowColour_;
    kit::UniformBlock<kit::DepthMapUniforms> mapUniforms_;
    kit::UniformBlock<ShadowColourPassUniforms> colourPassUniforms_;
};

} // namespace

SHADOWLAB_PLUGIN(TranslucentShadows, kDescriptor)
