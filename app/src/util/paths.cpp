// Run-time file locations (see paths.h).
#include "util/paths.h"

#include <cstdlib>
#include <system_error>

namespace shadowlab {

std::filesystem::path executableDir() {
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::filesystem::current_path() : exe.parent_path();
}

std::filesystem::path pluginDir() {
    if (const char* dir = std::getenv("SHADOWLAB_PLUGIN_DIR"); dir && *dir) return dir;
    return executableDir() / "plugins";
}

std::filesystem::path dataRoot() {
    if (const char* dir = std::getenv("SHADOWLAB_DATA_DIR"); dir && *dir) return dir;
    const std::filesystem::path source = SHADOWLAB_SOURCE_DIR;
    std::error_code ec;
    if (std::filesystem::exists(source / "shaders" / "common.glsl", ec)) return source;
    return executableDir();
}

} // namespace shadowlab
