// A depth map that can write its own depth: linear depth along the light, the bias applied in the
// fragment stage, and the two-layer biases of seed 002 ch. 5 (a second layer by depth peeling,
// sec. 5.2: the midpoint of eq. 5.1 and second-depth shadow mapping). The plumbing of every
// single-map technique's `bias_method` (shadowmap, psm, lispsm, tsm; pcf, adaptive-pcf, pcss, rbsm
// and edtsm through kit::LayeredDepthMaps and resolve()): with the offset method and neither
// linear depth nor a fragment-stage bias it is a plain kit::DepthMap pass (glPolygonOffset).
//
// Why the bias in the fragment stage for warped maps: with depth clamp on, a warped caster's
// unclamped window z can be far outside [0, 1], and a 32F depth buffer's offset unit is 2^(e - 23)
// for the primitive's largest exponent e, so on an H200 those casters were pushed behind the
// receivers (every shadow of the perspective-near and light-behind stress cases lost under lispsm;
// llvmpipe's unit stayed 2^-24). In the fragment stage a unit is 2^-24.
// Main-pass side: shaders/layered_depth.glsl's layeredShadowMap(); block binding 14, units 12-13.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <shadowlab/kit/depth_map.h>
#include <shadowlab/kit/layered_depth_shared.h>
#include <shadowlab/kit/params.h>

namespace shadowlab::kit {

enum class BiasMethod : int { Offset = 0, Midpoint = 1, SecondDepth = 2, InvertedBackFaces = 3 };

constexpr ParamDesc biasMethodParam() {
    return enumParam("bias_method", "bias method", 0, "offset|midpoint|second-depth|inverted-back-faces",
            "offset: constant and slope-scaled offset (eq. 5.2). midpoint: a second layer by depth peeling and "
            "the test against min((z2 - z1) / 2, z_offset) past the first (eq. 5.1, dual shadow maps). "
            "second-depth: the test against the second layer (Wang and Molnar). inverted-back-faces: back faces "
            "stored (cull front) with the offset reversed, towards the light. The two-layer methods draw every "
            "face, ignore the bias and cull parameters and cost a second depth pass (seed 002 ch. 5); pcf, "
            "adaptive-pcf, pcss, rbsm and edtsm also resolve both layers into the one map they read (one more "
            "pass); the filtering ones keep their cone bias, a receiver-side bias. Point lights' cube maps: "
            "offset only.");
}
constexpr ParamDesc zOffsetParam() {
    return {"z_offset", "midpoint z_offset", ParamType::Float, 0, 1, 0.05, "depth range",
            "Eq. 5.1's largest bias, in units of the map's depth range: about an object's size. Too small "
            "brings back acne where the second surface is far (a ground plane); too large lets light leak "
            "under casters close to their receivers.",
            nullptr};
}

} // namespace shadowlab::kit

// The two-layer biases of every single-map technique (seed 002 ch. 5), spliced after its bias group.
#define SHADOWLAB_TWO_LAYER_PARAMS(X)                                   \
    X(int, bias_method, ::shadowlab::kit::biasMethodParam())            \
    X(float, z_offset, ::shadowlab::kit::zOffsetParam())

