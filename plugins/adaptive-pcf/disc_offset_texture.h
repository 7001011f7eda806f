// GL side of jittered_disk.h: the m x m x ceil(n^2/2) RGBA32F 3D texture of jittered disc sets,
// built on the CPU and uploaded once, again only when n or m change. Header-only so that pcss
// can include it by relative path ("../adaptive-pcf/disc_offset_texture.h"): plugins share C++
// only through header-only files. The GLSL side is shaders/disc_sampling.glsl.
#pragma once

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "jittered_disk.h"

namespace shadowlab::jittered_disk {

class DiscOffsetTexture {
public:
    // (Re)builds the texture when n or m changed; `label` names it in the memory table. Different
    // seeds give independent sets (pcss: search and filter).
    void ensure(IHost& host, int n, int m, const char* label, uint64_t seed = 1) {
        if (texture_ && n == n_ && m == m_) return;
        release(host);
        n_ = n;
        m_ = m;
        const TextureSize size = offsetTextureSize(n, m);
        texture_ = host.createTexture({GL_TEXTURE_3D, GL_RGBA32F, size.width, size.height, size.depth, 1, label});
        const std::vector<glm::vec4> texels = makeOffsetTexture(n, m, seed);
        glTextureSubImage3D(texture_, 0, 0, 0, 0, size.width, size.height, size.depth, GL_RGBA, GL_FLOAT, texels.data());
        // Read with texelFetch only; the parameters keep the texture complete and never filter.
        glTextureParameteri(texture_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_T, GL_REPEAT);
        glTextureParameteri(texture_, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    }

    void release(IHost& host) {
        if (texture_) host.destroyTexture(texture_);
        texture_ = 0;
        n_ = m_ = 0;
    }

    GLuint texture() const { return texture_; }
    int n() const { return n_; }

private:
    GLuint texture_ = 0;
    int n_ = 0, m_ = 0;
};

} // namespace shadowlab::jittered_disk
