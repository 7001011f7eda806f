// Host debug views of the shadow maps a technique reported (SHADOWLAB_EXT_SHADOW_MAPS), drawn over
// the last frame's G-buffer into the display: the texel footprint m (seed 002 eq. 8.1) as a heat
// map, the map's texel grid projected on the receivers, and the map coverage (which map or
// cascade serves each pixel) with the edges of every map's volume (the light frustum). Programs
// and the uniform buffer are made once; a frame only updates the buffer.
#pragma once

#include <string>
#include <vector>

#include "gl/gl.h"
#include "render/renderer.h"
#include "render/shader_library.h"

namespace shadowlab {

enum class ShadowMapView { Footprint = 0, TexelGrid = 1, Coverage = 2 };

class ShadowMapViews {
public:
    static constexpr size_t kMaxMaps = 16;   // shaders/shadow_map_view.glsl's array
    bool init(ShaderLibrary& shaders, std::string& error);
    // Draws `view` of `maps` into `framebuffer` (viewport `size`) from the renderer's position,
    // normal and colour targets, which must hold the frame (accuracy targets current). No maps:
    // the lit image dimmed, with nothing to show.
    void draw(Renderer& renderer, ShadowMapView view, const std::vector<ShadowMapInfo>& maps, GLuint framebuffer,
              glm::ivec2 size);
    // Deletes the GL objects (the app calls it while its context still exists).
    void release();

private:
    ShaderLibrary* shaders_ = nullptr;
    ProgramId viewProgram_ = 0, frustumProgram_ = 0;
    GlBuffer uniforms_;
    GlVertexArray emptyVao_;
};

} // namespace shadowlab
