// GL start-up: loader, version check, KHR_debug routing, format sizes for memory accounting.
#include "gl/gl.h"

#include <cstring>

#include "util/log.h"

namespace shadowlab {
namespace {

void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                              const GLchar* message, const void*) {
    (void)source;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;   // buffer placement chatter
    const LogLevel level = (type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH)
                               ? LogLevel::Error
                               : LogLevel::Warning;
    logMessage(level, "GL debug (" + std::to_string(id) + "): " + message);
}

} // namespace

bool initGl(GlLoader loader, bool debugOutput, std::string& error) {
    const int version = gladLoadGL(loader);
    if (version == 0) {
        error = "could not load OpenGL entry points";
        return false;
    }
    if (GLAD_VERSION_MAJOR(version) < 4 || (GLAD_VERSION_MAJOR(version) == 4 && GLAD_VERSION_MINOR(version) < 5)) {
        error = "OpenGL 4.5 core is required, the context offers " + glVersionString();
        return false;
    }
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    if (!(profile & GL_CONTEXT_CORE_PROFILE_BIT)) {
        error = "an OpenGL core profile context is required, got " + glVersionString();
        return false;
    }
#ifndef NDEBUG
    debugOutput = true;
#endif
    if (debugOutput) {
        glEnable(GL_DEBUG_OUTPUT);
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(debugCallback, nullptr);
    }
    return true;
}

std::string glVersionString() {
    const auto* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return version ? version : "unknown";
}

std::string glRendererString() {
    const auto* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return renderer ? renderer : "unknown";
}

std::string framebufferStatusName(GLenum status) {
    switch (status) {
    case GL_FRAMEBUFFER_COMPLETE: return "complete";
    case GL_FRAMEBUFFER_UNDEFINED: return "undefined";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "incomplete attachment";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "missing attachment";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "incomplete draw buffer";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "incomplete read buffer";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "unsupported format combination";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "incomplete multisample";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "incomplete layer targets";
    default: return "status 0x" + std::to_string(status);
    }
}

size_t bytesPerTexel(GLenum internalFormat) {
    switch (internalFormat) {
    case GL_R8: case GL_R8UI: case GL_R8I: case GL_STENCIL_INDEX8: return 1;
    case GL_R16: case GL_R16F: case GL_R16_SNORM: case GL_RG8: case GL_DEPTH_COMPONENT16: case GL_R16UI: return 2;
    case GL_DEPTH_COMPONENT24: return 4;   // padded to 32 bits by every driver we know
    case GL_R32F: case GL_RG16: case GL_RG16F: case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_R32UI:
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: case GL_DEPTH_COMPONENT32: case GL_RGB10_A2:
    case GL_R11F_G11F_B10F: case GL_RG16UI: case GL_RG16_SNORM: case GL_RGBA8_SNORM:
        return 4;
    case GL_DEPTH32F_STENCIL8: return 8;   // 32-bit depth + 8-bit stencil, padded
    case GL_RG32F: case GL_RGBA16: case GL_RGBA16F: case GL_RGBA16UI: case GL_RGBA16_SNORM: return 8;
    case GL_RGB32F: return 12;
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 0;
    }
}

} // namespace shadowlab
