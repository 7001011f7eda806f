// A point light's warped maps, one per cube face (seed 002 sec. 8.2.4 / 9.2.3: a point light as up
// to six spot-like frusta, each warped as a spot light is; Kozlov's cube of sec. 7.2 likewise splits
// the light's view). For each face of the light's cube (90 degrees, kit::CubeDepthMap's faces, a
// little wider: kFacePad) the part of the view in it, V n S n F, and its focus body
// B_f = ((V n S n F) + l) n S n F (eq. 4.2 with the face as L, the view clipped to the face first:
// a visible point in the face and its segment to the light both lie in F, so no caster of a point
// the face serves is lost, and B_f is smaller than B n F); a face that sees no visible point is not
// drawn. The technique gives each face's matrix (a warp, or none: the face's uniform map focused on
// B_f), and kit::WarpedFaceMaps draws the faces into one depth atlas with kit::LayeredDepthMap's
// depth pass (fragment-stage bias, linear depth per face, both layers of the two-layer biases),
// reports them to the host and binds them for shaders/warped_faces.glsl.
//
// Why an atlas (3 x 2 tiles of resolution^2) rather than a 2D array: the depth pass, the peel of a
// second layer (it fetches the first layer at gl_FragCoord, which in a tile's viewport is the
// atlas texel) and the main pass's 2D comparison sampler are kit::LayeredDepthMap's unchanged, and
// the `shadow map` debug image shows all six faces at once. The cost: the lookup clamps its
// coordinates half a texel inside the tile (an array's layers clamp by themselves), and the atlas'
// width, 3 x resolution, must fit GL_MAX_TEXTURE_SIZE (the face resolution is lowered otherwise).
// Seams: the lookup picks the face by (P - light)'s major axis, every face's frustum is padded by
// kFacePad, so the face picked holds P's casters and the filter's texels beyond the seam.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <shadowlab/kit/cube_depth_map.h>
#include <shadowlab/kit/layered_depth.h>
#include <shadowlab/kit/warped_faces_shared.h>

