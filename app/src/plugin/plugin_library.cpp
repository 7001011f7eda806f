// Plugin libraries (see plugin_library.h).
#include "plugin/plugin_library.h"

#include <dlfcn.h>
#include <elf.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstddef>
#include <cmath>
#include <cstring>
#include <fstream>
#include <chrono>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <system_error>

#include "util/scratch_dir.h"
#include "util/strings.h"

namespace shadowlab {
namespace {

// Lengths a descriptor string may have: a string without its terminator within this many bytes is
// garbage, not text (explanations are a paragraph).
constexpr size_t kMaxIdLength = 64;
constexpr size_t kMaxTextLength = 64 * 1024;

// "" when `text` is a terminated string of at most `limit` bytes (and, for ids, non-empty and
// made of [A-Za-z0-9_-]: ids are --set keys, file names and CSV columns), else the problem.
std::string checkText(const char* text, size_t limit, bool isId, bool required) {
    if (!text) return required ? "is null" : "";
    const size_t length = ::strnlen(text, limit + 1);
    if (length > limit) return "is longer than " + std::to_string(limit) + " bytes (or not terminated)";
    if (isId) {
        if (length == 0) return "is empty";
        for (size_t i = 0; i < length; ++i) {
            const unsigned char c = static_cast<unsigned char>(text[i]);
            if (!std::isalnum(c) && c != '_' && c != '-') return "'" + std::string(text) + "' has a character other than A-Z, a-z, 0-9, _ and -";
        }
    }
    return "";
}

} // namespace

std::string validateDescriptor(const TechniqueDesc& desc) {
    // An ABI 3 descriptor reaches at least to paramCount; fields after it (flags) are optional.
    if (desc.structSize < offsetof(TechniqueDesc, paramCount) + sizeof(desc.paramCount))
        return "descriptor structSize " + std::to_string(desc.structSize) + " is too small for an ABI " +
               std::to_string(SHADOWLAB_ABI_VERSION) + " TechniqueDesc";
    if (std::string problem = checkText(desc.id, kMaxIdLength, true, true); !problem.empty()) return "id " + problem;
    const std::string id = desc.id;
    const std::pair<const char*, const char*> texts[] = {{"displayName", desc.displayName},
                                                         {"category", desc.category},
                                                         {"explanation", desc.explanation}};
    for (const auto& [name, text] : texts)
        if (std::string problem = checkText(text, kMaxTextLength, false, false); !problem.empty()) return std::string(name) + " " + problem;
    if (desc.structSize >= offsetof(TechniqueDesc, debugViews) + sizeof(desc.debugViews))
        if (std::string problem = checkText(desc.debugViews, kMaxTextLength, false, false); !problem.empty())
            return "debugViews " + problem;
    if (std::string problem = checkText(desc.shadowGlsl, kMaxTextLength, false, true); !problem.empty() || !*desc.shadowGlsl)
        return "shadowGlsl " + (problem.empty() ? std::string("is empty") : problem) + " (it names the GLSL file with shadowTerm)";
    if (desc.structSize >= offsetof(TechniqueDesc, translucencyModel) + sizeof(desc.translucencyModel) &&
        static_cast<uint32_t>(desc.translucencyModel) >= kTranslucencyModelCount)
        return "translucencyModel " + std::to_string(static_cast<uint32_t>(desc.translucencyModel)) +
               " is not one of 0-" + std::to_string(kTranslucencyModelCount - 1) + " (TranslucencyModel in technique.h)";
    if (desc.paramCount > kMaxParams)
        return "paramCount " + std::to_string(desc.paramCount) + " is more than " + std::to_string(kMaxParams);
    if (desc.paramCount > 0 && !desc.params) return "paramCount is " + std::to_string(desc.paramCount) + " but params is null";
    std::set<std::string> seen;
    for (uint32_t i = 0; i < desc.paramCount; ++i) {
        const ParamDesc& p = desc.params[i];
        std::string name = "parameter " + std::to_string(i);
        if (std::string problem = checkText(p.id, kMaxIdLength, true, true); !problem.empty()) return name + ": id " + problem;
        name = "parameter '" + std::string(p.id) + "'";
        if (!seen.insert(p.id).second) return name + " is declared twice";
        for (const auto& [field, text] : {std::pair{"label", p.label}, std::pair{"unit", p.unit}, std::pair{"help", p.help}})
            if (std::string problem = checkText(text, kMaxTextLength, false, false); !problem.empty()) return name + ": " + field + " " + problem;
        const uint32_t type = static_cast<uint32_t>(p.type);
        if (type > static_cast<uint32_t>(ParamType::Enum)) return name + ": unknown type " + std::to_string(type);
        if (!std::isfinite(p.minValue) || !std::isfinite(p.maxValue) || !std::isfinite(p.defaultValue))
            return name + ": min, max and default must be finite numbers";
        if (!(p.minValue <= p.defaultValue && p.defaultValue <= p.maxValue))
            return name + ": default outside its range (min <= default <= max)";
        const bool whole = p.minValue == std::floor(p.minValue) && p.maxValue == std::floor(p.maxValue) &&
                           p.defaultValue == std::floor(p.defaultValue);
        if ((p.type == ParamType::Int || p.type == ParamType::Enum) && !whole)
            return name + ": an int or enum parameter needs whole min, max and default";
        if (p.type == ParamType::Bool && !(p.minValue == 0.0 && p.maxValue == 1.0 && whole))
            return name + ": a bool parameter has the range 0 to 1 and a default of 0 or 1";
        if (p.type == ParamType::Enum) {
            if (std::string problem = checkText(p.enumLabels, kMaxTextLength, false, true); !problem.empty())
                return name + ": enumLabels " + problem;
            size_t labels = 1;
            for (const char* c = p.enumLabels; *c; ++c) labels += *c == '|';
            if (p.minValue != 0.0 || p.maxValue != double(labels - 1))
                return name + ": enum labels do not match its range (" + std::to_string(labels) +
                       " labels need min 0 and max " + std::to_string(labels - 1) + ")";
        }
    }
    // Flag conditions (after translucencyModel, optional): each names declared flags, one of the
    // descriptor's parameters and values that parameter can take.
    if (desc.structSize >= offsetof(TechniqueDesc, flagConditionCount) + sizeof(desc.flagConditionCount) &&
        desc.flagConditionCount > 0) {
        if (!desc.flagConditions)
            return "flagConditionCount is " + std::to_string(desc.flagConditionCount) + " but flagConditions is null";
        if (desc.flagConditionCount > kMaxParams)
            return "flagConditionCount " + std::to_string(desc.flagConditionCount) + " is more than " + std::to_string(kMaxParams);
        // The parameters as the host parses them (the struct is complete here: it reaches the
        // last field), without the conditions not yet checked.
        TechniqueDesc withoutConditions = desc;
        withoutConditions.flagConditionCount = 0;
        const TechniqueInfo info = copyDescriptor(withoutConditions, {});
        for (uint32_t i = 0; i < desc.flagConditionCount; ++i) {
            const FlagCondition& c = desc.flagConditions[i];
            const std::string name = "flagConditions[" + std::to_string(i) + "]";
            if (c.flags == 0 || (c.flags & ~desc.flags) != 0)
                return name + ": flags " + std::to_string(c.flags) + " are not a non-empty subset of the descriptor's flags " +
                       std::to_string(desc.flags);
            if (std::string problem = checkText(c.param, kMaxIdLength, true, true); !problem.empty())
                return name + ": param " + problem;
            const ParamSpec* spec = info.findParam(c.param);
            if (!spec) return name + ": '" + std::string(c.param) + "' is not one of the descriptor's parameters";
            if (std::string problem = checkText(c.values, kMaxTextLength, false, true); !problem.empty() || !*c.values)
                return name + ": values " + (problem.empty() ? std::string("is empty") : problem);
            std::string value;
            for (const char* p = c.values;; ++p) {
                if (*p && *p != '|') {
                    value += *p;
                    continue;
                }
                std::string error;
                if (!parseParamValue(*spec, value, error)) return name + ": " + error;
                value.clear();
                if (!*p) break;
            }
        }
    }
    return "";
}

namespace {

int categoryRank(const std::string& category) {
    static const char* order[] = {"baseline", "hard", "filtered", "soft", "coloured", "reference"};
    for (int i = 0; i < 6; ++i)
        if (category == order[i]) return i;
    return 6;
}

} // namespace

std::string incompleteElfImage(const std::filesystem::path& file) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) return "cannot read its size (" + ec.message() + ")";
    std::ifstream in(file, std::ios::binary);
    Elf64_Ehdr header{};
    if (!in.read(reinterpret_cast<char*>(&header), sizeof(header)))
        return "incomplete ELF image (" + std::to_string(size) + " bytes, shorter than an ELF header)";
    if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0) return "incomplete ELF image (no ELF header yet)";
    if (header.e_ident[EI_CLASS] != ELFCLASS64) return "not a 64-bit ELF library";
    auto beyond = [&](uint64_t offset, uint64_t count, uint64_t entry, const char* what) -> std::string {
        const uint64_t end = offset + count * entry;
        if (end <= size && end >= offset) return "";
        return std::string("incomplete ELF image (") + what + " end at byte " + std::to_string(end) + ", the file has " +
               std::to_string(size) + ")";
    };
    if (auto problem = beyond(header.e_phoff, header.e_phnum, header.e_phentsize, "program headers"); !problem.empty())
        return problem;
    if (auto problem = beyond(header.e_shoff, header.e_shnum, header.e_shentsize, "section headers"); !problem.empty())
        return problem;
    if (header.e_phentsize != sizeof(Elf64_Phdr)) return "";   // unusual layout: left to the loader
    for (uint16_t i = 0; i < header.e_phnum; ++i) {
        Elf64_Phdr segment{};
        in.seekg(std::streamoff(header.e_phoff + uint64_t(i) * sizeof(Elf64_Phdr)));
        if (!in.read(reinterpret_cast<char*>(&segment), sizeof(segment))) return "incomplete ELF image (program headers)";
        if (segment.p_type != PT_LOAD) continue;
        if (auto problem = beyond(segment.p_offset, 1, segment.p_filesz, "a loadable segment's bytes"); !problem.empty())
            return problem;
    }
    return "";
}

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
    std::string scratchError;
    const std::filesystem::path scratch = scratchDir(scratchError);
    if (scratch.empty()) {
        error = file.string() + ": cannot copy plugin for loading (" + scratchError + ")";
        return nullptr;
    }
    library->loadedCopy_ = scratch / (file.stem().string() + "-" + std::to_string(loadCounter++) + ".so");
    std::filesystem::copy_file(file, library->loadedCopy_, std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) {
        error = file.string() + ": cannot copy plugin for loading (" + ec.message() + ")";
        return nullptr;
    }
    // The copy is what gets loaded: checked itself, since the original may change while copied.
    if (const std::string problem = incompleteElfImage(library->loadedCopy_); !problem.empty()) {
        error = file.string() + ": cannot load plugin (" + problem + ")";
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
    // The major version must match; any minor version of it loads (technique.h, "Versions").
    const uint32_t major = entry->abiVersion & 0xFFFFu, minor = entry->abiVersion >> 16;
    if (major != SHADOWLAB_ABI_VERSION) {
        error = file.string() + ": plugin ABI version " + std::to_string(major) + "." + std::to_string(minor) +
                ", host expects " + std::to_string(SHADOWLAB_ABI_VERSION) + ".x (rebuild the plugin against this "
                "shadowlab/technique.h)";
        return nullptr;
    }
    // From 3.1 the entry says how much of it the plugin has; 3.0 entries end before structSize.
    if (minor >= 1 && (entry->structSize < offsetof(PluginEntry, structSize) + sizeof(uint32_t) || entry->structSize > 4096)) {
        error = file.string() + ": plugin entry structSize " + std::to_string(entry->structSize) +
                " does not fit an ABI 3." + std::to_string(minor) + " entry";
        return nullptr;
    }
    library->abiMinor_ = minor;
    if (!entry->describe || !entry->create || !entry->destroy || !entry->describe()) {
        error = file.string() + ": plugin entry is incomplete (describe/create/destroy missing)";
        return nullptr;
    }
    // Checked before anything in it is copied or used: a paramCount of 1e8 would otherwise be read.
    const TechniqueDesc& desc = *entry->describe();
    if (const std::string problem = validateDescriptor(desc); !problem.empty()) {
        error = file.string() + ": invalid descriptor: " + problem;
        return nullptr;
    }
    library->entry_ = entry;
    library->info_ = copyDescriptor(desc, file);
    return library;
}

