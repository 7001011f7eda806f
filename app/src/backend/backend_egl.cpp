// EGL headless backend: an OpenGL 4.5 core context with no surface at all (the host renders into its
// own framebuffers). Displays are tried in the order that works across drivers: hardware devices of
// EGL_EXT_platform_device (NVIDIA's only headless path), Mesa's surfaceless platform, software
// devices (Mesa's llvmpipe device), and finally eglGetDisplay(EGL_DEFAULT_DISPLAY).
// libEGL is opened at run time by glad's loader, so the binary starts where no EGL is installed.
#include <dlfcn.h>

#include <glad/egl.h>

#include <cstdio>
#include <utility>
#include <vector>

#include "backend/backend.h"

namespace shadowlab {

std::string describeGlContext(GlLoader loader); // backend.cpp

namespace {

// EGL_EXT_device_drm, which the glad loader is not generated with; only used for description().
constexpr EGLint kEglDrmDeviceFile = 0x3233;

bool hasExtension(const char* extensions, const std::string& name) {
    if (extensions == nullptr) return false;
    const std::string list = std::string(" ") + extensions + " ";
    return list.find(" " + name + " ") != std::string::npos;
}

std::string eglErrorName(EGLint code) {
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: {
        char text[16];
        std::snprintf(text, sizeof text, "0x%04X", static_cast<unsigned>(code));
        return text;
    }
    }
}

std::string eglFailure(const char* call) {
    return std::string(call) + " failed (" + eglErrorName(eglGetError()) + ")";
}

struct Candidate {
    std::string platform; // for description() and error messages
    EGLDisplay display;
};

struct EglContext {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLint major = 0;
    EGLint minor = 0;
};

// Everything after eglGetPlatformDisplay: initialise, pick a GL config, create the 4.5 core context
// and make it current without a surface. On failure the display is terminated again.
bool createContext(EGLDisplay display, EglContext& out, std::string& reason) {
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
        reason = eglFailure("eglInitialize");
        return false;
    }
    auto fail = [&](std::string why) {
        reason = std::move(why);
        eglTerminate(display);
        return false;
    };
    // Again with the display: only now does glad see its version (eglBindAPI is EGL 1.2) and its
    // display extensions.
    if (gladLoaderLoadEGL(display) == 0 || eglBindAPI == nullptr) {
        return fail("glad could not load EGL 1.2 entry points");
    }
    if (!hasExtension(eglQueryString(display, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
        return fail("no EGL_KHR_surfaceless_context");
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) return fail(eglFailure("eglBindAPI(EGL_OPENGL_API)"));

    // Headless configs are pbuffer-only (NVIDIA) or may have no surface type at all (Mesa
    // surfaceless), and the default EGL_SURFACE_TYPE of eglChooseConfig is EGL_WINDOW_BIT.
    const EGLint surfaceTypes[] = {EGL_PBUFFER_BIT, EGL_DONT_CARE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    for (EGLint surfaceType : surfaceTypes) {
        const EGLint attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, surfaceType,
                                     EGL_NONE};
        if (eglChooseConfig(display, attributes, &config, 1, &configCount) == EGL_TRUE && configCount > 0) {
            break;
        }
    }
    if (configCount == 0) return fail("no config with EGL_OPENGL_BIT");

    // EGL 1.5 names; the values are those of EGL_KHR_create_context, which 1.4 drivers take.
    std::vector<EGLint> attributes = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
#ifndef NDEBUG
    // Debug builds ask for KHR_debug output; EGL_CONTEXT_OPENGL_DEBUG is new in EGL 1.5.
    const bool egl15 = major > 1 || minor >= 5;
    attributes.insert(attributes.end() - 1,
                      {egl15 ? EGL_CONTEXT_OPENGL_DEBUG : EGL_CONTEXT_FLAGS_KHR,
                       egl15 ? EGL_TRUE : EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR});
#endif
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes.data());
#ifndef NDEBUG
    if (context == EGL_NO_CONTEXT) {
        // The debug flag is a convenience; a driver that refuses it still gives a usable context.
        attributes.erase(attributes.end() - 3, attributes.end() - 1);
        context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes.data());
    }
#endif
    if (context == EGL_NO_CONTEXT) return fail(eglFailure("eglCreateContext(OpenGL 4.5 core)"));
    if (eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context) != EGL_TRUE) {
        std::string why = eglFailure("eglMakeCurrent(EGL_NO_SURFACE)");
        eglDestroyContext(display, context);
        return fail(why);
    }
    out = {display, context, major, minor};
    return true;
}