namespace shadowlab::kit {

// A face's half-width, as a tangent, beyond the cube's 1 (0.57 degrees): a few warped texels of
// the neighbouring face's side at any resolution the parameter allows.
inline constexpr float kFacePad = 0.02f;

struct CubeFaceFocus {
    int face = 0;             // GL's order: +x, -x, +y, -y, +z, -z
    LightSpace light;         // the face's padded 90-degree perspective
    ConvexBody visible;       // V n S n F: the view's part in the face (sec. 9.2.3's LVS)
    ConvexBody body;          // B_f; empty when the face sees no visible point
};

// The face's padded perspective around the light (cubeFaceView's frame, the cube's depth range).
inline LightSpace cubeFaceLightSpace(glm::vec3 position, int face, const Bounds& scene, float pad = kFacePad) {
    const glm::vec2 range = cubeDepthRange(position, scene);
    LightSpace light;
    light.view = cubeFaceView(position, face);
    light.projection = glm::perspective(2.0f * std::atan(1.0f + pad), 1.0f, range.x, range.y);
    light.viewProjection = light.projection * light.view;
    light.nearPlane = range.x;
    light.farPlane = range.y;
    light.perspective = true;
    light.worldSizeAtUnitDepth = glm::vec2(2.0f * (1.0f + pad));
    return light;
}

// V n S n F: the part of a view body (the camera's frustum, or sec. 9.2.5's virtual one) inside
// the scene and the face `light`.
inline ConvexBody faceVisibleBody(ConvexBody view, const Bounds& scene, const LightSpace& light) {
    clip(view, scene);
    clip(view, frustumBody(glm::inverse(light.viewProjection)));
    return view;
}

// B_f of a view body in the face `light`.
inline ConvexBody faceFocusBody(const ConvexBody& view, const LightInfo& lightInfo, const Bounds& scene, const LightSpace& light) {
    const ConvexBody visible = faceVisibleBody(view, scene, light);
    return visible.empty() ? visible : focusBody(visible, lightInfo, scene, light);
}

// The six faces' bodies for the camera's view (pure maths: tests/test_lispsm_faces.cpp).
inline std::array<CubeFaceFocus, 6> cubeFaceFocus(const CameraInfo& camera, const LightInfo& light, const Bounds& scene,
                                                  float pad = kFacePad) {
    std::array<CubeFaceFocus, 6> faces;
    for (int i = 0; i < 6; ++i) {
        CubeFaceFocus& f = faces[size_t(i)];
        f.face = i;
        f.light = cubeFaceLightSpace(light.position, i, scene, pad);
        f.visible = faceVisibleBody(frustumBody(camera.inverseViewProjection), scene, f.light);
        if (!f.visible.empty()) f.body = focusBody(f.visible, light, scene, f.light);
    }
    return faces;
}

// One face as drawn: its map's light space (the warp as the whole matrix, or the face cropped to
// B_f), the casters' cull planes (B_f's) and B_f.
struct FaceMap {
    int face = 0;
    LightSpace light;
    glm::mat4 faceMatrix{1.0f};   // the face's own perspective (its w > 0: the light's side)
    std::vector<glm::vec4> cullPlanes;
    ConvexBody body;
    bool warped = false;
};

// The faces that see a visible point, each with `warp`'s matrix where it gives one, else the face
// focused on B_f (snapped to texels with `snap`, seed 000 sec. 2.2.5).
inline std::vector<FaceMap> faceMaps(const std::array<CubeFaceFocus, 6>& faces,
                                     const std::function<std::optional<glm::mat4>(const CubeFaceFocus&)>& warp,
                                     const Bounds& scene, bool snap, int resolution) {
    std::vector<FaceMap> maps;
    const float margin = 1e-4f * std::max(glm::length(scene.max - scene.min), 1.0f);
    for (const CubeFaceFocus& f : faces) {
        if (f.body.empty()) continue;
        FaceMap map{.face = f.face, .light = f.light, .faceMatrix = f.light.viewProjection,
                    .cullPlanes = inwardPlanes(f.body, margin), .body = f.body};
        if (const std::optional<glm::mat4> w = warp(f)) {
            map.light.viewProjection = *w;
            map.light.projection = *w * glm::inverse(map.light.view);
            map.warped = true;
        } else {
            CropWindow window = cropWindow(f.light.viewProjection, f.body.vertices());
            if (snap) window = snapToTexels(window, resolution);
            map.light = cropLightSpace(f.light, window);
        }
        maps.push_back(std::move(map));
    }
    return maps;
}

class WarpedFaceMaps {
public:
    // The program and the (inactive) block; the atlas and the faces' blocks come with the first
    // point light, so a technique that never meets one holds nothing more.
    bool create(IHost& host, std::string& error) {
        host_ = &host;
        uniforms_.create(host, "warped faces");
        uniforms_.set(faces_);
        GLint largest = 16384;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
        largestTexture_ = int(largest);
        return program_.build(host, {.vertexFile = "warped_face_depth.vert", .fragmentFile = "layered_depth.frag"}, error);
    }

    // This frame is not a point light's: the main pass reads the single map.
    void deactivate() {
        faces_.uFaceInfo.x = 0;
        uniforms_.update(faces_);
    }

