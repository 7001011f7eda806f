// Composing the window's view (see view_compositor.h).
#include "render/view_compositor.h"

#include <algorithm>

#include "util/log.h"

namespace shadowlab {
namespace {

GlTexture makeTexture(GLenum format, glm::ivec2 size) {
    GLuint name = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &name);
    glTextureStorage2D(name, 1, format, size.x, size.y);
    glTextureParameteri(name, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return GlTexture(name);
}

} // namespace

ViewCompositor::ViewCompositor(ShaderLibrary& shaders) : shaders_(shaders) {
    std::string error;
    differenceProgram_ = shaders_.build(hostShaderRequest("fullscreen.vert", "compare_difference.frag", "comparison difference"), error);
    if (!differenceProgram_) logError(error);
}

ViewCompositor::~ViewCompositor() {
    if (differenceProgram_) shaders_.release(differenceProgram_);
}

bool ViewCompositor::prepareOffscreen(glm::ivec2 size, std::string& error) {
    if (surfaceSize_ == size && surface_.get()) return true;
    surfaceColor_ = makeTexture(GL_RGBA8, size);
    GLuint name = 0;
    glCreateFramebuffers(1, &name);
    surface_.reset(name);
    glNamedFramebufferTexture(name, GL_COLOR_ATTACHMENT0, surfaceColor_.get(), 0);
    const GLenum status = glCheckNamedFramebufferStatus(name, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        error = "the offscreen window's framebuffer is " + framebufferStatusName(status);
        return false;
    }
    surfaceSize_ = size;
    return true;
}

void ViewCompositor::keepFirstTerm(const Renderer& renderer) {
    const glm::ivec2 size = renderer.size();
    if (firstTermSize_ != size) {
        firstTerm_ = makeTexture(GL_RGBA16F, size);
        firstTermSize_ = size;
    }
    glCopyImageSubData(renderer.target(MainTarget::Visibility), GL_TEXTURE_2D, 0, 0, 0, 0, firstTerm_.get(), GL_TEXTURE_2D, 0,
                       0, 0, 0, size.x, size.y, 1);
}

bool ViewCompositor::drawDifference(Renderer& renderer) {
    if (!differenceProgram_) return false;
    glBindFramebuffer(GL_FRAMEBUFFER, renderer.displayFramebuffer());
    glViewport(0, 0, renderer.size().x, renderer.size().y);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(shaders_.program(differenceProgram_));
    glBindTextureUnit(0, firstTerm_.get());
    glBindTextureUnit(1, renderer.target(MainTarget::Visibility));
    renderer.drawFullscreenTriangle();
    return true;
}

void ViewCompositor::setHeatmap(int side, const Image& heatmap) {
    const glm::ivec2 size{heatmap.width, heatmap.height};
    if (side < 0 || side >= kSides) return;
    if (heatmapSizes_[side] != size) {
        heatmaps_[side] = makeTexture(GL_RGBA8, size);
        heatmapSizes_[side] = size;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(heatmaps_[side].get(), 0, 0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, heatmap.pixels.data());
}

void ViewCompositor::blitDisplay(const Renderer& renderer, GLuint target, glm::ivec2 surface, glm::ivec2 origin,
                                 glm::ivec2 size, int sourceX) {
    if (size.x <= 0 || size.y <= 0) return;
    const glm::ivec2 display = renderer.size();
    const int w = std::min(size.x, display.x - sourceX), h = std::min(size.y, display.y);
    const int y0 = surface.y - (origin.y + h);
    glBlitNamedFramebuffer(renderer.displayFramebuffer(), target, sourceX, 0, sourceX + w, h, origin.x, y0, origin.x + w,
                           y0 + h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

Image ViewCompositor::readSurface(GLuint framebuffer, glm::ivec2 size) {
    Image image{size.x, size.y, 4, std::vector<uint8_t>(size_t(size.x) * size_t(size.y) * 4)};
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    glReadBuffer(framebuffer == 0 ? GL_BACK : GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
    for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
    return image;
}

} // namespace shadowlab
