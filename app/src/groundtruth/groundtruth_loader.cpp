// Opens the ground-truth module (libshadowlab_groundtruth.so) with dlopen; see groundtruth.h.
//
// RTLD_NODELETE: the module pulls in Embree and TBB, whose worker threads outlive any one
// device; unmapping them under a live thread crashes at exit. The handle is still counted, so
// the module formally outlives every instance, but the code stays mapped.
#include "groundtruth/groundtruth.h"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

#include "util/paths.h"

namespace shadowlab {

namespace {

using CreateFn = IGroundTruth* (*)(uint32_t);

std::shared_ptr<void> openModule(const std::string& name, std::string& dlError) {
    void* handle = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!handle) {
        const char* message = dlerror();
        dlError = message ? message : "dlopen failed";
        return nullptr;
    }
    return std::shared_ptr<void>(handle, [](void* h) { dlclose(h); });
}

} // namespace

GroundTruthPtr loadGroundTruth(std::string& error) {
    namespace fs = std::filesystem;
    const fs::path exeDir = executableDir();
    std::vector<std::string> candidates;
    std::error_code ec;
    for (const fs::path& dir : {exeDir, pluginDir().parent_path()}) {
        const fs::path file = dir / SHADOWLAB_GROUNDTRUTH_MODULE;
        if (fs::exists(file, ec)) candidates.push_back(file.string());
    }
    candidates.push_back(SHADOWLAB_GROUNDTRUTH_MODULE); // LD_LIBRARY_PATH and the system paths

    std::shared_ptr<void> module;
    std::string where, dlError, firstError;
    for (const std::string& candidate : candidates) {
        module = openModule(candidate, dlError);
        if (module) {
            where = candidate;
            break;
        }
        // A file that exists but does not load (missing libembree3, undefined symbol) is the
        // interesting failure; the plain-name attempt only ever says "not found".
        if (firstError.empty() && candidate != SHADOWLAB_GROUNDTRUTH_MODULE) firstError = dlError;
    }
    if (!module) {
        error = firstError.empty()
                    ? "ground truth: " SHADOWLAB_GROUNDTRUTH_MODULE " not found beside " + exeDir.string() +
                          " (build target shadowlab_groundtruth; needs libembree3)"
                    : "ground truth: " + firstError + " (build target shadowlab_groundtruth; needs libembree3)";
        return nullptr;
    }

    dlerror();
    auto create = reinterpret_cast<CreateFn>(dlsym(module.get(), SHADOWLAB_GROUNDTRUTH_ENTRY_SYMBOL));
    if (!create) {
        error = "ground truth: " + where + " does not export " SHADOWLAB_GROUNDTRUTH_ENTRY_SYMBOL;
        return nullptr;
    }
    IGroundTruth* instance = create(SHADOWLAB_GROUNDTRUTH_ABI_VERSION);
    if (!instance) {
        error = "ground truth: " + where + " was built for another ABI version than " +
                std::to_string(SHADOWLAB_GROUNDTRUTH_ABI_VERSION) + "; rebuild shadowlab_groundtruth";
        return nullptr;
    }
    error.clear();
    return GroundTruthPtr(instance, GroundTruthDeleter{std::move(module)});
}

} // namespace shadowlab
