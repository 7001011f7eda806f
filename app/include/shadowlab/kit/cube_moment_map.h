// A point light's moment map as a cube: the filterable shadow maps' point-light path (vsm, esm,
// evsm, msm; the 2D map is kit/moment_map.h). The six faces' distances are rendered in one pass
// as the kit's cube depth map renders them (shaders/cube_depth.geom and cube_depth.frag, without
// bias) into a 2D array of six depth layers, stored as d = distance / far in [0, 1]: linear, the
// same in every direction, so a filter window's statistics mean what they mean for the 2D map's
// linear depth. The moments are then derived and blurred in compute, face by face
// (shaders/separable_blur.comp with MOMENT_CUBE): along x from the depth layers into a scratch
// array, along y from it into the cube moment map, whose mipmaps (when on) are built per face.
// The main pass looks the cube up by the direction from the light with seamless filtering
// (shaders/moment_shadows.glsl).
//
// Seams: the blur does not cross them. Each face is blurred as an image of its own, texels beyond
// its edge repeating the edge (as the 2D map's border), so within half a kernel of a seam the
// window is cut short on the far side: the penumbra is a little narrower and sharper there (a
// shadow edge crossing the seam shows a slight kink). Only the final bilinear (and trilinear)
// lookup filters across the seam (GL_TEXTURE_CUBE_MAP_SEAMLESS), which hides the step between the
// faces' values. Filtering across seams would need each face's apron read from its neighbours
// with their orientations (or a cube-space blur by direction): left out.
//
// Always the compute path, whatever `blur` says (a cube colour target would need a layered
// moment pass); moments needing screen-space derivatives (vsm's eq. 3.16) do not apply here.
// Depth range: far is the farthest the casters reach from the light plus half their extent of room
// (if any receiver lies there), as the 2D map's; near is the light itself (0).
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include <algorithm>
#include <bit>
#include <string>

#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/moment_map_config.h"
#include "shadowlab/kit/moment_map_shared.h"

namespace shadowlab::kit {

using shared::moment_map::BlurUniforms;
using shared::moment_map::kBlurDestinationImageUnit;
using shared::moment_map::kBlurSourceUnit;
using shared::moment_map::kCubeMomentMapUnit;

// The cube moment map's far distance (see the top of this file): every caster nearer, receivers
// beyond it clamped to d = 1, where nothing can occlude them.
inline float cubeMomentFar(glm::vec3 lightPosition, const Bounds& casters, const Bounds& all) {
    auto farthest = [&](const Bounds& b) {
        glm::vec3 corners[8];
        boundsCorners(b, corners);
        float d = 0.0f;
        for (const glm::vec3& c : corners) d = std::max(d, glm::distance(c, lightPosition));
        return d;
    };
    const glm::vec3 closest = glm::clamp(lightPosition, casters.min, casters.max);
    const float casterNear = glm::distance(closest, lightPosition);   // 0 with the light among them
    const float casterFar = farthest(casters);
    const float extent = std::max(casterFar - casterNear, 1e-3f);
    const float room = std::min(casterFar + 0.5f * extent, std::max(farthest(all), casterFar));
    return std::max(room + 0.01f * extent, 1e-2f);
}

class CubeMomentMap {
public:
    // `momentFile`: the technique's moment file, built here as the first (x) compute pass.
    bool create(IHost& host, const char* momentFile, std::string& error) {
        host_ = &host;
        if (!depthProgram_.build(host,
                                 {.vertexFile = "world_position.vert", .geometryFile = "cube_depth.geom",
                                  .fragmentFile = "cube_depth.frag"},
                                 error))
            return false;
        if (!blurX_.build(host, {.computeFile = momentFile, .defines = "MOMENT_PASS_COMPUTE 1;MOMENT_BLUR_AXIS 0;MOMENT_CUBE 1"},
                          error))
            return false;
        if (!blurY_.build(host, {.computeFile = "separable_blur.comp", .defines = "MOMENT_BLUR_AXIS 1;MOMENT_CUBE 1"}, error))
            return false;
        framebuffer_ = makeFramebuffer(host, "cube moment map (depth)");
        return true;
    }

    // Distances, moments and blur (x, then y), mipmaps. The technique's own block (binding 2)
    // must be bound already: the x pass derives the moments with it.
    void render(const FrameContext& frame, const MomentMapConfig& config) {
        ensureTextures(config);
        const float far = cubeMomentFar(frame.light.position, host_->bounds(DrawSet::Casters), host_->bounds(DrawSet::All));
        faces_ = cubeFaceViewProjections(frame.light.position, far * 1e-3f, far);
        CubeDepthMapUniforms u{};
        for (int i = 0; i < 6; ++i) u.uCubeFaceMatrix[i] = faces_[size_t(i)];
        u.uCubeLight = glm::vec4(frame.light.position, far);
        u.uCubeBias = {0.0f, 0.0f, float(resolution_), 0.0f};   // moments need no depth offset
        cubeUniforms_.set(u);
        reportCubeFaces(*host_, faces_, resolution_);
        {
            GpuPass pass(*host_, "shadow map");
            glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
            glViewport(0, 0, resolution_, resolution_);
            const float farDepth = 1.0f;
            glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &farDepth);
            // No face culling (the 2D moment map's choice): thin and open casters need both sides.
            host_->drawScene(DrawSet::OpaqueCasters, depthProgram_.use());
        }
        blur(config);
        if (config.mipmaps) {
            GpuPass pass(*host_, "mipmaps");
            glGenerateTextureMipmap(moments_);
        }
    }