namespace shadowlab::kit {

struct LayeredDepthConfig {
    BiasMethod method = BiasMethod::Offset;
    float zOffset = 0.05f;
    // A world plane giving the stored depth 0..1 (linear depth along the light), or none: the light
    // matrix's own z.
    std::optional<glm::vec4> linearDepthPlane{};
    bool fragmentBias = false;   // the offset in the fragment stage even for plain depth (warped maps)
};

template <class Values>
LayeredDepthConfig layeredDepthConfig(const Values& values) {
    return {.method = BiasMethod(std::clamp(int(values.bias_method), 0, 3)), .zOffset = float(values.z_offset)};
}

// Linear depth 0..1 along the light matrix's view axis over `points` (seed 002 sec. 5.3; TSM's
// linear z): the plane for LayeredDepthConfig::linearDepthPlane. Along any ray from a spot light
// the distance along its axis grows too, so the order of depths is the light's for both types.
// The range is padded by 1e-4 of the points' extent at both ends (issue 28): a receiver on B's
// boundary lies outside B by its clipping's rounding, which scales with B's size, not with its
// depth range. On `aliasing-plane` (B 205 m wide and 1 m deep along the light, the light 4.4e-8
// rad off vertical from float trigonometry) the ground's far right came out 4e-6 beyond the far
// end: depth 1 + 4e-6 against a cleared 1.0, which a 32F map does not clamp, so tsm's far view
// read shadowed wherever the view was wide enough (16:9, not 16:10).
inline glm::vec4 linearDepthPlane(const LightSpace& lightSpace, const std::vector<glm::vec3>& points) {
    const glm::vec3 axis = -glm::vec3(lightSpace.view[0][2], lightSpace.view[1][2], lightSpace.view[2][2]);
    float lo = INFINITY, hi = -INFINITY;
    glm::vec3 boxLo(INFINITY), boxHi(-INFINITY);
    for (const glm::vec3& p : points) {
        lo = std::min(lo, glm::dot(axis, p));
        hi = std::max(hi, glm::dot(axis, p));
        boxLo = glm::min(boxLo, p);
        boxHi = glm::max(boxHi, p);
    }
    if (!points.empty()) {
        const float pad = 1e-4f * glm::length(boxHi - boxLo);
        lo -= pad;
        hi += pad;
    }
    const float range = std::max(hi - lo, 1e-6f);
    return points.empty() ? glm::vec4(0.0f) : glm::vec4(axis / range, -lo / range);
}
// The same over the focus body B, or the scene's corners where B is empty.
inline glm::vec4 linearDepthPlane(const LightSpace& lightSpace, const ConvexBody& body, const Bounds& scene) {
    if (!body.empty()) return linearDepthPlane(lightSpace, body.vertices());
    glm::vec3 corners[8];
    boundsCorners(scene, corners);
    return linearDepthPlane(lightSpace, std::vector<glm::vec3>(corners, corners + 8));
}

inline bool usesTwoLayers(BiasMethod method) { return method == BiasMethod::Midpoint || method == BiasMethod::SecondDepth; }

// One depth pass of `layered` (LayeredDepthMap::draw, kit::WarpedFaceMaps): `config` adjusted for
// the method (inverted back faces: front faces culled, the offset reversed; two layers: every face,
// no offset, the layers' gap being the bias) and the pass's block. Where the fragment stage writes
// depth (two layers, linear depth, a fragment-stage bias) the offset moves into the block and
// `config.program` becomes `program` (shaders/layered_depth.vert/.frag).
inline shared::layered_depth::LayeredDepthUniforms layeredPass(DepthMapConfig& config, const LayeredDepthConfig& layered,
                                                              const Program& program) {
    const bool twoLayers = usesTwoLayers(layered.method);
    if (layered.method == BiasMethod::InvertedBackFaces) {
        config.cull = Cull::Front;
        config.constantBias = -config.constantBias;
        config.slopeBias = -config.slopeBias;
    }
    if (twoLayers) {
        config.cull = Cull::None;
        config.constantBias = config.slopeBias = 0.0f;
    }
    shared::layered_depth::LayeredDepthUniforms block{};
    block.uLinearDepthPlane = layered.linearDepthPlane.value_or(glm::vec4(0.0f));
    block.uLinearDepth = layered.linearDepthPlane ? 1 : 0;
    block.uBiasMethod = twoLayers ? int(layered.method) : 0;
    block.uZOffset = layered.zOffset;
    block.uPeelTolerance = config.format == GL_DEPTH_COMPONENT16   ? 1.0f / 65535.0f
                           : config.format == GL_DEPTH_COMPONENT24 ? 1.0f / 16777215.0f
                                                                   : 0.0f;
    if (twoLayers || layered.linearDepthPlane || layered.fragmentBias) {
        block.uSlopeFactor = config.slopeBias;
        block.uConstantUnits = config.constantBias;
        config.program = &program;
        config.constantBias = config.slopeBias = 0.0f;
    }
    return block;
}

class LayeredDepthMap {
public:
    // `resolvable`: the map also builds resolve() (the filtering techniques' one compare map).
    bool create(IHost& host, std::string& error, bool resolvable = false) {
        host_ = &host;
        if (!map_.create(host, error) || !second_.create(host, error)) return false;
        uniforms_.create(host, "layered depth");
        if (resolvable && (!resolved_.create(host, error) ||
                           !resolveProgram_.build(host, {.vertexFile = "fullscreen.vert",
                                                         .fragmentFile = "layered_depth_resolve.frag"}, error)))
            return false;
        return program_.build(host, {.vertexFile = "layered_depth.vert", .fragmentFile = "layered_depth.frag"}, error);
    }

