// Texture readbacks, at once or through a pixel-pack buffer and a fence (texture_readback.h).
#include "render/texture_readback.h"

#include <cstring>
#include <string>

#include "util/log.h"

namespace shadowlab {

void ImmediateReader::read(GLuint texture, GLenum format, GLenum type, size_t bytes, void* into) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(texture, 0, format, type, GLsizei(bytes), into);
}

PixelBufferReadback::~PixelBufferReadback() { reset(); }

void PixelBufferReadback::begin(size_t bytes) {
    reset();
    if (bytes > capacity_) {
        // Grown only when a readback needs more (a larger view or more layers), not per frame.
        GLuint name = 0;
        glCreateBuffers(1, &name);
        glNamedBufferData(name, GLsizeiptr(bytes), nullptr, GL_STREAM_READ);
        buffer_.reset(name);
        capacity_ = bytes;
    }
    used_ = 0;
}

void PixelBufferReadback::read(GLuint texture, GLenum format, GLenum type, size_t bytes, void* into) {
    if (used_ + bytes > capacity_) {
        logError("pixel-buffer readback: " + std::to_string(used_ + bytes) + " bytes asked, " + std::to_string(capacity_) +
                 " reserved (read dropped)");
        return;
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    // With a pack buffer bound the pointer is an offset into it: the copy stays on the GPU's queue.
    glGetTextureImage(texture, 0, format, type, GLsizei(bytes), reinterpret_cast<void*>(used_));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    reads_.push_back({used_, bytes, into});
    // 16-byte steps keep every float image aligned for the copies.
    used_ += (bytes + 15) & ~size_t(15);
}

void PixelBufferReadback::end() {
    if (fence_) glDeleteSync(fence_);
    fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    glFlush();   // submits the reads and the fence; no wait
}

bool PixelBufferReadback::ready() {
    if (!fence_) return false;
    const GLenum status = glClientWaitSync(fence_, 0, 0);
    return status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED;
}

bool PixelBufferReadback::map() {
    if (mapped_) return true;
    if (used_ == 0) return false;
    mapped_ = static_cast<const uint8_t*>(glMapNamedBufferRange(buffer_.get(), 0, GLsizeiptr(used_), GL_MAP_READ_BIT));
    if (!mapped_) logError("pixel-buffer readback: the buffer could not be mapped");
    return mapped_ != nullptr;
}

void PixelBufferReadback::deliver() const {
    if (!mapped_) return;
    for (const Read& read : reads_) std::memcpy(read.into, mapped_ + read.offset, read.bytes);
}

void PixelBufferReadback::reset() {
    if (mapped_) {
        glUnmapNamedBuffer(buffer_.get());
        mapped_ = nullptr;
    }
    if (fence_) {
        glDeleteSync(fence_);
        fence_ = nullptr;
    }
    reads_.clear();
    used_ = 0;
}

} // namespace shadowlab