PluginLibrary::~PluginLibrary() {
    if (handle_) dlclose(handle_);
    std::error_code ec;
    if (!loadedCopy_.empty()) std::filesystem::remove(loadedCopy_, ec);
}

namespace {

// What opening one library gave: its descriptor or the error. A scan only reads descriptors, so a
// library unchanged since an earlier scan in this process need not be copied and loaded again:
// each load is a copy and a dlopen, and under the sanitizers (23 instrumented libraries of several
// MiB, each dlopen relocating and registering tens of thousands of globals) one scan took about
// 0.5 s of CPU; a test process scanned five times before its first line and once more for each
// App, and a command-line run twice (issue 31).
struct OpenedDescriptor {
    std::filesystem::file_time_type time{};
    uintmax_t size = 0;
    std::optional<TechniqueInfo> info;
    std::string error;
};

// A file is taken as unchanged when its time and size are those of the earlier open and that time
// was already two seconds old then: file times are kept at the kernel's clock tick, so a file
// rewritten within a tick of being read can keep its time and size (git's "racily clean" entries).
constexpr auto kSettledAge = std::chrono::seconds(2);

OpenedDescriptor openDescriptor(const std::filesystem::path& file) {
    static std::mutex mutex;
    static std::map<std::filesystem::path, OpenedDescriptor> opened;
    std::error_code timeError, sizeError;
    const auto time = std::filesystem::last_write_time(file, timeError);
    const uintmax_t size = std::filesystem::file_size(file, sizeError);
    const bool known = !timeError && !sizeError;
    if (known) {
        const std::lock_guard lock(mutex);
        if (auto it = opened.find(file); it != opened.end() && it->second.time == time && it->second.size == size)
            return it->second;
    }
    OpenedDescriptor result{time, size, std::nullopt, ""};
    if (auto library = PluginLibrary::open(file, result.error)) result.info = library->info();
    if (known && std::filesystem::file_time_type::clock::now() - time > kSettledAge) {
        const std::lock_guard lock(mutex);
        opened[file] = result;
    }
    return result;
}

} // namespace

