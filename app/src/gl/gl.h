// GL access for the host: glad's 4.5 core loader and small RAII owners for GL objects the host
// creates once (never per frame).
#pragma once

#include <glad/gl.h>

#include <string>
#include <utility>

#include "shadowlab/technique.h"

namespace shadowlab {

// Owns one GL object name; Deleter is a function deleting one name.
template <void (*Deleter)(GLuint)>
class GlHandle {
public:
    GlHandle() = default;
    explicit GlHandle(GLuint name) : name_(name) {}
    ~GlHandle() { reset(); }
    GlHandle(GlHandle&& other) noexcept : name_(std::exchange(other.name_, 0)) {}
    GlHandle& operator=(GlHandle&& other) noexcept {
        if (this != &other) {
            reset();
            name_ = std::exchange(other.name_, 0);
        }
        return *this;
    }
    GlHandle(const GlHandle&) = delete;
    GlHandle& operator=(const GlHandle&) = delete;

    GLuint get() const { return name_; }
    explicit operator bool() const { return name_ != 0; }
    void reset(GLuint name = 0) {
        if (name_ != 0) Deleter(name_);
        name_ = name;
    }

private:
    GLuint name_ = 0;
};

namespace gl_delete {
inline void texture(GLuint n) { glDeleteTextures(1, &n); }
inline void buffer(GLuint n) { glDeleteBuffers(1, &n); }
inline void framebuffer(GLuint n) { glDeleteFramebuffers(1, &n); }
inline void vertexArray(GLuint n) { glDeleteVertexArrays(1, &n); }
inline void program(GLuint n) { glDeleteProgram(n); }
inline void sampler(GLuint n) { glDeleteSamplers(1, &n); }
inline void query(GLuint n) { glDeleteQueries(1, &n); }
} // namespace gl_delete

using GlTexture = GlHandle<gl_delete::texture>;
using GlBuffer = GlHandle<gl_delete::buffer>;
using GlFramebuffer = GlHandle<gl_delete::framebuffer>;
using GlVertexArray = GlHandle<gl_delete::vertexArray>;
using GlProgram = GlHandle<gl_delete::program>;
using GlSampler = GlHandle<gl_delete::sampler>;

// Loads GL through `loader`, checks for a 4.5 core context and, in debug builds (or when
// `debugOutput` is set), routes KHR_debug messages to the log. Returns false with a message.
bool initGl(GlLoader loader, bool debugOutput, std::string& error);
std::string glVersionString();   // "4.5 (Core Profile) Mesa 22.3.6 | llvmpipe (LLVM 15...)"
std::string glRendererString();
std::string framebufferStatusName(GLenum status);
// Bytes of one texel of a sized internal format (0 if unknown).
size_t bytesPerTexel(GLenum internalFormat);

} // namespace shadowlab
