// Where the program finds its run-time files.
//   plugins:  $SHADOWLAB_PLUGIN_DIR, else <exe dir>/plugins
//   GLSL:     $SHADOWLAB_DATA_DIR/{shaders,plugins/<id>}, else the source tree the binary was
//             built from (so editing a shader there hot-reloads), else <exe dir>.
#pragma once

#include <filesystem>

namespace shadowlab {

std::filesystem::path executableDir();
std::filesystem::path pluginDir();
std::filesystem::path dataRoot();
inline std::filesystem::path sharedShaderDir() { return dataRoot() / "shaders"; }
inline std::filesystem::path pluginSourceDir(const std::string& id) { return dataRoot() / "plugins" / id; }

} // namespace shadowlab
