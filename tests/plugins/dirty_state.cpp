// Test plugin that leaves every piece of GL state the contract names dirty, in renderShadows and
// in bindMainPass (shadowlab/technique.h, "GL state contract"). Its shadow term is 1 everywhere,
// so the host's main pass must produce exactly the image of `none`.
#include <glad/gl.h>
#include <shadowlab/technique.h>

namespace {

using namespace shadowlab;

class DirtyState final : public IShadowTechnique {
public:
    bool init(IHost& host, std::string& error) override {
        if (!gladLoadGL(host.glLoader())) {
            error = "no GL";
            return false;
        }
        host_ = &host;
        framebuffer_ = host.createFramebuffer("dirty");
        texture_ = host.createTexture({.internalFormat = GL_RGBA8, .width = 4, .height = 4, .label = "dirty target"});
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture_, 0);
        return true;
    }
    void renderShadows(const FrameContext&, const ParamValues&) override { makeEverythingDirty(); }
    void bindMainPass(const FrameContext&, const ParamValues&) override { makeEverythingDirty(); }

private:
    void makeEverythingDirty() {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(1, 1, 2, 2);
        glDepthFunc(GL_NEVER);
        glDepthMask(GL_FALSE);
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_DEPTH_CLAMP);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
        glBlendFunc(GL_ZERO, GL_ONE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT_AND_BACK);
        glFrontFace(GL_CW);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_NEVER, 1, 0xFF);
        glStencilMask(0x00);
        glStencilOp(GL_INCR, GL_INCR, GL_INCR);
        glEnable(GL_SCISSOR_TEST);
        glScissor(0, 0, 1, 1);
        for (GLenum i = 0; i < 8; ++i) glEnable(GL_CLIP_DISTANCE0 + i);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1000.0f, 100000.0f);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_FRAMEBUFFER_SRGB);
        glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
        glBindBufferBase(GL_UNIFORM_BUFFER, 0, 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
        glBindVertexArray(0);
        glUseProgram(0);
    }

    IHost* host_ = nullptr;
    uint32_t framebuffer_ = 0, texture_ = 0;
};

const TechniqueDesc kDescriptor{.id = "dirty_state", .displayName = "Dirty state", .category = "baseline",
                                .explanation = "Test plugin.", .shadowGlsl = "none.glsl"};

} // namespace

SHADOWLAB_PLUGIN(DirtyState, kDescriptor)
