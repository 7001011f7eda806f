// Wavefront OBJ meshes through tinyobjloader: all shapes merged into one triangle mesh, the file's
// normals used when every corner has one, otherwise smooth area-weighted normals generated.
// Materials in the OBJ are not used (the scene file assigns one), so a missing .mtl or texture
// only warns. Anything that would give a wrong mesh throws a SceneError naming the file and line.
#include <array>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include <tiny_obj_loader.h>

#include "scene/scene.h"

namespace shadowlab {
namespace {

// tinyobj reports "... line 12 ..." inside its messages; 0 when there is no line number.
int lineNumberIn(const std::string& message) {
    const size_t at = message.find("line ");
    if (at == std::string::npos) return 0;
    return std::atoi(message.c_str() + at + 5);
}

std::string firstLine(const std::string& text) {
    const size_t end = text.find('\n');
    return end == std::string::npos ? text : text.substr(0, end);
}

// tinyobj only warns (with the last line of the file) when a face refers to a vertex that does
// not exist, so the offending face is found here: the first `f` line with an index out of range.
// Positive indices count from the start of the file, negative ones back from the current line.
std::string describeBadFace(const std::filesystem::path& path) {
    std::ifstream file(path);
    std::vector<std::string> lines;
    std::array<long, 3> totals{};   // v, vt, vn
    for (std::string line; std::getline(file, line);) {
        if (line.rfind("v ", 0) == 0) ++totals[0];
        else if (line.rfind("vt ", 0) == 0) ++totals[1];
        else if (line.rfind("vn ", 0) == 0) ++totals[2];
        lines.push_back(std::move(line));
    }
    const char* kinds[] = {"vertex", "texture coordinate", "normal"};
    std::array<long, 3> seen{};
    for (size_t number = 0; number < lines.size(); ++number) {
        const std::string& line = lines[number];
        if (line.rfind("v ", 0) == 0) ++seen[0];
        else if (line.rfind("vt ", 0) == 0) ++seen[1];
        else if (line.rfind("vn ", 0) == 0) ++seen[2];
        if (line.rfind("f ", 0) != 0) continue;
        std::istringstream corners(line.substr(2));
        for (std::string corner; corners >> corner;) {
            std::istringstream parts(corner);
            std::string part;
            for (int kind = 0; kind < 3 && std::getline(parts, part, '/'); ++kind) {
                if (part.empty()) continue;
                const long index = std::atol(part.c_str());
                const bool valid = index > 0 ? index <= totals[kind] : seen[kind] + index >= 0;
                if (!valid) {
                    return path.string() + ":" + std::to_string(number + 1) + ": face refers to " +
                           kinds[kind] + " " + std::to_string(index) + " but the file has " +
                           std::to_string(totals[kind]) + " (index out of range)";
                }
            }
        }
    }
    return path.string() + ": a face refers to a vertex that does not exist (index out of range)";
}

} // namespace

Mesh loadObj(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        throw SceneError(file + ": cannot open OBJ file (no such file)");
    }

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    if (!reader.ParseFromFile(file, config)) {
        const std::string message = firstLine(reader.Error());
        const int line = lineNumberIn(message);
        throw SceneError(file + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                         ": OBJ parse error: " + message);
    }

    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const int positionCount = static_cast<int>(attrib.vertices.size() / 3);
    const int normalCount = static_cast<int>(attrib.normals.size() / 3);
    const int uvCount = static_cast<int>(attrib.texcoords.size() / 2);
    bool everyCornerHasNormal = normalCount > 0;
    size_t cornerCount = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            const bool badPosition = corner.vertex_index < 0 || corner.vertex_index >= positionCount;
            const bool badNormal = corner.normal_index < -1 || corner.normal_index >= normalCount;
            const bool badUv = corner.texcoord_index < -1 || corner.texcoord_index >= uvCount;
            if (badPosition || badNormal || badUv) throw SceneError(describeBadFace(path));
            everyCornerHasNormal = everyCornerHasNormal && corner.normal_index >= 0;
        }
        cornerCount += shape.mesh.indices.size();
    }
    if (cornerCount == 0) throw SceneError(file + ": no faces (a scene object needs triangles)");

    // Checked above, so the remaining warnings are about materials and the like: not fatal.
    std::istringstream warnings(reader.Warning());
    for (std::string warning; std::getline(warnings, warning);) {
        if (!warning.empty()) std::cerr << file << ": warning: " << warning << "\n";
    }
    if (normalCount > 0 && !everyCornerHasNormal) {
        std::cerr << file << ": warning: some faces have no normals; generating smooth normals for all\n";
    }

    // One vertex per distinct (position, normal, uv) corner. Without usable file normals the normal
    // index is left out of the key so that generateNormals sees shared corners.
    Mesh mesh;
    std::map<std::array<int, 3>, uint32_t> vertexOfCorner;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            const std::array<int, 3> key{corner.vertex_index, everyCornerHasNormal ? corner.normal_index : -1,
                                         corner.texcoord_index};
            auto [found, inserted] = vertexOfCorner.try_emplace(key, static_cast<uint32_t>(mesh.vertices.size()));
            if (inserted) {
                Vertex vertex{};
                const size_t p = 3 * static_cast<size_t>(corner.vertex_index);
                vertex.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
                if (everyCornerHasNormal) {
                    const size_t n = 3 * static_cast<size_t>(corner.normal_index);
                    const glm::vec3 normal{attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]};
                    const float length = glm::length(normal);
                    vertex.normal = length > 0.0f ? normal / length : glm::vec3(0.0f, 1.0f, 0.0f);
                }
                if (corner.texcoord_index >= 0) {
                    const size_t t = 2 * static_cast<size_t>(corner.texcoord_index);
                    vertex.uv = {attrib.texcoords[t], attrib.texcoords[t + 1]};
                }
                mesh.vertices.push_back(vertex);
            }
            mesh.indices.push_back(found->second);
        }
    }
    if (!everyCornerHasNormal) generateNormals(mesh);
    return mesh;
}

void generateNormals(Mesh& mesh) {
    // Vertices at the same position share one normal, so uv seams do not show as creases. The
    // unnormalised cross product is twice the triangle's area: large faces weigh more than slivers.
    std::map<std::array<float, 3>, uint32_t> groupOfPosition;
    std::vector<uint32_t> groupOfVertex(mesh.vertices.size());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::vec3& p = mesh.vertices[i].position;
        auto found = groupOfPosition.try_emplace({p.x, p.y, p.z}, static_cast<uint32_t>(groupOfPosition.size()));
        groupOfVertex[i] = found.first->second;
    }
    std::vector<glm::vec3> sums(groupOfPosition.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 areaNormal = glm::cross(mesh.vertices[b].position - mesh.vertices[a].position,
                                                mesh.vertices[c].position - mesh.vertices[a].position);
        for (uint32_t corner : {a, b, c}) sums[groupOfVertex[corner]] += areaNormal;
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::vec3 sum = sums[groupOfVertex[i]];
        const float length = glm::length(sum);
        // A vertex of degenerate triangles only still needs a unit normal for lighting.
        mesh.vertices[i].normal = length > 0.0f ? sum / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

} // namespace shadowlab
