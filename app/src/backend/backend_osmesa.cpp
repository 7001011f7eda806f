// OSMesa backend: Mesa's off-screen llvmpipe renderer, for CI and machines without a GPU. The
// library is opened with dlopen (never linked), so the binary also starts where it is not
// installed; <GL/osmesa.h> is used only for its constants and types.
#include <dlfcn.h>

#include <GL/osmesa.h>

#include <utility>
#include <vector>

#include "backend/backend.h"

namespace shadowlab {

std::string describeGlContext(GlLoader loader); // backend.cpp

namespace {

// The four entry points the backend needs, resolved once per process. The library is never
// closed: unloading Mesa and LLVM mid-process is unsafe, and a second backend would reopen it.
struct OSMesaLibrary {
    decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
    decltype(&OSMesaDestroyContext) destroyContext = nullptr;
    std::string error; // empty when loaded
};

template <typename Function>
bool resolve(void* library, const char* name, Function& function, std::string& error) {
    function = reinterpret_cast<Function>(dlsym(library, name));
    if (function == nullptr && error.empty()) error = std::string("OSMesa backend: libOSMesa has no ") + name;
    return function != nullptr;
}

const OSMesaLibrary& osmesaLibrary() {
    static const OSMesaLibrary library = [] {
        OSMesaLibrary loaded;
        void* handle = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) handle = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
        if (handle == nullptr) {
            loaded.error = "OSMesa backend: libOSMesa.so.8 not found (install libosmesa6)";
            return loaded;
        }
        resolve(handle, "OSMesaCreateContextAttribs", loaded.createContextAttribs, loaded.error);
        resolve(handle, "OSMesaMakeCurrent", loaded.makeCurrent, loaded.error);
        resolve(handle, "OSMesaGetProcAddress", loaded.getProcAddress, loaded.error);
        resolve(handle, "OSMesaDestroyContext", loaded.destroyContext, loaded.error);
        return loaded;
    }();
    return library;
}

class OSMesaBackend final : public GlBackend {
public:
    OSMesaBackend(const OSMesaLibrary& library, OSMesaContext context, glm::ivec2 size,
                  std::vector<unsigned char> buffer)
            : library_(library), context_(context), size_(size), colorBuffer_(std::move(buffer)) {
        description_ = "OSMesa, " + describeGlContext(loader());
    }
    ~OSMesaBackend() override {
        library_.makeCurrent(nullptr, nullptr, 0, 0, 0); // Mesa: null context and buffer release
        library_.destroyContext(context_);
    }
    OSMesaBackend(const OSMesaBackend&) = delete;
    OSMesaBackend& operator=(const OSMesaBackend&) = delete;

    BackendKind kind() const override { return BackendKind::OSMesa; }
    // OSMesaGetProcAddress from the process-wide library table; it already has the GlLoader
    // signature (OSMESAproc is void (*)()) and also returns core GL functions.
    GlLoader loader() const override { return library_.getProcAddress; }
    glm::ivec2 framebufferSize() const override { return size_; }
    std::string description() const override { return description_; }

private:
    const OSMesaLibrary& library_;
    OSMesaContext context_;
    glm::ivec2 size_;
    // OSMesaMakeCurrent insists on a colour buffer (the default framebuffer) even though the host
    // renders into its own framebuffers; it must outlive the context.
    std::vector<unsigned char> colorBuffer_;
    std::string description_;
};

} // namespace

std::unique_ptr<GlBackend> createOSMesaBackend(glm::ivec2 size, std::string& error) {
    const OSMesaLibrary& library = osmesaLibrary();
    if (!library.error.empty()) {
        error = library.error;
        return nullptr;
    }
    // Allocated first: a size too large throws here, before there is a context to leak.
    std::vector<unsigned char> colorBuffer(static_cast<size_t>(size.x) * static_cast<size_t>(size.y) * 4);
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA,
                              OSMESA_DEPTH_BITS, 24,
                              OSMESA_STENCIL_BITS, 8,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION, 4,
                              OSMESA_CONTEXT_MINOR_VERSION, 5,
                              0};
    OSMesaContext context = library.createContextAttribs(attributes, nullptr);
    if (context == nullptr) {
        // Only llvmpipe reaches 4.5; softpipe and older Mesa releases stop below it.
        error = "OSMesa backend: OSMesaCreateContextAttribs refused an OpenGL 4.5 core context";
        return nullptr;
    }
    if (library.makeCurrent(context, colorBuffer.data(), GL_UNSIGNED_BYTE, size.x, size.y) != GL_TRUE) {
        library.destroyContext(context);
        error = "OSMesa backend: OSMesaMakeCurrent failed for " + std::to_string(size.x) + "x" +
                std::to_string(size.y);
        return nullptr;
    }
    return std::make_unique<OSMesaBackend>(library, context, size, std::move(colorBuffer));
}

} // namespace shadowlab
