// Render targets from the light for techniques whose passes do more than kit::DepthMap's one depth
// pass (stochastic-sm, cssm2, translucent-shadows): a framebuffer with a depth texture (its own
// or another target's, to depth-test against without writing) and optionally one colour texture,
// single-sample or multisample, reallocated only when the resolution, a format or the sample count
// changes. Also the kit depth map's block for a light space, which shaders/depth_only.vert and
// translucent_caster.vert read (uShadowMatrix) and the main pass's light_space.glsl /
// light_depth.glsl helpers take.
#pragma once

#include <string>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/depth_map_shared.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/shadow_map_report.h"

namespace shadowlab::kit {

using shared::depth_map::DepthMapUniforms;
using shared::depth_map::kDepthMapUnit;

// The depth map block (depth_map_shared.h) of `lightSpace` for a map of `resolution` texels.
inline shared::depth_map::DepthMapUniforms lightSpaceUniforms(const LightSpace& lightSpace, int resolution) {
    shared::depth_map::DepthMapUniforms u{};
    u.uShadowMatrix = lightSpace.viewProjection;
    u.uLightDepth = {lightSpace.nearPlane, lightSpace.farPlane, lightSpace.perspective ? 1.0f : 0.0f, float(resolution)};
    u.uLightWorldSize4 = {lightSpace.worldSizeAtUnitDepth, 0.0f, 0.0f};
    // The light camera looks down its view space's -z: that axis in world space.
    const glm::mat4& view = lightSpace.view;
    u.uLightAxis4 = {-view[0][2], -view[1][2], -view[2][2], 0.0f};
    return u;
}

// Front to back from the light, by the objects' bounds centres (seed 001 sec. 4.2.1: sorted per
// mesh by its bounding box's centre): along the travel direction of a directional light, by
// distance from a spot or point light.
inline DrawRequest frontToBackFromLight(DrawSet set, const LightInfo& light) {
    DrawRequest request;
    request.set = set;
    request.order = DrawOrder::FrontToBack;
    request.orderReference = light.type == LightType::Directional ? glm::vec4(light.direction, 0.0f)
                                                                  : glm::vec4(light.position, 1.0f);
    return request;
}

struct LightTargetFormat {
    int resolution = 2048;
    GLenum depthFormat = GL_DEPTH_COMPONENT32F;   // ignored when depthFrom is set
    GLenum colourFormat = 0;                      // 0: depth only
    const class LightTarget* depthFrom = nullptr; // attach this target's depth instead of owning one
    int samples = 0;                              // > 0: GL_TEXTURE_2D_MULTISAMPLE textures of this many
                                                  // samples (a count the format supports; see GL_SAMPLES)
    bool operator==(const LightTargetFormat&) const = default;
};

class LightTarget {
public:
    void create(IHost& host, const char* label) {
        host_ = &host;
        label_ = label;
        framebuffer_ = makeFramebuffer(host, label);
    }

    // (Re)allocates when the format changed (never per frame). A target borrowing another's depth
    // must be ensured after it; it re-attaches when that texture was reallocated. True when the
    // textures are new (register debug images then).
    bool ensure(const LightTargetFormat& format) {
        const bool sameFormat = allocated_ && format == format_;
        if (!sameFormat) {
            format_ = format;
            depth_.reset();
            colour_.reset();
            if (!format.depthFrom) depth_ = texture(format.depthFormat, "depth");
            if (format.colourFormat) colour_ = texture(format.colourFormat, "colour");
            allocated_ = true;
        }
        const GLuint depth = format.depthFrom ? format.depthFrom->depth() : depth_.get();
        if (sameFormat && depth == attachedDepth_) return false;
        attachedDepth_ = depth;
        glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, attachedDepth_, 0);
        glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, colour_.get(), 0);
        const GLenum buffer = colour_ ? GL_COLOR_ATTACHMENT0 : GL_NONE;
        glNamedFramebufferDrawBuffer(framebuffer_, buffer);
        glNamedFramebufferReadBuffer(framebuffer_, buffer);
        host_->checkFramebuffer(framebuffer_, label_);
        return true;
    }

    // Binds the framebuffer with a viewport covering the target.
    void bind() const {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, format_.resolution, format_.resolution);
    }

    GLuint depth() const { return depth_.get(); }
    GLuint colour() const { return colour_.get(); }
    int resolution() const { return format_.resolution; }

private:
    Texture texture(GLenum format, const char* what) {
        const std::string label = std::string(label_) + " " + what;
        const bool multisample = format_.samples > 0;
        Texture texture = makeTexture(*host_, {.target = GLenum(multisample ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D),
                                               .internalFormat = format, .width = format_.resolution,
                                               .height = format_.resolution, .samples = format_.samples,
                                               .label = label.c_str()});
        // A multisample texture has no sampler state (texelFetch only): setting it is an error.
        if (multisample) return texture;
        // Complete without a sampler object; techniques bind host samplers for their lookups.
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        return texture;
    }

    IHost* host_ = nullptr;
    const char* label_ = "";
    Framebuffer framebuffer_;
    Texture depth_;
    Texture colour_;
    GLuint attachedDepth_ = 0;
    bool allocated_ = false;
    LightTargetFormat format_{.resolution = 0};
};

} // namespace shadowlab::kit
