// The host's GL side: scene geometry on the GPU, the per-frame uniform block, the GL state
// contract, the camera pre-pass, the main pass (forward Blinn-Phong into the colour target; on
// frames measured for accuracy also into visibility and G-buffer targets), the optional depth
// pre-pass, and the present pass. Everything here is created once (or when the size changes),
// never per frame.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "gl/gl.h"
#include "render/overdraw_counter.h"
#include "render/shader_library.h"
#include "scene/scene.h"
#include "shadowlab/technique.h"
#include "util/image.h"

namespace shadowlab {

enum class PresentMode : int { Lit = 0, Visibility = 1, Depth = 2, Color = 3, Moments = 4 };
enum class MainTarget { Color, Visibility, Position, Normal };
// What a main pass writes. Timed frames write what a real renderer writes, the lit colour; only
// frames measured for accuracy (never timed) add the shadow term, world position and normal.
enum class FrameOutputs { Colour, Accuracy };

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

    // Host services for techniques.
    Bounds bounds(DrawSet set) const;
    uint32_t objectCount() const;
    const ObjectInfo* objects() const;
    void drawScene(const DrawRequest& request, GLuint program);
    void drawScene(DrawSet set, GLuint program) {
        DrawRequest request;
        request.set = set;
        drawScene(request, program);
    }
    void drawObject(uint32_t index, GLuint program);
    void drawFullscreenTriangle();
    GLuint sampler(SamplerKind kind) const;

    // The GL state contract of shadowlab/technique.h, set before every technique call.
    void applyDefaultState();
    // Its pipeline part only (not the texture, sampler and buffer bindings a technique made).
    void resetPipelineState();

    // Camera pre-pass into its own targets (allocated on first use): depth, world position,
    // normal and object id of the opaque surfaces, rasterised exactly as the main pass does; or
    // (Depth, kTechniqueNeedsCameraDepth) the depth alone, into the same depth texture with the
    // main pass's vertex stage and no fragment stage, so it is bit for bit the full pass's depth.
    // The colour targets are allocated only once a full pre-pass is asked for.
    enum class PrepassKind { Full, Depth };
    void cameraPrepass(PrepassKind kind = PrepassKind::Full);
    // The full pre-pass's targets (depth 0 before the first full pre-pass) and the depth-only
    // view of the same depth texture (position, normal and objectId 0).
    const CameraPrepass& prepassTargets() const { return prepass_; }
    const CameraPrepass& prepassDepthTargets() const { return prepassDepthOnly_; }

    // SHADOWLAB_EXT_ADJACENCY: the casters' triangles with adjacency (the buffers of
    // DrawPrimitive::TrianglesAdjacency) and their batches, built on the first call or adjacency
    // draw after setScene() and kept until the next setScene().
    const AdjacencyScene& adjacencyScene();

    // SHADOWLAB_EXT_RAY_TRACING: the shadow casters' BVH (render/bvh.h) in storage buffers, built
    // on the first call after setScene() and kept (with its buffers) until the next setScene().
    const RayTracingScene& rayTracing();