class EglBackend final : public GlBackend {
public:
    EglBackend(const EglContext& context, glm::ivec2 size, const std::string& platform)
            : context_(context), size_(size) {
        const char* vendor = eglQueryString(context_.display, EGL_VENDOR);
        description_ = "EGL " + std::to_string(context_.major) + "." + std::to_string(context_.minor) + " " +
                platform + ", " + (vendor != nullptr ? vendor : "unknown vendor") + ", " +
                describeGlContext(loader());
    }
    ~EglBackend() override {
        eglMakeCurrent(context_.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(context_.display, context_.context);
        eglTerminate(context_.display);
        eglReleaseThread();
        // libEGL stays loaded (no gladLoaderUnloadEGL): unloading a vendor driver mid-process is
        // unsafe, and the next backend would load it again anyway.
    }
    EglBackend(const EglBackend&) = delete;
    EglBackend& operator=(const EglBackend&) = delete;

    BackendKind kind() const override { return BackendKind::Egl; }
    // libEGL's own eglGetProcAddress (glad holds it in a global; one backend per process at a
    // time). It returns core GL functions too (EGL 1.5, EGL_KHR_get_all_proc_addresses).
    GlLoader loader() const override { return eglGetProcAddress; }
    glm::ivec2 framebufferSize() const override { return size_; }
    std::string description() const override { return description_; }

private:
    EglContext context_;
    glm::ivec2 size_;
    std::string description_;
};

std::vector<Candidate> candidateDisplays(const char* clientExtensions) {
    std::vector<Candidate> hardware, surfaceless, software;
    const bool platformBase =
            hasExtension(clientExtensions, "EGL_EXT_platform_base") && eglGetPlatformDisplayEXT != nullptr;
    if (platformBase && hasExtension(clientExtensions, "EGL_EXT_platform_device") &&
        eglQueryDevicesEXT != nullptr) {
        EGLint count = 0;
        if (eglQueryDevicesEXT(0, nullptr, &count) == EGL_TRUE && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<size_t>(count));
            eglQueryDevicesEXT(count, devices.data(), &count);
            devices.resize(static_cast<size_t>(count));
            for (size_t index = 0; index < devices.size(); ++index) {
                const char* deviceExtensions = eglQueryDeviceStringEXT != nullptr
                        ? eglQueryDeviceStringEXT(devices[index], EGL_EXTENSIONS)
                        : nullptr;
                std::string name = "device platform #" + std::to_string(index);
                if (hasExtension(deviceExtensions, "EGL_EXT_device_drm")) {
                    if (const char* file = eglQueryDeviceStringEXT(devices[index], kEglDrmDeviceFile)) {
                        name += std::string(" (") + file + ")";
                    }
                }
                EGLDisplay display =
                        eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[index], nullptr);
                if (display == EGL_NO_DISPLAY) continue;
                // Mesa lists llvmpipe as a device too; a GPU, where there is one, comes first.
                const bool isSoftware = hasExtension(deviceExtensions, "EGL_MESA_device_software");
                (isSoftware ? software : hardware)
                        .push_back({name + (isSoftware ? " (software)" : ""), display});
            }
        }
    }
    if (platformBase && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay display =
                eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (display != EGL_NO_DISPLAY) surfaceless.push_back({"surfaceless platform", display});
    }
    std::vector<Candidate> candidates = std::move(hardware);
    candidates.insert(candidates.end(), surfaceless.begin(), surfaceless.end());
    candidates.insert(candidates.end(), software.begin(), software.end());
    if (EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY); display != EGL_NO_DISPLAY) {
        candidates.push_back({"default display", display});
    }
    return candidates;
}

} // namespace

std::unique_ptr<GlBackend> createEglBackend(glm::ivec2 size, std::string& error) {
    // Probe first so that a missing library gets its own message (glad reports only failure), and
    // keep the reference: the library then stays resident for the rest of the process.
    static void* const libEgl = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (libEgl == nullptr) {
        error = "EGL backend: libEGL.so.1 not found (install libegl1)";
        return nullptr;
    }
    // With EGL_NO_DISPLAY glad loads the client side: EGL 1.0 functions and client extensions
    // (device enumeration, eglGetPlatformDisplayEXT).
    if (gladLoaderLoadEGL(EGL_NO_DISPLAY) == 0) {
        error = "EGL backend: libEGL.so.1 found, but glad could not load its entry points";
        return nullptr;
    }
    // Client extensions: read now, since reloading glad with a display resets its extension flags.
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    std::string failures;
    for (const Candidate& candidate : candidateDisplays(clientExtensions)) {
        EglContext context;
        std::string reason;
        if (createContext(candidate.display, context, reason)) {
            return std::make_unique<EglBackend>(context, size, candidate.platform);
        }
        failures += "; " + candidate.platform + ": " + reason;
    }
    error = "EGL backend: no display gave an OpenGL 4.5 core context" +
            (failures.empty()
                     ? std::string(" (libEGL has no driver: check the glvnd vendor files in "
                                   "/usr/share/glvnd/egl_vendor.d or __EGL_VENDOR_LIBRARY_FILENAMES)")
                     : failures);
    return nullptr;
}

} // namespace shadowlab
