// Plugin libraries (see plugin_library.h).
#include "plugin/plugin_library.h"

#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <system_error>

namespace shadowlab {
namespace {

std::filesystem::path scratchDir() {
    std::error_code ec;
    auto dir = std::filesystem::temp_directory_path(ec) / ("shadowlab-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir, ec);
    return dir;
}

int categoryRank(const std::string& category) {
    static const char* order[] = {"baseline", "hard", "filtered", "soft", "coloured", "reference"};
    for (int i = 0; i < 6; ++i)
        if (category == order[i]) return i;
    return 6;
}

} // namespace

std::unique_ptr<PluginLibrary> PluginLibrary::open(const std::filesystem::path& file, std::string& error) {
    static std::atomic<int> loadCounter{0};
    std::error_code ec;
    auto library = std::unique_ptr<PluginLibrary>(new PluginLibrary());
    library->file_ = file;
    library->fileTime_ = std::filesystem::last_write_time(file, ec);
    library->fileSize_ = std::filesystem::file_size(file, ec);
    if (ec) {
        error = file.string() + ": cannot read plugin library (" + ec.message() + ")";
        return nullptr;
    }
    library->loadedCopy_ = scratchDir() / (file.stem().string() + "-" + std::to_string(loadCounter++) + ".so");
    std::filesystem::copy_file(file, library->loadedCopy_, std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) {
        error = file.string() + ": cannot copy plugin for loading (" + ec.message() + ")";
        return nullptr;
    }
    library->handle_ = dlopen(library->loadedCopy_.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library->handle_) {
        const char* reason = dlerror();
        error = file.string() + ": cannot load plugin (" + (reason ? reason : "unknown dlopen error") + ")";
        return nullptr;
    }
    using EntryFunction = const PluginEntry* (*)();
    auto entryFunction = reinterpret_cast<EntryFunction>(dlsym(library->handle_, SHADOWLAB_ENTRY_SYMBOL));
    if (!entryFunction) {
        error = file.string() + ": not a shadowlab plugin (no '" SHADOWLAB_ENTRY_SYMBOL "' entry symbol)";
        return nullptr;
    }
    const PluginEntry* entry = entryFunction();
    if (!entry) {
        error = file.string() + ": entry point returned nothing";
        return nullptr;
    }
    if (entry->abiVersion != SHADOWLAB_ABI_VERSION) {
        error = file.string() + ": plugin ABI version " + std::to_string(entry->abiVersion) + ", host expects " +
                std::to_string(SHADOWLAB_ABI_VERSION) + " (rebuild the plugin against this shadowlab/technique.h)";
        return nullptr;
    }
    if (!entry->describe || !entry->create || !entry->destroy || !entry->describe()) {
        error = file.string() + ": plugin entry is incomplete (describe/create/destroy missing)";
        return nullptr;
    }
    library->entry_ = entry;
    library->info_ = copyDescriptor(*entry->describe(), file);
    if (const std::string problem = validateDescriptor(library->info_); !problem.empty()) {
        error = file.string() + ": invalid descriptor: " + problem;
        return nullptr;
    }
    return library;
}

PluginLibrary::~PluginLibrary() {
    if (handle_) dlclose(handle_);
    std::error_code ec;
    if (!loadedCopy_.empty()) std::filesystem::remove(loadedCopy_, ec);
}

PluginScan scanPlugins(const std::filesystem::path& dir) {
    PluginScan scan;
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) {
        scan.errors.push_back(dir.string() + ": plugin folder not found (build the project, or set SHADOWLAB_PLUGIN_DIR)");
        return scan;
    }
    std::vector<std::filesystem::path> files;
    for (const auto& item : std::filesystem::directory_iterator(dir, ec))
        if (item.path().extension() == ".so") files.push_back(item.path());
    std::sort(files.begin(), files.end());
    for (const auto& file : files) {
        std::string error;
        auto library = PluginLibrary::open(file, error);
        if (!library) {
            scan.errors.push_back(error);
            continue;
        }
        const bool duplicate = std::any_of(scan.techniques.begin(), scan.techniques.end(),
                                           [&](const TechniqueInfo& t) { return t.id == library->info().id; });
        if (duplicate) {
            scan.errors.push_back(file.string() + ": technique id '" + library->info().id + "' is already provided by another library");
            continue;
        }
        scan.techniques.push_back(library->info());
    }
    std::stable_sort(scan.techniques.begin(), scan.techniques.end(), [](const TechniqueInfo& a, const TechniqueInfo& b) {
        return std::pair(categoryRank(a.category), a.id) < std::pair(categoryRank(b.category), b.id);
    });
    return scan;
}

} // namespace shadowlab