    // DepthMap::render()'s frame (the fit, one timed "shadow map" pass, the map reported) with the
    // layers of `layered`.
    void render(const FrameContext& frame, const DepthMapConfig& config, const LayeredDepthConfig& layered) {
        GpuPass pass(*host_, "shadow map");
        const FocusedLightSpace focused = focusLightSpace(*host_, frame, config.fit, config.resolution);
        draw(focused.light, config, layered, focused.cullPlanes);
        map_.setFocusBody(focused.body);
        map_.reportToHost();
    }

    // A warped map's frame (lispsm, tsm): the map focused on B (`focused`), its matrix replaced by
    // `warp` (world -> clip, projective) where there is one (the statistic "warped" says whether),
    // the bias in the fragment stage, linear depth over B when asked, depth clamp on so that the
    // parts of kept casters beyond the warp's depth range stay in the map, and B reported.
    void drawWarped(const FocusedLightSpace& focused, const std::optional<glm::mat4>& warp, const DepthMapConfig& config,
                    LayeredDepthConfig layered, bool linearDepth) {
        LightSpace lightSpace = focused.light;
        if (warp) {
            // The view stays the light's (the block's light axis reads it); the warp is the whole matrix.
            lightSpace.viewProjection = *warp;
            lightSpace.projection = *warp * glm::inverse(lightSpace.view);
            lightSpace.perspective = true;
        }
        host_->reportStatistic("warped", warp ? 1.0 : 0.0);
        layered.fragmentBias = true;
        if (linearDepth) layered.linearDepthPlane = linearDepthPlane(lightSpace, focused.body, host_->bounds(DrawSet::All));
        glEnable(GL_DEPTH_CLAMP);
        draw(lightSpace, config, layered, focused.cullPlanes);
        glDisable(GL_DEPTH_CLAMP);
        map_.setFocusBody(focused.body);
        map_.reportToHost();
    }

    // One depth pass, or two for the two-layer methods (the second peeled behind the first), from
    // `lightSpace` with the casters culled to `cullPlanes`. The caller owns depth clamp and the timer.
    void draw(const LightSpace& lightSpace, DepthMapConfig config, const LayeredDepthConfig& layered,
              const std::vector<glm::vec4>& cullPlanes = {}) {
        twoLayers_ = usesTwoLayers(layered.method);
        shared::layered_depth::LayeredDepthUniforms block = layeredPass(config, layered, program_);
        uniforms_.set(block);
        uniforms_.bind();
        format_ = config.format;
        map_.ensureTexture(config.resolution, config.format);
        map_.drawDepth(lightSpace, config, cullPlanes);
        // The debug view shows the first layer (each layer's allocation registers itself; a frame
        // after a two-layer one must not show a stale layer). resolve() shows its map instead.
        host_->registerDebugImage("shadow map", map_.texture(), DebugImageKind::Depth);
        if (!twoLayers_) return;
        second_.ensureTexture(config.resolution, config.format);
        glBindTextureUnit(shared::layered_depth::kFirstDepthUnit, map_.texture());
        glBindSampler(shared::layered_depth::kFirstDepthUnit, host_->sampler(SamplerKind::Nearest));
        block.uPeel = 1;
        uniforms_.set(block);
        second_.drawDepth(lightSpace, config, cullPlanes);
        host_->registerDebugImage("shadow map", map_.texture(), DebugImageKind::Depth);
    }