    // Main pass: the cube's block (light position, far) and the moment cube, filtered across seams.
    void bindMainPass() const {
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        cubeUniforms_.bind();
        glBindTextureUnit(kCubeMomentMapUnit, moments_);
        glBindSampler(kCubeMomentMapUnit, host_->sampler(mipmaps_ ? SamplerKind::LinearMipmap : SamplerKind::Linear));
    }

    GLuint texture() const { return moments_; }
    int resolution() const { return resolution_; }

private:
    BlurUniforms blurValues(const MomentMapConfig& config, glm::vec2 step, int source) const {
        return {{}, {step, 0.0f, 0.0f}, config.kernelSize, config.gaussian ? 1 : 0, source, format_ == GL_RGBA16 ? 1 : 0};
    }

    // Six faces per dispatch (z = face). x: depth layers -> moments -> scratch layers; y: scratch
    // -> cube faces (kernel 1: both passes only copy). Barriers as kit/moment_map.h's computeBlur.
    void blur(const MomentMapConfig& config) {
        GpuPass pass(*host_, config.kernelSize > 1 ? "blur" : "moments");
        blurUniforms_[0].set(blurValues(config, {1.0f, 0.0f}, 1));
        glBindTextureUnit(kBlurSourceUnit, depth_);
        glBindImageTexture(kBlurDestinationImageUnit, scratch_, 0, GL_TRUE, 0, GL_WRITE_ONLY, format_);
        blurX_.use();
        glDispatchCompute(GLuint(resolution_ + 255) / 256u, GLuint(resolution_), 6);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        blurUniforms_[1].set(blurValues(config, {0.0f, 1.0f}, 0));
        glBindTextureUnit(kBlurSourceUnit, scratch_);
        glBindImageTexture(kBlurDestinationImageUnit, moments_, 0, GL_TRUE, 0, GL_WRITE_ONLY, format_);
        blurY_.use();
        glDispatchCompute(GLuint(resolution_ + 3) / 4u, GLuint(resolution_ + 63) / 64u, 6);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                        GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(kBlurSourceUnit, 0);
        glBindImageTexture(kBlurDestinationImageUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    }

    // (Re)allocates when resolution, format or mipmapping change: never per frame. The blocks come
    // with the first cube, so a technique that never meets a point light holds nothing of this path.
    void ensureTextures(const MomentMapConfig& config) {
        if (moments_ && config.resolution == resolution_ && config.format == format_ && config.mipmaps == mipmaps_) return;
        if (!moments_) {
            cubeUniforms_.create(*host_, "cube moment map uniforms");
            blurUniforms_[0].create(*host_, "cube moment blur uniforms (x)");
            blurUniforms_[1].create(*host_, "cube moment blur uniforms (y)");
        }
        resolution_ = config.resolution;
        format_ = config.format;
        mipmaps_ = config.mipmaps;
        const int levels = mipmaps_ ? std::bit_width(unsigned(resolution_)) : 1;
        moments_ = makeTexture(*host_, {.target = GL_TEXTURE_CUBE_MAP, .internalFormat = format_, .width = resolution_,
                                        .height = resolution_, .levels = levels, .label = "cube moment map"});
        glTextureParameteri(moments_, GL_TEXTURE_MIN_FILTER, mipmaps_ ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        glTextureParameteri(moments_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        scratch_ = makeTexture(*host_, {.target = GL_TEXTURE_2D_ARRAY, .internalFormat = format_, .width = resolution_,
                                        .height = resolution_, .depth = 6, .label = "cube blur scratch (six layers)"});
        glTextureParameteri(scratch_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(scratch_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        depth_ = makeTexture(*host_, {.target = GL_TEXTURE_2D_ARRAY, .internalFormat = GL_DEPTH_COMPONENT32F,
                                      .width = resolution_, .height = resolution_, .depth = 6,
                                      .label = "cube moment map depth (six layers)"});
        attachDepthTarget(*host_, framebuffer_, depth_, "cube moment map (depth)");   // layered: gl_Layer picks the face
    }

    IHost* host_ = nullptr;
    Program depthProgram_, blurX_, blurY_;
    Framebuffer framebuffer_;
    Texture moments_, scratch_, depth_;
    UniformBlock<CubeDepthMapUniforms> cubeUniforms_;
    UniformBlock<BlurUniforms> blurUniforms_[2];
    int resolution_ = 0;
    GLenum format_ = 0;
    bool mipmaps_ = false;
    std::array<glm::mat4, 6> faces_{};
};

} // namespace shadowlab::kit
