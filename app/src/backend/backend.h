// Where GL comes from: a GLFW window, EGL headless (device platform on NVIDIA, surfaceless on
// Mesa), or OSMesa (CI without a GPU). Every backend gives an OpenGL 4.5 core context; the host
// renders into its own framebuffers, so headless backends need no default framebuffer at all.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "shadowlab/technique.h"

struct GLFWwindow;

namespace shadowlab {

enum class BackendKind { Glfw, Egl, OSMesa };

const char* backendName(BackendKind kind);
std::optional<BackendKind> parseBackend(const std::string& name);
// GLFW when a display (X11 or Wayland) is present, EGL otherwise.
BackendKind defaultBackend();

class GlBackend {
public:
    virtual ~GlBackend() = default;
    virtual BackendKind kind() const = 0;
    // Function that glad loads GL entry points with (valid while the backend lives).
    virtual GlLoader loader() const = 0;
    // Windowed backends: the GLFW window; headless: nullptr.
    virtual GLFWwindow* window() const { return nullptr; }
    // Window framebuffer size; headless: the size given at creation.
    virtual glm::ivec2 framebufferSize() const = 0;
    virtual void swapBuffers() {}
    virtual void pollEvents() {}
    virtual bool shouldClose() const { return false; }
    // e.g. "EGL 1.5 device platform" / "OSMesa 22.3.6"
    virtual std::string description() const = 0;
};

// Creates the context and makes it current. On failure returns nullptr and a message that says
// what is missing (e.g. "OSMesa backend: libOSMesa.so.8 not found (install libosmesa6)").
std::unique_ptr<GlBackend> createBackend(BackendKind kind, glm::ivec2 size, const std::string& title,
                                         bool visible, std::string& error);

} // namespace shadowlab
