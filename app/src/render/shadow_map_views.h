// Host debug views of the shadow maps a technique reported (SHADOWLAB_EXT_SHADOW_MAPS), drawn over
// the last frame's G-buffer into the display: the texel footprint m (seed 002 eq. 8.1) as a heat
// map, the map's texel grid projected on the receivers, and the map coverage (which map or
// cascade serves each pixel) with the edges of every map's volume (the light frustum); the focus
// body B the map was fitted to (seed 002 eq. 4.2) as white edges; the filter kernel's footprint
// around a probed pixel (render/kernel_probe.h). Programs, the uniform buffer and the overlay's
// vertex buffer are made once; a frame only updates the buffers.
#pragma once

#include <string>
#include <vector>

#include "gl/gl.h"
#include "render/kernel_probe.h"
#include "render/renderer.h"
#include "render/shader_library.h"

namespace shadowlab {

enum class ShadowMapView { Footprint = 0, TexelGrid = 1, Coverage = 2, FocusBody = 3, Kernel = 4 };

// Colours of the overlays (sRGB, 0..1), for the tests that find them in the image.
namespace overlay_colour {
inline constexpr glm::vec3 kFocusBody{1.0f, 1.0f, 1.0f};      // B's edges
inline constexpr glm::vec3 kBox{1.0f, 0.85f, 0.0f};           // PCF: the texels the box reads
inline constexpr glm::vec3 kFilterDisc{0.1f, 1.0f, 0.3f};     // the filter disc's rim
inline constexpr glm::vec3 kSearchDisc{0.0f, 0.9f, 1.0f};     // PCSS: the blocker search region
inline constexpr glm::vec3 kLitTap{1.0f, 1.0f, 0.6f};
inline constexpr glm::vec3 kShadowedTap{1.0f, 0.2f, 0.9f};
inline constexpr glm::vec3 kSkippedTap{0.45f, 0.45f, 0.45f};  // after the early out: not read
inline constexpr glm::vec3 kBlocker{1.0f, 0.15f, 0.1f};       // PCSS search sample that found a blocker
inline constexpr glm::vec3 kNoBlocker{0.2f, 0.6f, 1.0f};
inline constexpr glm::vec3 kProbe{1.0f, 1.0f, 1.0f};          // cross on the probed point
}

class ShadowMapViews {
public:
    static constexpr size_t kMaxMaps = 16;   // shaders/shadow_map_view.glsl's array
    bool init(ShaderLibrary& shaders, std::string& error);
    // Draws `view` of `maps` into `framebuffer` (viewport `size`) from the renderer's position,
    // normal and colour targets, which must hold the frame (accuracy targets current). No maps:
    // the lit image dimmed, with nothing to show.
    // FocusBody: `bodies` (PluginHost::focusBodyEdges, per map) over the dimmed lit image and the
    // maps' volumes. Kernel: `probe`'s footprint (map 0's) over the lit image.
    void draw(Renderer& renderer, ShadowMapView view, const std::vector<ShadowMapInfo>& maps, GLuint framebuffer,
              glm::ivec2 size, const std::vector<std::vector<glm::vec3>>* bodies = nullptr,
              const KernelProbe* probe = nullptr);
    static constexpr size_t kMaxOverlayVertices = 32768;
    // Deletes the GL objects (the app calls it while its context still exists).
    void release();

private:
    ShaderLibrary* shaders_ = nullptr;
    struct OverlayVertex {
        glm::vec3 position;
        glm::vec3 colour;
    };
    // Appends the kernel footprint's lines and points of `probe` (world space on the receiver plane).
    static void kernelOverlay(const ShadowMapInfo& map, const KernelProbe& probe, std::vector<OverlayVertex>& lines,
                              std::vector<OverlayVertex>& points);
    void drawOverlay(const std::vector<OverlayVertex>& vertices, GLenum mode);
    ProgramId viewProgram_ = 0, frustumProgram_ = 0, overlayProgram_ = 0;
    GlBuffer uniforms_, overlayVertices_;
    GlVertexArray emptyVao_, overlayVao_;
};

} // namespace shadowlab
