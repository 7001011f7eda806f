// Composing the window's view from the renderer's display texture (App::runInteractive): the
// surface it is drawn on (the window's framebuffer, or an offscreen one of the same layout when
// there is no display), the difference of two techniques' shadow terms, the error heatmaps of a
// measurement, and blits of the display into a rectangle of the surface. GL objects are created
// when a size changes or a measurement arrives, never per frame; all of them go with the object.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "gl/gl.h"
#include "render/renderer.h"
#include "render/shader_library.h"
#include "util/image.h"

namespace shadowlab {

class ViewCompositor {
public:
    explicit ViewCompositor(ShaderLibrary& shaders);
    ~ViewCompositor();
    ViewCompositor(const ViewCompositor&) = delete;
    ViewCompositor& operator=(const ViewCompositor&) = delete;

    // The offscreen surface at `size` (re-created when it changes): false, with `error`, when
    // the framebuffer is incomplete.
    bool prepareOffscreen(glm::ivec2 size, std::string& error);
    GLuint offscreenFramebuffer() const { return surface_.get(); }

    // The difference view: keepFirstTerm() copies side A's shadow term (the renderer's visibility
    // target) before B renders into the same targets; drawDifference() then writes |A - B| into
    // the renderer's display texture. False when the difference program failed to build.
    void keepFirstTerm(const Renderer& renderer);
    bool drawDifference(Renderer& renderer);

    // A side's error heatmap over its dimmed frame (RGBA8), shown in place of its view.
    void setHeatmap(int side, const Image& heatmap);
    GLuint heatmap(int side) const { return side >= 0 && side < kSides ? heatmaps_[side].get() : 0; }

    // The display texture into `target` (of size `surface`) at the rectangle whose top-left corner
    // is `origin` (window pixels from the top left), from the part of the display `sourceX` pixels in.
    static void blitDisplay(const Renderer& renderer, GLuint target, glm::ivec2 surface, glm::ivec2 origin, glm::ivec2 size,
                            int sourceX);
    // The surface's pixels (a screenshot), opaque.
    static Image readSurface(GLuint framebuffer, glm::ivec2 size);

private:
    ShaderLibrary& shaders_;
    ProgramId differenceProgram_ = 0;
    GlTexture surfaceColor_;
    GlFramebuffer surface_;
    glm::ivec2 surfaceSize_{0};
    GlTexture firstTerm_;
    glm::ivec2 firstTermSize_{0};
    static constexpr int kSides = 4;   // a grid's four cells
    GlTexture heatmaps_[kSides];
    glm::ivec2 heatmapSizes_[kSides]{};
};

} // namespace shadowlab