    // The faces `maps` into the atlas (one or two layers as `layered` says), depth clamp on and the
    // bias in the fragment stage as LayeredDepthMap::drawWarped's; reported to the host with B_f.
    void draw(const std::vector<FaceMap>& maps, DepthMapConfig config, LayeredDepthConfig layered, bool linearDepth,
              const Bounds& scene) {
        config.resolution = faceResolution(config.resolution);
        twoLayers_ = usesTwoLayers(layered.method);
        ensure(config.resolution, config.format);
        layered.fragmentBias = true;
        layered.linearDepthPlane = glm::vec4(0.0f);   // the planes are per face (linearDepth)
        if (!linearDepth) layered.linearDepthPlane.reset();
        DepthMapConfig pass = config;
        const shared::layered_depth::LayeredDepthUniforms base = layeredPass(pass, layered, program_);
        shared::warped_faces::WarpedFacesUniforms u{};
        std::array<shared::layered_depth::LayeredDepthUniforms, 6> blocks{};
        for (const FaceMap& m : maps) {
            const size_t i = size_t(m.face);
            u.uFaceMatrix[i] = m.light.viewProjection;
            u.uFaceTile[i] = tile(m.face);
            u.uFaceInfo.y |= 1 << m.face;
            blocks[i] = base;
            if (linearDepth) u.uFaceLinearPlane[i] = blocks[i].uLinearDepthPlane = linearDepthPlane(m.light, m.body, scene);
            shared::depth_map::DepthMapUniforms depth{};
            depth.uShadowMatrix = m.light.viewProjection;
            depthBlocks_[i].update(depth);
            const auto wRow = [](const glm::mat4& m) { return glm::vec4(m[0][3], m[1][3], m[2][3], m[3][3]); };
            shared::warped_faces::WarpedFacePassUniforms clipping{};
            clipping.uFaceClipPlanes[0] = wRow(m.light.viewProjection);
            clipping.uFaceClipPlanes[1] = wRow(m.faceMatrix);
            passBlocks_[i].update(clipping);
        }
        u.uFaceLight = glm::vec4(lightPosition_, 0.5f / float(resolution_));
        u.uFaceInfo.x = 1;
        glEnable(GL_DEPTH_CLAMP);
        drawLayer(first_, maps, pass, blocks, false);
        if (twoLayers_) {
            glBindTextureUnit(shared::layered_depth::kFirstDepthUnit, first_.texture);
            glBindSampler(shared::layered_depth::kFirstDepthUnit, host_->sampler(SamplerKind::Nearest));
            drawLayer(second_, maps, pass, blocks, true);
        }
        glDisable(GL_DEPTH_CLAMP);
        faces_ = u;
        uniforms_.set(faces_);
        layeredUniforms_[6].set(base);
        report(maps);
    }

    // Where the next draw()'s faces meet: the light's position (the lookup's major axis).
    void setLight(glm::vec3 position) { lightPosition_ = position; }

    // The atlas on the depth map's unit with `sampling`, the raw layers on units 12-13, the blocks.
    void bindMainPass(SamplerKind sampling) const {
        uniforms_.bind();
        if (!first_.texture) return;
        glBindTextureUnit(shared::depth_map::kDepthMapUnit, first_.texture);
        glBindSampler(shared::depth_map::kDepthMapUnit, host_->sampler(sampling));
        const GLuint nearest = host_->sampler(SamplerKind::Nearest);
        glBindTextureUnit(shared::layered_depth::kFirstDepthUnit, first_.texture);
        glBindSampler(shared::layered_depth::kFirstDepthUnit, nearest);
        glBindTextureUnit(shared::layered_depth::kSecondDepthUnit, twoLayers_ ? second_.texture : first_.texture);
        glBindSampler(shared::layered_depth::kSecondDepthUnit, nearest);
        layeredUniforms_[6].bind();
    }

    void bindInactive() const { uniforms_.bind(); }

    // The face resolution the atlas allows (3 faces across must fit the largest texture).
    int faceResolution(int requested) const { return std::max(1, std::min(requested, largestTexture_ / 3)); }

private:
    struct Atlas {
        Texture texture;
        Framebuffer framebuffer;
    };

    static glm::vec4 tile(int face) { return {float(face % 3) / 3.0f, float(face / 3) / 2.0f, 1.0f / 3.0f, 0.5f}; }

    // (Re)allocates the atlas when resolution or format change, never per frame; the second layer's
    // only while a two-layer method asks for it.
    void ensure(int resolution, GLenum format) {
        if (!first_.framebuffer) {
            for (auto& block : depthBlocks_) block.create(*host_, "warped face");
            for (auto& block : passBlocks_) block.create(*host_, "warped face clipping");
            for (auto& block : layeredUniforms_) block.create(*host_, "warped face layers");
            first_.framebuffer = makeFramebuffer(*host_, "warped faces");
            second_.framebuffer = makeFramebuffer(*host_, "warped faces, second layer");
        }
        if (!first_.texture || resolution != resolution_ || format != format_) {
            resolution_ = resolution;
            format_ = format;
            allocate(first_, "warped faces");
            second_.texture = Texture();   // reallocated below when asked for
        }
        if (twoLayers_ && !second_.texture) allocate(second_, "warped faces, second layer");
    }

