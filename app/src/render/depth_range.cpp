// The depth range a shadow map holds (see depth_range.h).
#include "render/depth_range.h"

#include <algorithm>

namespace shadowlab {

glm::vec2 DepthRange::rangeOf(const std::vector<float>& texels) {
    float lo = 1.0f, hi = 0.0f;
    for (const float t : texels)
        if (t < 0.999999f && t >= 0.0f) {
            lo = std::min(lo, t);
            hi = std::max(hi, t);
        }
    if (lo > hi) return {0.0f, 1.0f};
    if (hi - lo < 1e-6f) return {lo - 0.5e-6f, hi + 0.5e-6f};   // one depth: grey rather than a divide by zero
    return {lo, hi};
}

// Size and the format to read a depth or colour texture as one float a texel (state queries:
// no wait for the GPU).
bool DepthRange::describe(GLuint texture, glm::ivec2& size, GLenum& format) const {
    GLint internal = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &size.x);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &size.y);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
    const bool depth = internal == GL_DEPTH_COMPONENT16 || internal == GL_DEPTH_COMPONENT24 || internal == GL_DEPTH_COMPONENT32 ||
                       internal == GL_DEPTH_COMPONENT32F || internal == GL_DEPTH_COMPONENT || internal == GL_DEPTH24_STENCIL8 ||
                       internal == GL_DEPTH32F_STENCIL8;
    format = depth ? GL_DEPTH_COMPONENT : GL_RED;
    return size.x > 0 && size.y > 0;
}

void DepthRange::update(GLuint texture) {
    if (pending_ && readback_.ready() && readback_.map()) {
        readback_.deliver();
        readback_.reset();
        range_ = rangeOf(texels_);
        measured_ = pending_;
        pending_ = 0;
    }
    if (pending_ || (texture == measured_ && ++frames_ < kEveryFrames)) return;
    glm::ivec2 size;
    GLenum format;
    if (!describe(texture, size, format)) return;
    frames_ = 0;
    texels_.assign(size_t(size.x) * size_t(size.y), 1.0f);
    const size_t bytes = texels_.size() * sizeof(float);
    readback_.begin(bytes);
    readback_.read(texture, format, GL_FLOAT, bytes, texels_.data());
    readback_.end();
    pending_ = texture;
}

void DepthRange::measureNow(GLuint texture) {
    glm::ivec2 size;
    GLenum format;
    if (!describe(texture, size, format)) return;
    texels_.assign(size_t(size.x) * size_t(size.y), 1.0f);
    ImmediateReader reader;
    reader.read(texture, format, GL_FLOAT, texels_.size() * sizeof(float), texels_.data());
    range_ = rangeOf(texels_);
    measured_ = texture;
}

} // namespace shadowlab