PluginScan scanPlugins(const std::filesystem::path& dir, const std::vector<std::string>& reservedIds) {
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
    // Two libraries claiming one id: neither is loaded, since which one is meant cannot be known
    // (a stale copy, a renamed build) and taking either silently changes what is measured.
    std::map<std::string, std::vector<TechniqueInfo>> byId;
    for (const auto& file : files) {
        OpenedDescriptor opened = openDescriptor(file);
        if (!opened.info) {
            scan.errors.push_back(opened.error);
            continue;
        }
        if (std::find(reservedIds.begin(), reservedIds.end(), opened.info->id) != reservedIds.end()) {
            scan.errors.push_back(file.string() + ": technique id '" + opened.info->id +
                                  "' belongs to the host's built-in technique");
            continue;
        }
        byId[opened.info->id].push_back(std::move(*opened.info));
    }
    for (auto& [id, claims] : byId) {
        if (claims.size() == 1) {
            scan.techniques.push_back(std::move(claims.front()));
            continue;
        }
        std::string files;
        for (const auto& claim : claims) appendListItem(files, claim.library.string());
        scan.errors.push_back("technique id '" + id + "' is claimed by " + std::to_string(claims.size()) +
                              " libraries: " + files + "; none of them is loaded (remove or rename all but one)");
    }
    std::stable_sort(scan.techniques.begin(), scan.techniques.end(), [](const TechniqueInfo& a, const TechniqueInfo& b) {
        return std::pair(categoryRank(a.category), a.id) < std::pair(categoryRank(b.category), b.id);
    });
    return scan;
}

} // namespace shadowlab