    void allocate(Atlas& atlas, const char* label) {
        atlas.texture = makeTexture(*host_, {.target = GL_TEXTURE_2D, .internalFormat = format_, .width = 3 * resolution_,
                                             .height = 2 * resolution_, .label = label});
        attachDepthTarget(*host_, atlas.framebuffer, atlas.texture, label);
    }

    // One layer of every face: the atlas cleared, each face in its tile (viewport and scissor),
    // its casters culled to B_f. `peel`: the second layer, behind the first (unit 12).
    void drawLayer(const Atlas& atlas, const std::vector<FaceMap>& maps, const DepthMapConfig& config,
                   std::array<shared::layered_depth::LayeredDepthUniforms, 6>& blocks, bool peel) {
        glBindFramebuffer(GL_FRAMEBUFFER, atlas.framebuffer);
        glDisable(GL_SCISSOR_TEST);
        glViewport(0, 0, 3 * resolution_, 2 * resolution_);
        glDepthMask(GL_TRUE);
        glClear(GL_DEPTH_BUFFER_BIT);
        glDisable(GL_POLYGON_OFFSET_FILL);
        applyCull(config.cull);
        glEnable(GL_SCISSOR_TEST);
        glEnable(GL_CLIP_DISTANCE0);
        glEnable(GL_CLIP_DISTANCE1);
        for (const FaceMap& m : maps) {
            const size_t i = size_t(m.face);
            blocks[i].uPeel = peel ? 1 : 0;
            layeredUniforms_[i].set(blocks[i]);
            depthBlocks_[i].bind();
            passBlocks_[i].bind();
            const int x = (m.face % 3) * resolution_, y = (m.face / 3) * resolution_;
            glViewport(x, y, resolution_, resolution_);
            glScissor(x, y, resolution_, resolution_);
            host_->drawScene(culledDraw(DrawSet::OpaqueCasters, m.cullPlanes), program_.use());
        }
        glDisable(GL_CLIP_DISTANCE0);
        glDisable(GL_CLIP_DISTANCE1);
        glDisable(GL_SCISSOR_TEST);
        glDisable(GL_CULL_FACE);
    }

    // The drawn faces to the host (their matrices, sizes and B_f), the atlas as the `shadow map`
    // image, and how many faces were drawn and warped.
    void report(const std::vector<FaceMap>& maps) {
        static const char* kLabels[6] = {"+x face", "-x face", "+y face", "-y face", "+z face", "-z face"};
        std::vector<std::vector<glm::vec3>> edges;
        std::vector<ShadowMapInfo> infos;
        int warped = 0;
        for (const FaceMap& m : maps) edges.push_back(bodyEdges(m.body));
        for (size_t k = 0; k < maps.size(); ++k) {
            ShadowMapInfo info;
            info.worldToClip = maps[k].light.viewProjection;
            info.size = glm::ivec2(resolution_);
            info.layer = uint32_t(maps[k].face);
            info.label = kLabels[maps[k].face];
            info.focusBodyEdges = edges[k].data();
            info.focusBodyEdgeCount = uint32_t(edges[k].size() / 2);
            infos.push_back(info);
            warped += maps[k].warped ? 1 : 0;
        }
        reportShadowMaps(*host_, infos.data(), uint32_t(infos.size()));
        host_->reportStatistic("faces", double(maps.size()));
        host_->reportStatistic("warped", maps.empty() ? 0.0 : double(warped) / double(maps.size()));
        host_->registerDebugImage("shadow map", first_.texture, DebugImageKind::Depth);
    }

    IHost* host_ = nullptr;
    Program program_;
    Atlas first_, second_;
    std::array<UniformBlock<shared::depth_map::DepthMapUniforms>, 6> depthBlocks_;
    std::array<UniformBlock<shared::warped_faces::WarpedFacePassUniforms>, 6> passBlocks_;
    std::array<UniformBlock<shared::layered_depth::LayeredDepthUniforms>, 7> layeredUniforms_;   // 6: the main pass's
    shared::warped_faces::WarpedFacesUniforms faces_{};   // the block's last values
    UniformBlock<shared::warped_faces::WarpedFacesUniforms> uniforms_;
    int largestTexture_ = 16384;
    glm::vec3 lightPosition_{0.0f};
    int resolution_ = 0;
    GLenum format_ = 0;
    bool twoLayers_ = false;
};

} // namespace shadowlab::kit