    // The main pass with a technique's main program: default state and the program bound,
    // bindTechnique() sets its uniforms and textures, then the host's main-pass state and draws.
    // `program` must be the variant built for `outputs` (LoadedTechnique::mainProgram).
    template <typename BindTechnique>
    void mainPass(GLuint program, FrameOutputs outputs, BindTechnique&& bindTechnique) {
        applyDefaultState();
        glUseProgram(program);
        bindTechnique();
        resetPipelineState();   // whatever bindTechnique() changed besides its bindings
        beginMainPass(program, outputs);
        drawMainPassObjects(program, outputs);
        endMainPass(outputs);
    }
    // Optional depth pre-pass (before mainPass, same frame): the opaque surfaces' depth into the
    // main targets, so the main pass then runs the shadow term once per visible pixel (depth test
    // EQUAL, no depth write). main.vert's invariant gl_Position makes both depths identical.
    void mainDepthPrepass(FrameOutputs outputs);
    // Depth complexity (render/overdraw_counter.h, issue 32): the next pass that depth-tests the
    // opaque surfaces with LESS (mainDepthPrepass, or mainPass without one) counts the fragments
    // that pass. pollOverdraw(): the newest finished count per sample, never waiting.
    void countOverdrawNextPass() { overdrawArmed_ = true; }
    std::optional<double> pollOverdraw() { return overdraw_.poll(); }
    // SHADOWLAB_EXT_TRANSLUCENT_DRAWS: while set, the main pass and translucentLayer() draw the
    // translucent objects one at a time (back to front from the camera) and call the hook before
    // each with its index, and once with kTranslucentDrawsDone after the last. The hook may change
    // any GL state, and leaves the pass's program bound with the technique's bindings; the
    // renderer sets its own state again before each draw. Empty: one sorted draw request.
    // The hook refers to a callable of the caller's, which must outlive its passes (a reference,
    // not a copy: nothing is allocated per frame).
    struct TranslucentHook {
        void* callable = nullptr;
        void (*call)(void* callable, uint32_t object) = nullptr;
        explicit operator bool() const { return call != nullptr; }
        void operator()(uint32_t object) const { call(callable, object); }
    };
    template <typename Callable>
    static TranslucentHook translucentHookFor(Callable& callable) {
        return {&callable, [](void* c, uint32_t object) { (*static_cast<Callable*>(c))(object); }};
    }
    void setTranslucentHook(TranslucentHook hook) { translucentHook_ = hook; }

    // Evaluation frames only (never timed): translucent layer `k` (0 = nearest the camera) in front
    // of the opaque depth of the last accuracy main pass, peeled behind layer k - 1 (call them in
    // order 0, 1, ...; host_shared/translucent_layers_shared.h). `program` is the technique's main
    // pass built with SHADOWLAB_ACCURACY_TARGETS and SHADOWLAB_TRANSLUCENT_PEEL; the layer's shadow
    // term, position and normal go to the layerTarget() textures. False (nothing drawn) when the
    // scene has no translucent object or the main pass is multisampled (its single-sample depth
    // is not written then).
    template <typename BindTechnique>
    bool translucentLayer(int k, GLuint program, BindTechnique&& bindTechnique) {
        if (!scene_ || opaqueBatches_.size() == batches_.size() || msaaSamples_ > 0) return false;
        applyDefaultState();
        glUseProgram(program);
        bindTechnique();
        resetPipelineState();
        beginTranslucentLayer(k);
        drawTranslucent(program, [this, k, program] { setTranslucentLayerState(k, program); });
        return true;
    }
    // The texture a translucent layer's Visibility, Position or Normal goes to (0 for Color).
    GLuint layerTarget(MainTarget which) const;

    // The framebuffer a main pass of `outputs` draws into (tests check its attachments).
    GLuint mainFramebuffer(FrameOutputs outputs) const;
    // Whether the last main pass wrote the visibility, position and normal targets.
    bool accuracyTargetsCurrent() const { return accuracyCurrent_; }

    // The eye-space depth-dependent blur of the shadow term (seed 002 sec. 6.3, 9.4.2;
    // host_shared/eye_blur_shared.h), between the technique's shadow pass and the main pass:
    // eyeBlurTermPass() draws the opaque surfaces with `program` (the technique's main pass built
    // with SHADOWLAB_EYE_BLUR_TERM) into a screen texture, rgb = shadow term, a = view depth;
    // eyeBlur() blurs it along x, then y, back into that texture. Main passes after
    // setEyeBlurRead(true) (with the SHADOWLAB_EYE_BLUR_READ program) read it on unit
    // kEyeBlurTermUnit for their opaque surfaces. The textures (two RGBA32F, exact for the term,
    // and a depth buffer) are made on first use and on resize, the program once in init().
    template <typename BindTechnique>
    void eyeBlurTermPass(GLuint program, BindTechnique&& bindTechnique) {
        applyDefaultState();
        glUseProgram(program);
        bindTechnique();
        resetPipelineState();
        beginEyeBlurTerm(program);
        drawOpaque(program);
    }
    void eyeBlur(float width, float referenceDepth);
    void setEyeBlurRead(bool on) { eyeBlurRead_ = on; }
    // Seed 002 sec. 6.2 / Fig. 6.7 in every main pass: 0 phong (the three rules), 1 none (unlit).
    void setLighting(int model) { lighting_ = model; }
    // The blurred term of the last eyeBlur() (tests read it), 0 before the first.
    GLuint eyeBlurTexture() const { return eyeBlurTerm_[0].get(); }

