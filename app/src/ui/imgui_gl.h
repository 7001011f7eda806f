// Draws Dear ImGui's draw lists with the host's GL (glad), into any framebuffer. Used instead of
// Debian's imgui_impl_opengl3, whose own GL loader looks up GLX entry points: with the EGL or
// OSMesa backends (no GLX context) it fails, and the window could not be drawn offscreen.
// Every GL object is created at init or when the font changes, none per frame.
#pragma once

#include <string>

#include <imgui.h>

#include "gl/gl.h"

namespace shadowlab {

class ImGuiGlRenderer {
public:
    bool init(std::string& error);
    // (Re)builds the font atlas texture from ImGui's current fonts.
    void createFontTexture();
    void render(const ImDrawData* data, GLuint framebuffer);

private:
    GlProgram program_;
    GlVertexArray vao_;
    GlBuffer vertices_, indices_;
    GlTexture font_;
    size_t vertexBytes_ = 0, indexBytes_ = 0;
};

} // namespace shadowlab
