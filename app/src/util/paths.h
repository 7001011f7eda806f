// Where the program finds its run-time files.
//   plugins:  $SHADOWLAB_PLUGIN_DIR, else <exe dir>/plugins
//   GLSL:     $SHADOWLAB_DATA_DIR/{shaders,plugins/<id>}, else the source tree the binary was
//             built from (so editing a shader there hot-reloads), else <exe dir>.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace shadowlab {

std::filesystem::path executableDir();
std::filesystem::path pluginDir();
std::filesystem::path dataRoot();
inline std::filesystem::path sharedShaderDir() { return dataRoot() / "shaders"; }
inline std::filesystem::path pluginSourceDir(const std::string& id) { return dataRoot() / "plugins" / id; }
// The public headers: GLSL includes the kit's shared C++/GLSL headers from here.
inline std::filesystem::path publicIncludeDir() { return dataRoot() / "app" / "include"; }
// Where every program looks for its files after its own folder.
inline std::vector<std::filesystem::path> hostShaderPaths() { return {sharedShaderDir(), publicIncludeDir()}; }

} // namespace shadowlab