    // Screen-space contact shadows (issue 30; host_shared/contact_shadows_shared.h): contactShadows()
    // marches from every pixel of the camera pre-pass's depth (cameraPrepass() must have run this
    // frame) towards the light, into an R8 screen texture (1 lit, 0 occluded); main passes after
    // setContactRead(true) take min(their term, it) for their opaque surfaces. The texture and its
    // framebuffer are made on first use and on resize, the program once in init().
    struct ContactSettings {
        float length = 0.0f;      // world units
        float thickness = 0.25f;  // world units
        int steps = 16;
        float jitter = 1.0f;
    };
    void contactShadows(const ContactSettings& settings);
    void setContactRead(bool on) { contactRead_ = on; }
    // The contact term of the last contactShadows() (tests read it), 0 before the first.
    GLuint contactTexture() const { return contactTerm_.get(); }

    // Present pass into `framebuffer` (0 = window) or, with framebuffer = ~0u, the display texture.
    // `origin`: the viewport's lower left corner in the framebuffer (a letterboxed debug image).
    void present(PresentMode mode, GLuint texture, GLuint framebuffer, glm::ivec2 viewport, glm::vec2 range = {0, 1},
                 glm::ivec2 origin = {0, 0});
    GLuint target(MainTarget which) const;
    GLuint displayTexture() const { return displayColor_.get(); }
    GLuint displayFramebuffer() const { return displayFbo_.get(); }

    // Synchronous read-backs: headless renders, screenshots and accuracy only, never per frame.
    Image readDisplay() const;
    std::vector<glm::vec4> readTarget(MainTarget which) const;
    // Uploads an RGBA8 image into the display texture (e.g. an error heatmap computed on the CPU).
    void uploadDisplay(const Image& image);

private:
    void uploadSceneGeometry(const Scene& scene);   // meshRanges_, vertexBuffer_, indexBuffer_
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
    void beginMainPass(GLuint program, FrameOutputs outputs);
    void beginEyeBlurTerm(GLuint program);
    void drawOpaque(GLuint program);
    void allocateEyeBlurTargets();
    void allocateContactTargets();
    void drawMainPassObjects(GLuint program, FrameOutputs outputs);
    // The translucent objects, back to front from the camera: one request, or one by one with the
    // hook (setState() runs before the draw, and after each hook call).
    void drawTranslucent(GLuint program, const std::function<void()>& setState);
    void setMainTranslucentState(GLuint program, FrameOutputs outputs);
    void beginTranslucentLayer(int k);
    void setTranslucentLayerState(int k, GLuint program);
    void allocateLayerTargets();
    void endMainPass(FrameOutputs outputs);
    void clearMainTargets(GLuint fbo, FrameOutputs outputs, bool depth);
    void drawBatch(uint32_t firstObject, uint32_t count, uint32_t mesh, uint32_t material,
                   DrawPrimitive primitive = DrawPrimitive::Triangles);
    // Triangles with adjacency of every mesh (DrawPrimitive::TrianglesAdjacency), built on the
    // first draw that asks after a scene load.
    void prepareAdjacency();
    void bindSceneGeometry(GLuint program);
    void allocatePrepassTargets(bool full);

