// Basic shadow mapping (Williams 1978; seed 000 sections 2.2.4 and 3.2.2, seed 004 slides).
// Pass 1 renders the depth of the scene from the light into a texture: orthographic for
// directional lights, perspective for spot (and point) lights. Pass 2, in the host's main pass,
// projects each shaded point into that texture and compares depths: a point farther from the
// light than the stored depth is in shadow.
// Known artefacts: shadow acne without bias (seed 000 Fig. 3.7-3.8a), peter panning with too much
// bias (Fig. 3.8b), blocky edges from limited resolution (Fig. 3.6).
// Options: constant and slope-scaled bias through glPolygonOffset, culling of front faces in
// the shadow pass (only back faces are stored; seed 002 "biasing with back faces"), and the
// hardware's 2x2 comparison filter (sampler2DShadow with linear filtering).
#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <glm/gtc/type_ptr.hpp>

namespace {

using namespace shadowlab;

enum Param : uint32_t { kResolution, kDepthFormat, kConstantBias, kSlopeBias, kCullFaces, kHardwareFilter, kParamCount };

const ParamDesc kParams[] = {
    {"resolution", "resolution", ParamType::Int, 256, 8192, 2048, "texels",
     "Width and height of the shadow map. Higher values sharpen the edge and shrink aliasing; memory and "
     "shadow-pass time grow with the square.", nullptr},
    {"depth_format", "depth format", ParamType::Enum, 0, 2, 2, "",
     "Precision of the stored depth. 16-bit depth quantises coarsely and needs more bias.", "16|24|32F"},
    {"constant_bias", "constant bias", ParamType::Float, 0, 200000, 2, "units",
     "glPolygonOffset units: a constant push of stored depths away from the light, in steps of the depth "
     "format's smallest difference (2^-24 of the range near depth 1 for 24-bit and 32F). Zero shows acne; "
     "tens of thousands detach shadows from their casters (peter panning).", nullptr},
    {"slope_bias", "slope-scaled bias", ParamType::Float, 0, 16, 2, "",
     "glPolygonOffset factor: bias growing with the surface slope as seen from the light, where acne is "
     "worst (grazing light).", nullptr},
    {"cull", "cull in shadow pass", ParamType::Enum, 0, 2, 1, "",
     "Faces culled while rendering the map. 'front' stores back faces only, which moves acne to the dark "
     "side of closed objects but leaks light at thin or open geometry.", "none|back|front"},
    {"hardware_filter", "hardware 2x2 filter", ParamType::Bool, 0, 1, 0, "",
     "Bilinear comparison filtering by the texture unit (sampler2DShadow with GL_LINEAR): smooths the "
     "staircase over one texel at no extra cost.", nullptr},
};

const TechniqueDesc kDescriptor{
    "shadowmap",
    "Shadow mapping",
    "hard",
    "Renders the scene's depth from the light, then compares each visible point's depth in light space "
    "with the stored one: farther means shadowed. Works for any geometry and receiver, costs one extra "
    "pass, and shows the classic artefacts: acne (self-shadowing from depth quantisation; cured by bias), "
    "peter panning (too much bias) and blocky edges (limited resolution). Try a low light and zero bias.",
    "shadowmap.glsl",
    kParams,
    kParamCount,
};

class ShadowMapping final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        host_ = &host;
        if (!gladLoadGL(host.glLoader())) {
            error = "could not load OpenGL entry points";
            return false;
        }
        depthProgram_ = host.buildProgram({"depth_only.vert", nullptr, nullptr}, error);
        if (!depthProgram_) return false;
        framebuffer_ = host.createFramebuffer("shadow map");
        return true;
    }

    void renderShadows(const ParamValues& params) override {
        ensureShadowMap(params);
        lightSpace_ = host_->fitLightSpace(DrawSet::All);

        GpuPass pass(*host_, "shadow map");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, resolution_, resolution_);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        const int cull = params.asInt(kCullFaces);
        if (cull == 0) {
            glDisable(GL_CULL_FACE);
        } else {
            glEnable(GL_CULL_FACE);
            glCullFace(cull == 1 ? GL_BACK : GL_FRONT);
        }
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(params.asFloat(kSlopeBias), params.asFloat(kConstantBias));
        const GLuint program = host_->glProgram(depthProgram_);
        glUseProgram(program);
        glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(lightSpace_.viewProjection));
        host_->drawScene(DrawSet::OpaqueCasters, program);
        glDisable(GL_POLYGON_OFFSET_FILL);
        glDisable(GL_CULL_FACE);
    }

    void bindMainPass(uint32_t program, const ParamValues& params) override {
        glUniformMatrix4fv(16, 1, GL_FALSE, glm::value_ptr(lightSpace_.viewProjection));
        (void)program;
        const GLint filter = params.asBool(kHardwareFilter) ? GL_LINEAR : GL_NEAREST;
        glTextureParameteri(depthTexture_, GL_TEXTURE_MIN_FILTER, filter);
        glTextureParameteri(depthTexture_, GL_TEXTURE_MAG_FILTER, filter);
        glBindTextureUnit(4, depthTexture_);
    }

    void shutdown() override {
        if (depthTexture_) host_->destroyTexture(depthTexture_);
        if (framebuffer_) host_->destroyFramebuffer(framebuffer_);
        depthTexture_ = framebuffer_ = 0;
    }

private:
    // (Re)allocates the map only when resolution or format changed, never per frame.
    void ensureShadowMap(const ParamValues& params) {
        const int resolution = params.asInt(kResolution);
        static constexpr GLenum kFormats[] = {GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT32F};
        const GLenum format = kFormats[params.asInt(kDepthFormat)];
        if (depthTexture_ && resolution == resolution_ && format == format_) return;
        if (depthTexture_) host_->destroyTexture(depthTexture_);
        resolution_ = resolution;
        format_ = format;
        depthTexture_ = host_->createTexture({GL_TEXTURE_2D, format, resolution, resolution, 1, 1, "shadow map"});
        glTextureParameteri(depthTexture_, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(depthTexture_, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        glTextureParameteri(depthTexture_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(depthTexture_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depthTexture_, 0);
        glNamedFramebufferDrawBuffer(framebuffer_, GL_NONE);
        glNamedFramebufferReadBuffer(framebuffer_, GL_NONE);
        host_->checkFramebuffer(framebuffer_, "shadow map");
        host_->registerDebugImage("shadow map", depthTexture_, DebugImageKind::Depth);
    }

    IHost* host_ = nullptr;
    ProgramId depthProgram_ = 0;
    GLuint framebuffer_ = 0;
    GLuint depthTexture_ = 0;
    int resolution_ = 0;
    GLenum format_ = 0;
    LightSpace lightSpace_{};
};

} // namespace

SHADOWLAB_PLUGIN(ShadowMapping, kDescriptor)
