// A full-screen pass into a colour target: shaders/fullscreen.vert with the technique's fragment
// shader, drawing one triangle over the viewport (IHost::drawFullscreenTriangle) into a
// framebuffer of its own. The passes that reduce or accumulate into colour textures: the
// depth-range mips (depth_range_mips.h), pcss's min-depth mips of the cube's faces and
// area-reference's visibility accumulation. Created in setup(), nothing per frame.
#pragma once

#include <string>

#include <glad/gl.h>
#include <glm/glm.hpp>
#include <shadowlab/technique.h>

#include "shadowlab/kit/handles.h"

namespace shadowlab::kit {

class FullscreenPass {
public:
    // `label` names the framebuffer in GL debug output.
    bool create(IHost& host, const char* fragmentFile, const char* label, std::string& error) {
        host_ = &host;
        framebuffer_ = makeFramebuffer(host, label);
        return program_.build(host, {.vertexFile = "fullscreen.vert", .fragmentFile = fragmentFile}, error);
    }

    // Colour attachment 0, the only draw buffer: `level` of `texture`, or of its `layer` (an
    // array texture's).
    void attach(GLuint texture, int level = 0, int layer = -1) {
        if (layer < 0) glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, texture, level);
        else glNamedFramebufferTextureLayer(framebuffer_, GL_COLOR_ATTACHMENT0, texture, level, layer);
        glNamedFramebufferDrawBuffer(framebuffer_, GL_COLOR_ATTACHMENT0);
    }

    // The framebuffer and the program bound, depth test off (the pass reads textures, writes colour).
    void begin() const {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glDisable(GL_DEPTH_TEST);
        program_.use();
    }

    // One triangle over a viewport of `size` texels of the attachment.
    void draw(glm::ivec2 size) const {
        glViewport(0, 0, size.x, size.y);
        host_->drawFullscreenTriangle();
    }

    GLuint framebuffer() const { return framebuffer_; }

private:
    IHost* host_ = nullptr;
    Program program_;
    Framebuffer framebuffer_;
};

} // namespace shadowlab::kit