    ShaderLibrary& shaders_;
    const Scene* scene_ = nullptr;
    GlBuffer vertexBuffer_, indexBuffer_, frameUniforms_, objectTransforms_;
    GlVertexArray sceneVao_, emptyVao_;
    // Scene::textures on the GPU (GL_LINEAR, GL_REPEAT, no mipmaps: as sampleTexture), and a
    // white texel bound where a material has none. drawBatch binds a material's textures on the
    // host's units 1 (transmission) and 2 (base colour) in every pass, light passes included.
    std::vector<GlTexture> transmissionTextures_, baseColorTextures_;
    GlTexture whiteTexture_;
    std::vector<MeshRange> meshRanges_;
    GlBuffer adjacencyIndices_;
    GlVertexArray adjacencyVao_;
    std::vector<MeshRange> adjacencyRanges_;     // empty until prepareAdjacency()
    std::vector<uint8_t> meshClosed_;
    bool adjacencyReady_ = false;                // prepareAdjacency() ran for this scene
    std::vector<AdjacencyBatch> adjacencyBatches_;   // the casters' runs (adjacencyScene())
    AdjacencyScene adjacencyScene_{};
    bool adjacencySceneReady_ = false;
    std::vector<Batch> batches_;                 // every object, in scene order
    std::vector<uint32_t> batchOfObject_;        // object index -> its batch
    std::vector<uint32_t> opaqueBatches_;        // indices into batches_
    std::vector<std::pair<float, uint32_t>> drawOrder_;  // sorted or culled draws, reused each frame
    std::vector<uint32_t> translucentOrder_;     // the hook's objects (the hook may draw in between)
    TranslucentHook translucentHook_;
    void collectDrawOrder(const DrawRequest& request);

    glm::ivec2 size_{0};
    int msaaSamples_ = 0;
    GlTexture color_, visibility_, position_, normal_, depth_;          // resolved, single-sample
    GlTexture msColor_, msVisibility_, msPosition_, msNormal_, msDepth_; // when MSAA is on
    // Per FrameOutputs: colour and depth only, or all four targets. MSAA ones resolve into these.
    GlFramebuffer mainFbo_[2], msFbo_[2];
    bool accuracyCurrent_ = false;
    bool depthPrepassed_ = false;                // this frame's main pass follows a depth pre-pass
    OverdrawCounter overdraw_;
    bool overdrawArmed_ = false;
    bool beginOverdrawCount();                   // consumes overdrawArmed_; true when a query runs
    GlTexture displayColor_;
    GlFramebuffer displayFbo_;
    GlSampler presentSampler_;
    GlSampler samplers_[6];                      // by SamplerKind
    ProgramId presentProgram_ = 0;
    ProgramId prepassProgram_ = 0;
    ProgramId depthOnlyProgram_ = 0;
    GlTexture prepassDepth_, prepassPosition_, prepassNormal_, prepassObjectId_;
    GlTexture prepassStencil_;   // a view of prepassDepth_ sampling its stencil (CameraPrepass::stencil)
    GlFramebuffer prepassFbo_, prepassDepthFbo_;  // all four targets; the depth alone
    bool prepassFull_ = false;                   // the colour targets exist
    CameraPrepass prepass_{}, prepassDepthOnly_{};
    GlBuffer rayTracingBuffers_[5];              // nodes, triangles, uvs, materials, texels
    RayTracingScene rayTracing_{};
    bool rayTracingBuilt_ = false;

    // The eye-space blur (eyeBlur*): [0] the term and the blurred result, [1] the blur along x.
    GlTexture eyeBlurTerm_[2], eyeBlurDepth_;
    GlFramebuffer eyeBlurTermFbo_, eyeBlurFbo_[2];
    ProgramId eyeBlurProgram_ = 0;
    bool eyeBlurRead_ = false;

    // Contact shadows (contactShadows): the term, its framebuffer and the march.
    GlTexture contactTerm_;
    GlFramebuffer contactFbo_;
    ProgramId contactProgram_ = 0;
    bool contactRead_ = false;

    // Translucent layers (translucentLayer): shadow term, position and normal as the accuracy
    // targets, and two 32F depths, this layer's and the previous one's, alternating.
    GlTexture layerVisibility_, layerPosition_, layerNormal_, layerDepth_[2];
    GlFramebuffer layerFbo_[2];
    int lighting_ = 0;

    CameraInfo camera_{};
    LightInfo light_{};
};

} // namespace shadowlab
