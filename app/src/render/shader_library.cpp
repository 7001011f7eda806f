// Shader building (see shader_library.h).
#include "render/shader_library.h"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "util/log.h"

namespace shadowlab {
namespace {

std::filesystem::file_time_type fileTime(const std::filesystem::path& file) {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(file, ec);
    return ec ? std::filesystem::file_time_type::min() : time;
}

// Expands #include "name" recursively (each file once), emitting #line directives whose source
// number indexes `files`, so compile logs can be mapped back to file names.
class Preprocessor {
public:
    Preprocessor(const ShaderRequest& request) : request_(request) {}

    bool expand(const std::filesystem::path& file, std::string& out, std::string& error) {
        if (!included_.insert(file).second) return true;
        std::ifstream in(file);
        if (!in) {
            error = file.string() + ": cannot open shader file";
            return false;
        }
        const int index = int(files.size());
        files.push_back(file);
        out += "#line 1 " + std::to_string(index) + "\n";
        std::string line;
        int lineNumber = 0;
        static const std::regex includePattern(R"(^\s*#\s*include\s+"([^"]+)\"\s*(//.*)?$)");
        // Headers shared with C++ (shadowlab/kit/shared.h) include system headers under
        // #ifdef __cplusplus; GLSL has none, so those lines are dropped before the driver sees them.
        static const std::regex systemIncludePattern(R"(^\s*#\s*include\s+<[^>]+>\s*$)");
        while (std::getline(in, line)) {
            ++lineNumber;
            std::smatch match;
            if (std::regex_match(line, systemIncludePattern)) {
                out += '\n';
            } else if (std::regex_match(line, match, includePattern)) {
                const auto resolved = resolve(match[1].str(), file.parent_path());
                if (resolved.empty()) {
                    error = file.string() + ":" + std::to_string(lineNumber) + ": cannot find include \"" +
                            match[1].str() + "\"";
                    return false;
                }
                if (!expand(resolved, out, error)) return false;
                out += "#line " + std::to_string(lineNumber + 1) + " " + std::to_string(index) + "\n";
            } else {
                out += line;
                out += '\n';
            }
        }
        return true;
    }

    std::filesystem::path resolve(const std::string& name, const std::filesystem::path& besides) const {
        if (auto alias = request_.aliases.find(name); alias != request_.aliases.end()) return alias->second;
        std::error_code ec;
        if (!besides.empty() && std::filesystem::exists(besides / name, ec)) return besides / name;
        for (const auto& dir : request_.searchPaths)
            if (std::filesystem::exists(dir / name, ec)) return dir / name;
        return {};
    }

    std::vector<std::filesystem::path> files;

private:
    const ShaderRequest& request_;
    std::set<std::filesystem::path> included_;
};

// Rewrites "0:12(5): error" (Mesa) and "0(12) : error" (NVIDIA) into "file.glsl:12: error".
std::string mapLog(const std::string& log, const std::vector<std::filesystem::path>& files) {
    static const std::regex location(R"((^|\n)\s*(\d+)(?::(\d+)|\((\d+)\))(?:\(\d+\))?\s*:?)");
    std::string out;
    auto begin = log.cbegin();
    std::smatch match;
    while (std::regex_search(begin, log.cend(), match, location)) {
        out.append(begin, match[0].first);
        const size_t index = std::stoul(match[2].str());
        const std::string line = match[3].matched ? match[3].str() : match[4].str();
        out += match[1].str();
        out += (index < files.size() ? files[index].string() : "source " + match[2].str()) + ":" + line + ":";
        begin = match[0].second;
    }
    out.append(begin, log.cend());
    while (!out.empty() && (out.back() == '\n' || out.back() == '\0')) out.pop_back();
    return out;
}

GLuint compileStage(GLenum stage, const std::string& source, const std::vector<std::filesystem::path>& files,
                    std::string& error) {
    const GLuint shader = glCreateShader(stage);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        error = mapLog(log, files);
        glDeleteShader(shader);
        return 0;
    }
    return shader;
}

std::string defineBlock(const std::string& defines) {
    std::string out;
    std::stringstream in(defines);
    std::string item;
    while (std::getline(in, item, ';'))
        if (!item.empty()) out += "#define " + item + "\n";
    return out;
}

} // namespace

GLuint ShaderLibrary::compileAndLink(const ShaderRequest& request, std::vector<Dependency>& dependencies,
                                     std::string& error) {
    const std::string header = "#version 450 core\n" + defineBlock(request.defines);
    std::vector<GLuint> shaders;
    std::vector<std::filesystem::path> allFiles;
    auto cleanup = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    const std::pair<GLenum, std::string> stages[] = {{GL_VERTEX_SHADER, request.vertexFile},
                                                     {GL_GEOMETRY_SHADER, request.geometryFile},
                                                     {GL_FRAGMENT_SHADER, request.fragmentFile},
                                                     {GL_COMPUTE_SHADER, request.computeFile}};
    if (!request.computeFile.empty() && !(request.vertexFile.empty() && request.geometryFile.empty() && request.fragmentFile.empty())) {
        error = (request.label.empty() ? "" : request.label + ": ") + "a compute program has no other stage";
        return 0;
    }
    if (request.computeFile.empty() && request.vertexFile.empty()) {
        error = (request.label.empty() ? "" : request.label + ": ") + "a program needs a vertex or a compute stage";
        return 0;
    }
    for (const auto& [stage, name] : stages) {
        if (name.empty()) continue;
        Preprocessor pre(request);
        const auto file = pre.resolve(name, {});
        if (file.empty()) {
            error = (request.label.empty() ? "" : request.label + ": ") + "cannot find shader file '" + name + "'";
            cleanup();
            return 0;
        }
        std::string source = header;
        if (!pre.expand(file, source, error)) {
            cleanup();
            return 0;
        }
        allFiles.insert(allFiles.end(), pre.files.begin(), pre.files.end());
        const GLuint shader = compileStage(stage, source, pre.files, error);
        if (!shader) {
            cleanup();
            return 0;
        }
        shaders.push_back(shader);
    }
    const GLuint program = glCreateProgram();
    for (GLuint s : shaders) glAttachShader(program, s);
    glLinkProgram(program);
    for (GLuint s : shaders) glDetachShader(program, s);
    cleanup();
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        error = (request.label.empty() ? "" : request.label + ": ") + "link failed: " + mapLog(log, allFiles);
        glDeleteProgram(program);
        return 0;
    }
    if (!request.label.empty()) glObjectLabel(GL_PROGRAM, program, GLsizei(request.label.size()), request.label.c_str());
    dependencies.clear();
    std::set<std::filesystem::path> unique(allFiles.begin(), allFiles.end());
    for (const auto& f : unique) dependencies.push_back({f, fileTime(f)});
    return program;
}

ProgramId ShaderLibrary::build(const ShaderRequest& request, std::string& error) {
    Entry entry;
    entry.request = request;
    const GLuint program = compileAndLink(request, entry.dependencies, error);
    if (!program) return 0;
    entry.program.reset(program);
    const ProgramId id = nextId_++;
    entries_.emplace(id, std::move(entry));
    return id;
}

GLuint ShaderLibrary::program(ProgramId id) const {
    const auto it = entries_.find(id);
    return it == entries_.end() ? 0 : it->second.program.get();
}

void ShaderLibrary::release(ProgramId id) { entries_.erase(id); }

int ShaderLibrary::pollForChanges(std::chrono::milliseconds interval) {
    const auto now = std::chrono::steady_clock::now();
    if (now - lastPoll_ < interval) return 0;
    lastPoll_ = now;
    int rebuilt = 0;
    for (auto& [id, entry] : entries_) {
        bool changed = false;
        for (auto& dep : entry.dependencies)
            if (fileTime(dep.file) != dep.time) changed = true;
        if (!changed) continue;
        std::vector<Dependency> dependencies;
        std::string error;
        const GLuint program = compileAndLink(entry.request, dependencies, error);
        if (!program) {
            // Keep the old program; remember the new times so the error is reported once per save.
            for (auto& dep : entry.dependencies) dep.time = fileTime(dep.file);
            lastReloadError_ = error;
            logError("shader reload failed, keeping the previous program: " + error);
            continue;
        }
        entry.program.reset(program);
        entry.dependencies = std::move(dependencies);
        lastReloadError_.clear();
        ++reloadCount_;
        ++rebuilt;
        logInfo("shader reloaded: " + entry.request.label);
    }
    return rebuilt;
}

} // namespace shadowlab
