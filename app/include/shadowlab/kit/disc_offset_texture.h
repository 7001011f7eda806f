// GL side of jittered_disk.h: the m x m x ceil(n^2/2) RGBA16_SNORM 3D texture of jittered disc sets,
// built on the CPU and uploaded once, again only when n or m change (adaptive-pcf, pcss). The GLSL
// side is shaders/disc_sampling.glsl.
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/jittered_disk.h"

namespace shadowlab::jittered_disk {

class DiscOffsetTexture {
public:
    // (Re)builds the texture when n or m changed; `label` names it in the memory table. Different
    // seeds give independent sets (pcss: search and filter).
    void ensure(IHost& host, int n, int m, const char* label, uint64_t seed = 1) {
        if (texture_ && n == n_ && m == m_) return;
        n_ = n;
        m_ = m;
        const TextureSize size = offsetTextureSize(n, m);
        texture_ = kit::makeTexture(host, {.target = GL_TEXTURE_3D, .internalFormat = GL_RGBA16_SNORM, .width = size.width,
                                           .height = size.height, .depth = size.depth, .label = label});
        // Unit-disc offsets in 16-bit signed normalised texels (steps of 1/32767 of the radius):
        // half the bytes of RGBA32F for the fetch made every two taps of adaptive-pcf and pcss.
        // Measured on forest on an H200 with the depth pre-pass, adaptive-pcf's shadow term:
        // 3.21 ms with RGBA32F, 2.93 ms with RGBA16_SNORM, 2.93 ms with RGBA8_SNORM (no gain for
        // 1/127 steps, so the finer format stays; docs/results/h200-2026-12-02-issue10).
        const std::vector<glm::vec4> texels = makeOffsetTexture(n, m, seed);
        glTextureSubImage3D(texture_, 0, 0, 0, 0, size.width, size.height, size.depth, GL_RGBA, GL_FLOAT, texels.data());
        // Read with texelFetch only; the parameters keep the texture complete and never filter.
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    }

    GLuint texture() const { return texture_; }
    int n() const { return n_; }

private:
    kit::Texture texture_;
    int n_ = 0, m_ = 0;
};

} // namespace shadowlab::jittered_disk

namespace shadowlab::kit {

// The `sets` parameter of the techniques that tile the screen with these sets (adaptive-pcf, pcss).
constexpr ParamDesc discSetsParam() {
    return {"sets", "sets m", ParamType::Int, 1, 32, 16, "",
            "m x m different sample sets tiled over the screen (pixel mod m). 1 brings back the banding of a "
            "single set; below about 14 the noise repeats visibly in motion; memory grows with m^2 (m x m x "
            "n^2/2 texels).",
            nullptr};
}

} // namespace shadowlab::kit
