// GLFW backend: a window with an OpenGL 4.5 core context (X11/GLX with Debian's GLFW build). The
// interactive path; vsync is off so that frame timings measure the technique, not the monitor.
#define GLFW_INCLUDE_NONE // GL declarations come from glad in the host; keep GL/gl.h out
#include <GLFW/glfw3.h>

#include "backend/backend.h"

namespace shadowlab {

std::string describeGlContext(GlLoader loader); // backend.cpp

namespace {

// GLFW reports errors through a callback only; the latest text goes into createBackend's message.
std::string lastGlfwError;

void recordGlfwError(int code, const char* description) {
    lastGlfwError = description != nullptr ? description : "error " + std::to_string(code);
}

class GlfwBackend final : public GlBackend {
public:
    explicit GlfwBackend(GLFWwindow* window) : window_(window) {
        int major = 0, minor = 0, revision = 0;
        glfwGetVersion(&major, &minor, &revision);
        description_ = "GLFW " + std::to_string(major) + "." + std::to_string(minor) + "." +
                std::to_string(revision) + " window, " + describeGlContext(loader());
    }
    ~GlfwBackend() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    GlfwBackend(const GlfwBackend&) = delete;
    GlfwBackend& operator=(const GlfwBackend&) = delete;

    BackendKind kind() const override { return BackendKind::Glfw; }
    // glfwGetProcAddress already has the GlLoader signature and keeps no per-backend state.
    GlLoader loader() const override { return glfwGetProcAddress; }
    GLFWwindow* window() const override { return window_; }
    glm::ivec2 framebufferSize() const override {
        glm::ivec2 size{0};
        glfwGetFramebufferSize(window_, &size.x, &size.y);
        return size;
    }
    void swapBuffers() override { glfwSwapBuffers(window_); }
    void pollEvents() override { glfwPollEvents(); }
    bool shouldClose() const override { return glfwWindowShouldClose(window_) != 0; }
    std::string description() const override { return description_; }

private:
    GLFWwindow* window_;
    std::string description_;
};

} // namespace

std::unique_ptr<GlBackend> createGlfwBackend(glm::ivec2 size, const std::string& title, bool visible,
                                             std::string& error) {
    lastGlfwError.clear();
    glfwSetErrorCallback(recordGlfwError);
    if (glfwInit() != GLFW_TRUE) {
        error = "GLFW backend: glfwInit failed: " + lastGlfwError;
        return nullptr;
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#ifndef NDEBUG
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE); // KHR_debug messages in debug builds
#endif
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window = glfwCreateWindow(size.x, size.y, title.c_str(), nullptr, nullptr);
    if (window == nullptr) {
        error = "GLFW backend: cannot create a window with an OpenGL 4.5 core context: " + lastGlfwError;
        glfwTerminate();
        return nullptr;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
    return std::make_unique<GlfwBackend>(window);
}

} // namespace shadowlab
