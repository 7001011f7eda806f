// Shader building with shared GLSL includes, and hot reload of GLSL files.
// Every program remembers the files it was built from; pollForChanges() rebuilds programs whose
// files changed. A failed rebuild keeps the previous program running and records the error
// (with file names and lines, not the driver's source-string numbers).
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gl/gl.h"
#include "shadowlab/technique.h"
#include "util/paths.h"

namespace shadowlab {

struct ShaderRequest {
    std::string vertexFile;
    std::string geometryFile;                       // optional
    std::string fragmentFile;                       // empty: depth-only program
    std::string computeFile;                        // a compute program has this stage alone
    std::string defines;                            // "NAME VALUE;NAME2 VALUE2"
    std::vector<std::filesystem::path> searchPaths; // for the stage files and #include "..."
    std::map<std::string, std::filesystem::path> aliases; // include name -> file (technique GLSL)
    std::string label;                              // for logs and KHR_debug
};

// A host program's request: stages found in the host's shader folders (hostShaderPaths()).
// An empty fragment file makes a depth-only program.
inline ShaderRequest hostShaderRequest(std::string vertexFile, std::string fragmentFile, std::string label) {
    ShaderRequest request;
    request.vertexFile = std::move(vertexFile);
    request.fragmentFile = std::move(fragmentFile);
    request.searchPaths = hostShaderPaths();
    request.label = std::move(label);
    return request;
}

class ShaderLibrary {
public:
    ShaderLibrary() = default;
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    // Builds now; returns 0 and an error naming file and line on failure.
    ProgramId build(const ShaderRequest& request, std::string& error);
    GLuint program(ProgramId id) const;
    void release(ProgramId id);
    // Checks file times (at most every `interval`); rebuilds changed programs. Returns the number
    // of programs rebuilt successfully; failures are logged and kept in lastReloadError().
    int pollForChanges(std::chrono::milliseconds interval = std::chrono::milliseconds(200));
    const std::string& lastReloadError() const { return lastReloadError_; }
    uint64_t reloadCount() const { return reloadCount_; }

private:
    struct Dependency {
        std::filesystem::path file;
        std::filesystem::file_time_type time;
    };
    struct Entry {
        ShaderRequest request;
        GlProgram program;
        std::vector<Dependency> dependencies;
    };
    GLuint compileAndLink(const ShaderRequest& request, std::vector<Dependency>& dependencies, std::string& error);

    std::map<ProgramId, Entry> entries_;
    ProgramId nextId_ = 1;
    std::chrono::steady_clock::time_point lastPoll_{};
    std::string lastReloadError_;
    uint64_t reloadCount_ = 0;
};

} // namespace shadowlab
