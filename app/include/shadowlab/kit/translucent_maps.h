// The three maps of translucent shadows from the light (Filion and McNaughton 2008; seed 001
// sec. 2.1.3 for the algorithm, sec. 4.2.1 for the modified colour and the front-to-back sort),
// shared by translucent-shadows and composited-translucent (sec. 4.2.3, which rebuilds D_t and C
// before each translucent mesh it draws):
//   D_o: the opaque casters' depth (an ordinary shadow map);
//   D_t: the nearest translucent caster's depth (LEQUAL, depth writes);
//   C:   a colour buffer cleared to white, multiplied (blend DST_COLOR, ZERO) by every
//        translucent caster in front of D_o (depth-tested against it, not written), drawn front
//        to back from the light. `original` multiplies by the surface colour, `modified` by
//        (1 - a) t (sec. 4.2.1; shaders/translucent_shadow_colour.frag).
// The main pass reads them with shaders/translucent_maps.glsl: visibility = o (t + (1 - t) C).
// The blend is a product, so the order does not change C; seed 001's order matters only for a
// blend that does not commute.
#pragma once

#include <string>
#include <vector>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/focus.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/light_target.h"
#include "shadowlab/kit/params.h"
#include "shadowlab/kit/shadow_map_report.h"
#include "shadowlab/kit/translucent_maps_shared.h"

namespace shadowlab::kit {

// What a translucent caster multiplies C by: the `variant` parameter of both techniques.
constexpr ParamDesc translucentVariantParam() {
    return enumParam("variant", "variant", shared::translucent_maps::kVariantModified, "original|modified",
            "What a translucent caster multiplies the shadow colour by. original: its surface colour (StarCraft "
            "II); a surface then does not darken a receiver of its own colour, and there is no reference model "
            "for it (eval judges it against the modified one). modified: (1 - alpha) t, seed 001's correction "
            "(the modified-translucent model M3), which still differs from the physical (1 - alpha) + alpha t.");
}
// The texture unit's 2x2 comparison on D_o and D_t (seed 001 timed translucent shadows so).
constexpr ParamDesc translucentHardwareFilterParam() {
    return {"hardware_filter", "hardware 2x2 filter", ParamType::Bool, 0, 1, 1, "",
            "Bilinear comparison filtering by the texture unit on both depth maps (seed 001 timed translucent "
            "shadows with 2x2 hardware PCF). Off: plain tests, staircase edges.",
            nullptr};
}

} // namespace shadowlab::kit

// The parameters of the techniques built on these maps (translucent-shadows,
// composited-translucent), declared once (kit/params.h); TranslucentMaps reads them.
#define SHADOWLAB_TRANSLUCENT_MAP_PARAMS(X)                                      \
    X(int, resolution, ::shadowlab::kit::resolutionParam())                      \
    X(int, variant, ::shadowlab::kit::translucentVariantParam())                 \
    X(bool, hardware_filter, ::shadowlab::kit::translucentHardwareFilterParam()) \
    SHADOWLAB_OFFSET_BIAS_PARAMS(X, 64)                                          \
    SHADOWLAB_FIT_PARAMS(X)

namespace shadowlab::kit {

SHADOWLAB_PARAMS(TranslucentMapParams, SHADOWLAB_TRANSLUCENT_MAP_PARAMS);
inline constexpr const auto& kTranslucentMapParams = TranslucentMapParams::table;

struct TranslucentMapSettings {
    int resolution = 2048;
    int variant = shared::translucent_maps::kVariantModified;
    float constantBias = 0.0f;   // polygon offset units of the two depth passes
    float slopeBias = 0.0f;      // polygon offset factor
};

class TranslucentMaps {
public:
    // `sharedOpaque`: another instance whose D_o this one reads and never renders (composited's
    // per-mesh maps share the frame's opaque depth); null: it owns its D_o.
    bool setup(IHost& host, const char* label, std::string& error, const TranslucentMaps* sharedOpaque = nullptr) {
        host_ = &host;
        sharedOpaque_ = sharedOpaque;
        if (!depthProgram_.build(host, {.vertexFile = "depth_only.vert"}, error)) return false;
        if (!colourProgram_.build(host, {.vertexFile = "depth_only.vert", .fragmentFile = "translucent_shadow_colour.frag"},
                                  error))
            return false;
        label_ = label;
        opaqueLabel_ = label_ + ": opaque depth D_o";
        translucentLabel_ = label_ + ": translucent depth D_t";
        colourLabel_ = label_ + ": shadow colour C";
        if (!sharedOpaque) opaqueDepth_.create(host, opaqueLabel_.c_str());
        translucentDepth_.create(host, translucentLabel_.c_str());
        shadowColour_.create(host, colourLabel_.c_str());
        mapUniforms_.create(host, (label_ + ": light space").c_str());
        colourPassUniforms_.create(host, (label_ + ": shadow colour pass").c_str());
        return true;
    }

    // (Re)allocates on a resolution change (a shared D_o must be ensured first). True when the
    // textures are new: register debug images then.
    bool ensure(int resolution) {
        const bool newOpaque = !sharedOpaque_ && opaqueDepth_.ensure({.resolution = resolution});
        const bool newTranslucent = translucentDepth_.ensure({.resolution = resolution});
        // RGBA16F: a product of many filters keeps its precision (8 bits would band under a few layers).
        const bool newColour = shadowColour_.ensure(
            {.resolution = resolution, .colourFormat = GL_RGBA16F, .depthFrom = &opaqueTarget()});
        return newOpaque || newTranslucent || newColour;
    }

