// Backend selection: names for the CLI, the default for the machine at hand, and the dispatch to
// the three implementations (backend_glfw.cpp, backend_egl.cpp, backend_osmesa.cpp).
#include "backend/backend.h"

#include <cstdlib>
#include <exception>
#include <initializer_list>

namespace shadowlab {

// Defined in the backend_*.cpp files; each returns nullptr and fills `error` on failure.
std::unique_ptr<GlBackend> createGlfwBackend(glm::ivec2 size, const std::string& title, bool visible,
                                             std::string& error);
std::unique_ptr<GlBackend> createEglBackend(glm::ivec2 size, std::string& error);
std::unique_ptr<GlBackend> createOSMesaBackend(glm::ivec2 size, std::string& error);

// "4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)" for description(); the context
// must be current. Goes through `loader` rather than glad so that the host's gladLoadGL stays the
// only place that fills glad's function pointers.
std::string describeGlContext(GlLoader loader) {
    constexpr unsigned kGlRenderer = 0x1F01, kGlVersion = 0x1F02;
    using GetString = const unsigned char* (*)(unsigned);
    auto getString = reinterpret_cast<GetString>(loader("glGetString"));
    if (getString == nullptr) return "glGetString missing";
    auto text = [&](unsigned name) {
        const unsigned char* value = getString(name);
        return value != nullptr ? std::string(reinterpret_cast<const char*>(value)) : std::string("?");
    };
    return text(kGlVersion) + ", " + text(kGlRenderer);
}

const char* backendName(BackendKind kind) {
    switch (kind) {
    case BackendKind::Glfw: return "glfw";
    case BackendKind::Egl: return "egl";
    case BackendKind::OSMesa: return "osmesa";
    }
    return "unknown";
}

std::optional<BackendKind> parseBackend(const std::string& name) {
    for (BackendKind kind : {BackendKind::Glfw, BackendKind::Egl, BackendKind::OSMesa}) {
        if (name == backendName(kind)) return kind;
    }
    return std::nullopt;
}

BackendKind defaultBackend() {
    auto present = [](const char* variable) {
        const char* value = std::getenv(variable);
        return value != nullptr && value[0] != '\0';
    };
    return present("DISPLAY") || present("WAYLAND_DISPLAY") ? BackendKind::Glfw : BackendKind::Egl;
}

std::unique_ptr<GlBackend> createBackend(BackendKind kind, glm::ivec2 size, const std::string& title,
                                         bool visible, std::string& error) {
    error.clear();
    if (size.x <= 0 || size.y <= 0) {
        error = std::string(backendName(kind)) + " backend: size must be positive, got " +
                std::to_string(size.x) + "x" + std::to_string(size.y);
        return nullptr;
    }
    // The callers treat nullptr + message as the only failure mode, so nothing may escape
    // (a huge size makes the OSMesa colour buffer allocation throw, for instance).
    try {
        switch (kind) {
        case BackendKind::Glfw: return createGlfwBackend(size, title, visible, error);
        case BackendKind::Egl: return createEglBackend(size, error);
        case BackendKind::OSMesa: return createOSMesaBackend(size, error);
        }
        error = "unknown backend";
    } catch (const std::exception& exception) {
        error = std::string(backendName(kind)) + " backend: " + exception.what();
    }
    return nullptr;
}

} // namespace shadowlab
