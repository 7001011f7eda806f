// The host's GL side: scene geometry on the GPU, the per-frame uniform block, the main pass
// (forward Blinn-Phong into colour + visibility + G-buffer targets) and the present pass.
// Everything here is created once (or when the size changes), never per frame.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "gl/gl.h"
#include "render/shader_library.h"
#include "scene/scene.h"
#include "shadowlab/technique.h"
#include "util/image.h"

namespace shadowlab {

enum class PresentMode : int { Lit = 0, Visibility = 1, Depth = 2, Color = 3, Moments = 4 };
enum class MainTarget { Color, Visibility, Position, Normal };

class Renderer {
public:
    explicit Renderer(ShaderLibrary& shaders) : shaders_(shaders) {}
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    bool init(std::string& error);
    void setScene(const Scene& scene);
    const Scene* scene() const { return scene_; }
    bool resize(glm::ivec2 size, int msaaSamples, std::string& error);
    glm::ivec2 size() const { return size_; }
    int msaaSamples() const { return msaaSamples_; }

    // Per frame: camera and light in, frame uniform block updated.
    void setView(const CameraInfo& camera, const LightInfo& light);
    const CameraInfo& camera() const { return camera_; }
    const LightInfo& light() const { return light_; }
    const LightSpace& defaultLightSpace() const { return defaultLightSpace_; }

    // Host services for techniques.
    Bounds bounds(DrawSet set) const;
    uint32_t objectCount() const;
    ObjectInfo objectInfo(uint32_t index) const;
    void drawScene(DrawSet set, GLuint program);
    void drawObject(uint32_t index, GLuint program);
    void drawFullscreenTriangle();

    // The main pass with a technique's main program (bindTechnique sets its uniforms).
    template <typename BindTechnique>
    void mainPass(GLuint program, BindTechnique&& bindTechnique) {
        beginMainPass(program);
        bindTechnique(program);
        drawMainPassObjects(program);
        endMainPass();
    }

    // Present pass into `framebuffer` (0 = window) or, with framebuffer = ~0u, the display texture.
    void present(PresentMode mode, GLuint texture, GLuint framebuffer, glm::ivec2 viewport, glm::vec2 range = {0, 1});
    void presentToDisplay(PresentMode mode, GLuint texture, glm::vec2 range = {0, 1});
    GLuint target(MainTarget which) const;
    GLuint displayTexture() const { return displayColor_.get(); }
    GLuint displayFramebuffer() const { return displayFbo_.get(); }

    // Synchronous read-backs: headless renders, screenshots and accuracy only, never per frame.
    Image readDisplay() const;
    std::vector<glm::vec4> readTarget(MainTarget which) const;
    // Uploads an RGBA8 image into the display texture (e.g. an error heatmap computed on the CPU).
    void uploadDisplay(const Image& image);

private:
    struct MeshRange {
        uint32_t firstIndex;
        uint32_t indexCount;
        int32_t baseVertex;
    };
    // A run of consecutive objects with the same mesh, material and shadow flags: one instanced draw.
    struct Batch {
        uint32_t firstObject;
        uint32_t count;
        uint32_t mesh;
        uint32_t material;
    };
    void beginMainPass(GLuint program);
    void drawMainPassObjects(GLuint program);
    void endMainPass();
    void drawBatch(uint32_t firstObject, uint32_t count, uint32_t mesh, uint32_t material);

    ShaderLibrary& shaders_;
    const Scene* scene_ = nullptr;
    GlBuffer vertexBuffer_, indexBuffer_, frameUniforms_, objectTransforms_;
    GlVertexArray sceneVao_, emptyVao_;
    std::vector<MeshRange> meshRanges_;
    std::vector<Batch> batches_;                 // every object, in scene order
    std::vector<uint32_t> opaqueBatches_;        // indices into batches_
    std::vector<uint32_t> translucentObjects_;   // drawn one by one, sorted
    std::vector<std::pair<float, uint32_t>> translucentOrder_;  // reused each frame

    glm::ivec2 size_{0};
    int msaaSamples_ = 0;
    GlTexture color_, visibility_, position_, normal_, depth_;          // resolved, single-sample
    GlTexture msColor_, msVisibility_, msPosition_, msNormal_, msDepth_; // when MSAA is on
    GlFramebuffer mainFbo_, msFbo_;
    GlTexture displayColor_;
    GlFramebuffer displayFbo_;
    GlSampler presentSampler_;
    ProgramId presentProgram_ = 0;

    CameraInfo camera_{};
    LightInfo light_{};
    LightSpace defaultLightSpace_{};
};

} // namespace shadowlab
