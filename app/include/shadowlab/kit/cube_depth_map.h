// A point light's shadow map as a cube (omnidirectional shadow mapping, Gerasimov 2004, GPU Gems
// ch. 12): six 90-degree faces around the light, drawn in one pass (shaders/cube_depth.geom: six
// geometry-stage invocations writing gl_Layer into the layered cube attachment), each storing the
// linear distance to the light over the far distance (shaders/cube_depth.frag), so the main pass
// looks it up by direction and compares distances (shaders/cube_shadow.glsl). The plumbing of the
// point-light path of shadowmap, pcf, adaptive-pcf, pcss and csm (kit/cube_moment_map.h holds the
// moment techniques' cube); a single frustum cannot see all around a lamp (the
// host's fitLightSpace clamps a point light's map to 80 degrees either side).
// Bias: glPolygonOffset does not reach a depth written by the fragment stage, so the fragment
// stage adds the same offset (slope factor and constant units); culling as the 2D map's.
#pragma once

#include <array>
#include <string>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <shadowlab/technique.h>

#include "shadowlab/kit/cube_depth_map_shared.h"
#include "shadowlab/kit/depth_map.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/shadow_map_report.h"

namespace shadowlab::kit {

using shared::cube_depth_map::CubeDepthMapUniforms;
using shared::cube_depth_map::kCubeDepthMapUnit;

// The six faces' view-projections around `position` in GL's face order. The up vectors are the
// ones GL's cube-map addressing implies (its faces are stored with t running down), so a face
// drawn with them is the image a lookup along its directions reads.
inline glm::mat4 cubeFaceView(glm::vec3 position, int face) {
    static const glm::vec3 kForward[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    static const glm::vec3 kUp[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
    return glm::lookAt(position, position + kForward[face], kUp[face]);
}
inline std::array<glm::mat4, 6> cubeFaceViewProjections(glm::vec3 position, float nearPlane, float farPlane) {
    const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, nearPlane, farPlane);
    std::array<glm::mat4, 6> faces;
    for (int i = 0; i < 6; ++i) faces[size_t(i)] = projection * cubeFaceView(position, i);
    return faces;
}

// Far: the farthest corner of the scene's bounds from the light (every receiver is nearer);
// near: a thousandth of it (it only clips casters touching the light: depth is linear).
inline glm::vec2 cubeDepthRange(glm::vec3 lightPosition, const Bounds& scene) {
    glm::vec3 corners[8];
    boundsCorners(scene, corners);
    float farthest = 0.0f;
    for (const glm::vec3& c : corners) farthest = std::max(farthest, glm::distance(c, lightPosition));
    const float farPlane = std::max(farthest * 1.01f, 1e-2f);
    return {farPlane * 1e-3f, farPlane};
}

// The six faces to the host (SHADOWLAB_EXT_SHADOW_MAPS): each serves every view depth, a point
// picking the face its direction from the light falls in.
inline void reportCubeFaces(IHost& host, const std::array<glm::mat4, 6>& faces, int resolution) {
    static const char* kLabels[6] = {"+x face", "-x face", "+y face", "-y face", "+z face", "-z face"};
    std::array<ShadowMapInfo, 6> maps;
    for (int i = 0; i < 6; ++i) {
        maps[size_t(i)].worldToClip = faces[size_t(i)];
        maps[size_t(i)].size = glm::ivec2(resolution);
        maps[size_t(i)].layer = uint32_t(i);
        maps[size_t(i)].label = kLabels[i];
    }
    reportShadowMaps(host, maps.data(), uint32_t(maps.size()));
}

class CubeDepthMap {
public:
    bool create(IHost& host, std::string& error) {
        host_ = &host;
        if (!program_.build(host,
                            {.vertexFile = "world_position.vert", .geometryFile = "cube_depth.geom",
                             .fragmentFile = "cube_depth.frag"},
                            error))
            return false;
        framebuffer_ = makeFramebuffer(host, "cube shadow map");
        return true;
    }

    // The six faces of the frame's (point) light in one timed "shadow map" pass, reported to the host.
    void render(const FrameContext& frame, const DepthMapConfig& config) {
        ensureTexture(config.resolution, config.format);
        GpuPass pass(*host_, "shadow map");
        const glm::vec2 range = cubeDepthRange(frame.light.position, host_->bounds(DrawSet::All));
        faces_ = cubeFaceViewProjections(frame.light.position, range.x, range.y);
        CubeDepthMapUniforms u{};
        for (int i = 0; i < 6; ++i) u.uCubeFaceMatrix[i] = faces_[size_t(i)];
        u.uCubeLight = glm::vec4(frame.light.position, range.y);
        u.uCubeBias = {config.slopeBias, config.constantBias, float(resolution_), 0.0f};
        uniforms_.set(u);
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, resolution_, resolution_);
        glClear(GL_DEPTH_BUFFER_BIT);
        applyCull(config.cull);
        host_->drawScene(DrawSet::OpaqueCasters, program_.use());
        report();
    }

    // The cube with a host sampler (CompareLinear: bilinear comparison, filtered across face edges
    // with seamless cube-map filtering) and its block.
    void bindMainPass(SamplerKind sampling) const {
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        glBindTextureUnit(kCubeDepthMapUnit, texture_);
        glBindSampler(kCubeDepthMapUnit, host_->sampler(sampling));
        uniforms_.bind();
    }

    void report() const { reportCubeFaces(*host_, faces_, resolution_); }

    // (Re)allocates the cube (six faces, counted so by the host) when resolution or format change.
    // The block's buffer comes with the first cube, so a technique that never meets a point light
    // holds nothing of the cube path.
    void ensureTexture(int resolution, GLenum format = GL_DEPTH_COMPONENT32F) {
        if (texture_ && resolution == resolution_ && format == format_) return;
        if (!texture_) uniforms_.create(*host_, "cube shadow map uniforms");
        resolution_ = resolution;
        format_ = format;
        texture_ = makeTexture(*host_, {.target = GL_TEXTURE_CUBE_MAP, .internalFormat = format, .width = resolution,
                                        .height = resolution, .label = "cube shadow map"});
        attachDepthTarget(*host_, framebuffer_, texture_, "cube shadow map");   // layered: gl_Layer picks the face
    }

    GLuint texture() const { return texture_; }
    int resolution() const { return resolution_; }
    const std::array<glm::mat4, 6>& faces() const { return faces_; }

private:
    IHost* host_ = nullptr;
    Program program_;
    Framebuffer framebuffer_;
    Texture texture_;
    UniformBlock<CubeDepthMapUniforms> uniforms_;
    int resolution_ = 0;
    GLenum format_ = 0;
    std::array<glm::mat4, 6> faces_{};
};

} // namespace shadowlab::kit
