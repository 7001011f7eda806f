// One loaded plugin library. Loading copies the .so to a fresh temporary name first, so that a
// rebuilt library at the same path is really loaded again (the dynamic loader would otherwise
// hand back the cached image; cr.h does the same), then checks the ABI version before calling
// anything else in it.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "plugin/params.h"
#include "shadowlab/technique.h"

namespace shadowlab {

class PluginLibrary {
public:
    // Returns nullptr and an error naming the file and the problem (missing entry symbol, ABI
    // version mismatch, invalid descriptor, dlopen failure).
    static std::unique_ptr<PluginLibrary> open(const std::filesystem::path& file, std::string& error);
    ~PluginLibrary();
    PluginLibrary(const PluginLibrary&) = delete;
    PluginLibrary& operator=(const PluginLibrary&) = delete;

    const PluginEntry& entry() const { return *entry_; }
    const TechniqueInfo& info() const { return info_; }
    // The minor ABI version the plugin was built for (0 for ABI 3.0: its entry has no structSize).
    uint32_t abiMinor() const { return abiMinor_; }
    const std::filesystem::path& file() const { return file_; }
    std::filesystem::file_time_type fileTime() const { return fileTime_; }
    uintmax_t fileSize() const { return fileSize_; }

private:
    PluginLibrary() = default;
    void* handle_ = nullptr;
    const PluginEntry* entry_ = nullptr;
    TechniqueInfo info_;
    uint32_t abiMinor_ = 0;
    std::filesystem::path file_;
    std::filesystem::path loadedCopy_;
    std::filesystem::file_time_type fileTime_{};
    uintmax_t fileSize_ = 0;
};

// "" when `file` is a complete 64-bit ELF image: its header, program headers, every loadable
// segment and the section header table lie inside the file. Otherwise what is missing, e.g.
// "incomplete ELF image (section headers end at byte 61234, the file has 40960)". A linker that
// is still writing leaves exactly this (GNU ld writes the ELF header last), so hot reload waits
// on it instead of reporting dlopen's "file too short" or "invalid ELF header".
std::string incompleteElfImage(const std::filesystem::path& file);

// Most parameters a descriptor may declare (the largest plugin has about twenty).
constexpr uint32_t kMaxParams = 256;

// A descriptor the host can trust, checked on the plugin's own struct before anything in it is
// copied: id (non-empty, [A-Za-z0-9_-], at most 64 bytes) and strings terminated within bounds,
// shadowGlsl named, paramCount at most kMaxParams with params non-null, each parameter's id
// unique and valid, its type known, min <= default <= max all finite (whole for int and enum,
// 0..1 for bool), and enum labels as many as the range. Returns the problem, or "".
// The one place descriptors are validated.
std::string validateDescriptor(const TechniqueDesc& desc);

struct PluginScan {
    std::vector<TechniqueInfo> techniques;   // sorted by category order, then id
    std::vector<std::string> errors;         // one line per skipped library
};

// Opens every *.so in `dir` to read its descriptor (no GL involved) and closes it again; a library
// this process already read, unchanged since (same time and size, settled), is not opened again. An id
// claimed by two libraries is refused for both, with an error naming both files. A library claiming
// one of `reservedIds` (the host's built-in techniques) is refused too.
PluginScan scanPlugins(const std::filesystem::path& dir, const std::vector<std::string>& reservedIds = {});

} // namespace shadowlab