    // The map with `sampling` for the comparison, the raw layers (the first again where there is
    // no second: never read then) and the block.
    void bindMainPass(SamplerKind sampling) const {
        map_.bindMainPass(sampling);
        uniforms_.bind();
        const GLuint nearest = host_->sampler(SamplerKind::Nearest);
        glBindTextureUnit(shared::layered_depth::kFirstDepthUnit, map_.texture());
        glBindSampler(shared::layered_depth::kFirstDepthUnit, nearest);
        glBindTextureUnit(shared::layered_depth::kSecondDepthUnit, twoLayers_ ? second_.texture() : map_.texture());
        glBindSampler(shared::layered_depth::kSecondDepthUnit, nearest);
    }

    // The path of the techniques that read a plain depth map (kit::LayeredDepthMaps: the filtering
    // techniques and the raw-depth ones; create() with `resolvable`): after draw() with a
    // two-layer method, both layers resolved into one more map of depths, the surface
    // eq. 5.1 tests against: z1 + min((z2 - z1) / 2, z_offset) (midpoint) or z2 (second depth), in
    // the first layer's light space. A comparison sampler, a gather, depth-range mips or a blocker
    // search on that map then read the biased surface as they read any depth map: every tap of a
    // kernel gets the two-layer test with no change to the technique's GLSL. One full-screen pass
    // writing depth (gl_FragDepth, depth test always); nothing without two layers.
    void resolve() {
        if (!twoLayers_) return;
        GpuPass pass(*host_, "two-layer resolve");
        resolved_.ensureTexture(map_.resolution(), format_);
        resolved_.adoptLightSpace(map_.lightSpace());
        uniforms_.bind();
        const GLuint nearest = host_->sampler(SamplerKind::Nearest);
        glBindTextureUnit(shared::layered_depth::kFirstDepthUnit, map_.texture());
        glBindSampler(shared::layered_depth::kFirstDepthUnit, nearest);
        glBindTextureUnit(shared::layered_depth::kSecondDepthUnit, second_.texture());
        glBindSampler(shared::layered_depth::kSecondDepthUnit, nearest);
        glBindFramebuffer(GL_FRAMEBUFFER, resolved_.framebuffer());
        glViewport(0, 0, map_.resolution(), map_.resolution());
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);   // depth writes need the test on; every texel is written
        glDepthFunc(GL_ALWAYS);
        glDepthMask(GL_TRUE);
        resolveProgram_.use();
        host_->drawFullscreenTriangle();
        glDepthFunc(GL_LESS);      // the host's default (Renderer::resetPipelineState)
        host_->registerDebugImage("shadow map", resolved_.texture(), DebugImageKind::Depth);
    }

    // The map a comparison reads after resolve(): the resolved one under a two-layer method, else
    // the first layer (the only one).
    const DepthMap& compareMap() const { return twoLayers_ ? resolved_ : map_; }

    DepthMap& map() { return map_; }

private:
    IHost* host_ = nullptr;
    DepthMap map_, second_;
    DepthMap resolved_;         // resolve()'s target (created only when resolvable)
    Program program_;
    Program resolveProgram_;    // fullscreen.vert + layered_depth_resolve.frag
    GLenum format_ = GL_DEPTH_COMPONENT32F;
    UniformBlock<shared::layered_depth::LayeredDepthUniforms> uniforms_;
    bool twoLayers_ = false;
};

} // namespace shadowlab::kit