    // The settings kTranslucentMapParams' values give.
    static TranslucentMapSettings settings(const ParamValues& params) {
        const TranslucentMapParams p = TranslucentMapParams::read(params);
        return {p.resolution, p.variant, p.constant_bias, p.slope_bias};
    }

    // A frame of translucent shadows from kTranslucentMapParams' values: the map fitted (`fit`,
    // `snap`, kit/focus.h) and reported to the host, D_o of the opaque casters, then D_t and C of
    // every translucent caster, front to back from the light, all culled to the map's volume.
    FocusedLightSpace renderAllCasters(const FrameContext& frame, const ParamValues& params) {
        const TranslucentMapSettings s = settings(params);
        if (ensure(s.resolution)) registerDebugImages("opaque depth D_o", "translucent depth D_t", "shadow colour C");
        const FitConfig fit = fitConfig(TranslucentMapParams::read(params));
        FocusedLightSpace focused = focusLightSpace(*host_, frame, fit, s.resolution);
        setLightSpace(focused.light, s.resolution);
        reportShadowMap(*host_, focused.light.viewProjection, {s.resolution, s.resolution});
        renderOpaqueDepth(culledDraw(DrawSet::OpaqueCasters, focused.cullPlanes), s);
        renderTranslucent(s, [&](GLuint program) {
            host_->drawScene(culledDraw(DrawSet::TranslucentCasters, focused.cullPlanes,
                                        frontToBackFromLight(DrawSet::TranslucentCasters, frame.light)),
                             program);
        });
        return focused;
    }

    void setLightSpace(const LightSpace& lightSpace, int resolution) {
        mapUniforms_.update(lightSpaceUniforms(lightSpace, resolution));
    }

    // D_o from the opaque casters `request` selects.
    void renderOpaqueDepth(const DrawRequest& request, const TranslucentMapSettings& settings) {
        GpuPass pass(*host_, "opaque depth");
        mapUniforms_.bind();
        opaqueDepth_.bind();
        glClear(GL_DEPTH_BUFFER_BIT);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(settings.slopeBias, settings.constantBias);
        host_->drawScene(request, depthProgram_.use());
        glDisable(GL_POLYGON_OFFSET_FILL);
    }

    // D_t and C from the translucent casters that drawCasters(program) draws with the program it
    // is given (called once per map; C wants them front to back from the light).
    template <typename DrawCasters>
    void renderTranslucent(const TranslucentMapSettings& settings, DrawCasters&& drawCasters) {
        mapUniforms_.bind();
        {
            GpuPass pass(*host_, "translucent depth");
            translucentDepth_.bind();
            glClear(GL_DEPTH_BUFFER_BIT);
            glEnable(GL_POLYGON_OFFSET_FILL);
            glPolygonOffset(settings.slopeBias, settings.constantBias);
            glDepthFunc(GL_LEQUAL);
            drawCasters(depthProgram_.use());
            glDisable(GL_POLYGON_OFFSET_FILL);
        }
        {
            GpuPass pass(*host_, "shadow colour");
            shadowColour_.bind();
            const float white[4] = {1.0f, 1.0f, 1.0f, 1.0f};
            glClearBufferfv(GL_COLOR, 0, white);
            glDepthFunc(GL_LESS);     // in front of the opaque depth
            glDepthMask(GL_FALSE);    // which stays D_o
            glEnable(GL_BLEND);
            glBlendFunc(GL_DST_COLOR, GL_ZERO);
            colourPassUniforms_.set({{}, settings.variant, 0, 0, 0});
            drawCasters(colourProgram_.use());
            glDisable(GL_BLEND);
            glDepthMask(GL_TRUE);
        }
    }

    // For shaders/translucent_maps.glsl: D_o and D_t through the comparison sampler (2x2 bilinear
    // with the hardware filter), C bilinear, and the light-space block.
    void bind(const ParamValues& params) const { bind(TranslucentMapParams::read(params).hardware_filter); }
    void bind(bool hardwareFilter) const {
        const GLuint comparison = host_->sampler(hardwareFilter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest);
        glBindTextureUnit(kDepthMapUnit, opaqueTarget().depth());
        glBindSampler(kDepthMapUnit, comparison);
        glBindTextureUnit(shared::translucent_maps::kTranslucentDepthUnit, translucentDepth_.depth());
        glBindSampler(shared::translucent_maps::kTranslucentDepthUnit, comparison);
        glBindTextureUnit(shared::translucent_maps::kShadowColourUnit, shadowColour_.colour());
        glBindSampler(shared::translucent_maps::kShadowColourUnit, host_->sampler(SamplerKind::Linear));
        mapUniforms_.bind();
    }

    void registerDebugImages(const char* opaque, const char* translucent, const char* colour) const {
        if (opaque) host_->registerDebugImage(opaque, opaqueTarget().depth(), DebugImageKind::Depth);
        host_->registerDebugImage(translucent, translucentDepth_.depth(), DebugImageKind::Depth);
        host_->registerDebugImage(colour, shadowColour_.colour(), DebugImageKind::Color);
    }

private:
    const LightTarget& opaqueTarget() const { return sharedOpaque_ ? sharedOpaque_->opaqueDepth_ : opaqueDepth_; }

    IHost* host_ = nullptr;
    const TranslucentMaps* sharedOpaque_ = nullptr;
    std::string label_, opaqueLabel_, translucentLabel_, colourLabel_;   // LightTarget keeps the pointers
    Program depthProgram_;
    Program colourProgram_;
    LightTarget opaqueDepth_;
    LightTarget translucentDepth_;
    LightTarget shadowColour_;
    UniformBlock<DepthMapUniforms> mapUniforms_;
    UniformBlock<shared::translucent_maps::ShadowColourPassUniforms> colourPassUniforms_;
};

} // namespace shadowlab::kit
