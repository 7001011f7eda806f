// Wavefront OBJ meshes: all groups merged into one triangle mesh, the file's normals used when
// every corner has one, otherwise smooth area-weighted normals generated.
//
// A reader of its own rather than tinyobjloader, because a mesh loader is fed files from anywhere:
//   - only `v`, `vt`, `vn` and `f` are read; `mtllib` is never opened (materials come from the
//     scene file), so `mtllib /dev/zero` or a FIFO cannot exhaust memory or block;
//   - every index is parsed as a 64-bit number and checked, so 4294967297 is out of range rather
//     than vertex 1 after wrapping;
//   - polygons are triangulated in linear time when convex (a fan), by ear clipping in O(n^2)
//     otherwise, and have at most kMaxPolygonCorners corners: no file takes quadratic time in its
//     size;
//   - one pass over the text, so the time is linear in the file (bounded by the budget's file size).
// Anything that would give a wrong mesh throws a SceneError naming the file and line.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <iostream>
#include <limits>
#include <string_view>

#include "scene/scene.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

// Indices are checked to fit 32 bits as they are read; 12 bytes a corner keeps a file's worst
// case (every two bytes a corner) at six times its size.
struct Corner {
    int32_t position = -1;   // 0-based once resolved
    int32_t uv = -1;         // -1: none
    int32_t normal = -1;
};

struct Face {
    uint32_t firstCorner;
    uint32_t cornerCount;
    size_t line;
};

class ObjParser {
public:
    ObjParser(std::string source, const SceneBudget& budget) : source_(std::move(source)), budget_(budget) {}

    [[noreturn]] void fail(const std::string& problem) const {
        throw SceneError(source_ + ":" + std::to_string(line_) + ": " + problem);
    }

    void parse(std::string_view text) {
        size_t start = 0;
        while (start < text.size()) {
            size_t end = text.find('\n', start);
            if (end == std::string_view::npos) end = text.size();
            ++line_;
            parseLine(text.substr(start, end - start));
            start = end + 1;
        }
    }

    Mesh finish();

private:
    static bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

    // The next whitespace-separated token of `rest`, consumed; empty at the end of the line.
    static std::string_view token(std::string_view& rest) {
        size_t begin = 0;
        while (begin < rest.size() && isSpace(rest[begin])) ++begin;
        size_t end = begin;
        while (end < rest.size() && !isSpace(rest[end])) ++end;
        const std::string_view word = rest.substr(begin, end - begin);
        rest.remove_prefix(end);
        return word;
    }

    float number(std::string_view word) const {
        if (!word.empty() && word.front() == '+') word.remove_prefix(1);
        double value = 0.0;
        const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
        if (word.empty() || result.ec != std::errc() || result.ptr != word.data() + word.size() ||
            !(std::abs(value) <= double(std::numeric_limits<float>::max()))) {
            fail("OBJ parse error: '" + std::string(word.substr(0, 40)) + "' is not a finite number");
        }
        return static_cast<float>(value);
    }

    // Reads up to `count` numbers into `out`; at least `required` must be there.
    template <size_t N>
    void numbers(std::string_view rest, std::array<float, N>& out, size_t required, const char* what) const {
        size_t read = 0;
        for (; read < N; ++read) {
            const std::string_view word = token(rest);
            if (word.empty()) break;
            out[read] = number(word);
        }
        if (read < required) fail("OBJ parse error: " + std::string(what) + " needs " + std::to_string(required) + " numbers");
    }

    // One index of a corner ("7", "-2"): resolved to 0-based; `count` is how many exist so far
    // (negative indices count back from there). Positive ones are checked at the end of the file.
    int32_t index(std::string_view word, int64_t count, const char* kind) const {
        int64_t value = 0;
        const auto result = std::from_chars(word.data(), word.data() + word.size(), value);
        if (word.empty() || result.ptr != word.data() + word.size()) {
            fail("OBJ parse error: '" + std::string(word.substr(0, 40)) + "' is not a " + kind + " index");
        }
        if (result.ec == std::errc::result_out_of_range || value > int64_t(INT32_MAX) || value < -int64_t(INT32_MAX)) {
            fail("face refers to " + std::string(kind) + " " + std::string(word.substr(0, 40)) + " (index out of range)");
        }
        if (value == 0) fail("OBJ parse error: " + std::string(kind) + " index 0 is invalid (OBJ indices start at 1)");
        if (value < 0) {
            if (count + value < 0) {
                fail("face refers to " + std::string(kind) + " " + std::to_string(value) + " but only " +
                     std::to_string(count) + " come before it (index out of range)");
            }
            return static_cast<int32_t>(count + value);
        }
        return static_cast<int32_t>(value - 1);
    }

    void parseLine(std::string_view rest) {
        const std::string_view keyword = token(rest);
        if (keyword == "v") {
            std::array<float, 3> p{};
            numbers(rest, p, 3, "a vertex");   // a w or vertex colours after x y z are ignored
            positions_.push_back({p[0], p[1], p[2]});
        } else if (keyword == "vt") {
            std::array<float, 2> t{};
            numbers(rest, t, 1, "a texture coordinate");
            uvs_.push_back({t[0], t[1]});
        } else if (keyword == "vn") {
            std::array<float, 3> n{};
            numbers(rest, n, 3, "a normal");
            normals_.push_back({n[0], n[1], n[2]});
        } else if (keyword == "f") {
            Face face{static_cast<uint32_t>(corners_.size()), 0, line_};
            for (std::string_view word = token(rest); !word.empty(); word = token(rest)) {
                if (++face.cornerCount > kMaxPolygonCorners) {
                    fail("a face with more than " + std::to_string(kMaxPolygonCorners) +
                         " corners (triangulate it before export)");
                }
                Corner corner;
                const size_t slash = word.find('/');
                corner.position = index(word.substr(0, slash), int64_t(positions_.size()), "vertex");
                if (slash != std::string_view::npos) {
                    const std::string_view tail = word.substr(slash + 1);
                    const size_t second = tail.find('/');
                    const std::string_view uv = tail.substr(0, second);
                    if (!uv.empty()) corner.uv = index(uv, int64_t(uvs_.size()), "texture coordinate");
                    if (second != std::string_view::npos) {
                        const std::string_view normal = tail.substr(second + 1);
                        if (!normal.empty()) corner.normal = index(normal, int64_t(normals_.size()), "normal");
                    }
                }
                corners_.push_back(corner);
                if (corners_.size() > size_t(UINT32_MAX)) fail("more face corners than a mesh can index");
            }
            if (face.cornerCount < 3) fail("OBJ parse error: a face needs at least 3 corners");
            // The budget while reading: the triangles this file adds, before they are stored.
            triangles_ += face.cornerCount - 2;
            if (triangles_ > budget_.triangles) {
                fail("more than " + std::to_string(budget_.triangles) +
                     " triangles, the scene budget; raise it with --budget triangles=N");
            }
            if (3 * triangles_ > uint64_t(UINT32_MAX)) fail("more triangles than a mesh can index (2^32 indices)");
            faces_.push_back(face);
        }
        // Everything else (comments, o, g, s, usemtl, mtllib, l, p, curves) is not needed.
    }

    void triangulate(const Face& face, std::vector<uint32_t>& triangles) const;

    std::string source_;
    const SceneBudget& budget_;
    uint64_t triangles_ = 0;
    size_t line_ = 0;
    std::vector<glm::vec3> positions_, normals_;
    std::vector<glm::vec2> uvs_;
    std::vector<Corner> corners_;
    std::vector<Face> faces_;
};

float cross2(glm::vec2 a, glm::vec2 b, glm::vec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

// Strictly inside the counter-clockwise triangle abc.
bool insideTriangle(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return cross2(a, b, p) > 0.0f && cross2(b, c, p) > 0.0f && cross2(c, a, p) > 0.0f;
}

// Appends the corners (indices into corners_, relative to face.firstCorner) of face's triangles,
// keeping the polygon's winding.
void ObjParser::triangulate(const Face& face, std::vector<uint32_t>& triangles) const {
    const uint32_t n = face.cornerCount;
    auto point = [&](uint32_t i) { return positions_[size_t(corners_[face.firstCorner + i].position)]; };
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) { triangles.insert(triangles.end(), {a, b, c}); };
    if (n == 3) {
        emit(0, 1, 2);
        return;
    }
    // Newell's normal of the polygon: robust for non-planar and nearly degenerate ones.
    glm::vec3 normal(0.0f);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec3 a = point(i), b = point((i + 1) % n);
        normal += glm::vec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    }
    bool convex = true;
    for (uint32_t i = 0; i < n && convex; ++i) {
        const glm::vec3 a = point((i + n - 1) % n), b = point(i), c = point((i + 1) % n);
        convex = glm::dot(glm::cross(b - a, c - b), normal) >= 0.0f;
    }
    if (convex || !(glm::length(normal) > 0.0f)) {
        if (n == 4 && glm::length(point(0) - point(2)) > glm::length(point(1) - point(3))) {
            emit(0, 1, 3);   // the shorter diagonal, as modelling tools split quads
            emit(1, 2, 3);
            return;
        }
        for (uint32_t i = 1; i + 1 < n; ++i) emit(0, i, i + 1);
        return;
    }

    // Ear clipping in the plane of the polygon (the axis the normal is largest along dropped, the
    // projection oriented so the polygon runs counter-clockwise). Ear flags are cached and only
    // the two neighbours of a clipped corner are tested again: O(n^2) for n corners.
    const int axis = std::abs(normal.x) > std::abs(normal.y) ? (std::abs(normal.x) > std::abs(normal.z) ? 0 : 2)
                                                             : (std::abs(normal.y) > std::abs(normal.z) ? 1 : 2);
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const bool flip = normal[axis] < 0.0f;
    std::vector<glm::vec2> flat(n);
    for (uint32_t i = 0; i < n; ++i) {
        const glm::vec3 p = point(i);
        flat[i] = flip ? glm::vec2(p[v], p[u]) : glm::vec2(p[u], p[v]);
    }
    std::vector<uint32_t> prev(n), next(n);
    for (uint32_t i = 0; i < n; ++i) {
        prev[i] = (i + n - 1) % n;
        next[i] = (i + 1) % n;
    }
    uint32_t remaining = n;
    auto isEar = [&](uint32_t i) {
        const glm::vec2 a = flat[prev[i]], b = flat[i], c = flat[next[i]];
        if (cross2(a, b, c) <= 0.0f) return false;   // reflex or flat
        for (uint32_t j = next[next[i]]; j != prev[i]; j = next[j]) {
            const glm::vec2 p = flat[j];
            if (p == a || p == b || p == c) continue;
            if (insideTriangle(p, a, b, c)) return false;
        }
        return true;
    };
    std::vector<char> ear(n);
    for (uint32_t i = 0; i < n; ++i) ear[i] = isEar(i);
    uint32_t current = 0;
    while (remaining > 3) {
        uint32_t steps = 0;
        while (!ear[current] && steps < remaining) {
            current = next[current];
            ++steps;
        }
        // No ear in a whole round: a self-intersecting or degenerate polygon; clip anyway.
        const uint32_t a = prev[current], c = next[current];
        emit(a, current, c);
        next[a] = c;
        prev[c] = a;
        --remaining;
        ear[a] = isEar(a);
        ear[c] = isEar(c);
        current = c;
    }
    emit(prev[current], current, next[current]);
}

Mesh ObjParser::finish() {
    // Positive indices may refer forward; every one is known now. The first bad face is reported.
    for (const Face& face : faces_) {
        for (uint32_t k = 0; k < face.cornerCount; ++k) {
            const Corner& corner = corners_[face.firstCorner + k];
            const std::pair<int64_t, size_t> checks[] = {
                {corner.position, positions_.size()}, {corner.uv, uvs_.size()}, {corner.normal, normals_.size()}};
            const char* kinds[] = {"vertex", "texture coordinate", "normal"};
            for (int kind = 0; kind < 3; ++kind) {
                const auto [index, total] = checks[kind];
                if (kind > 0 && index < 0) continue;
                if (index >= int64_t(total)) {
                    line_ = face.line;
                    fail(std::string("face refers to ") + kinds[kind] + " " + std::to_string(index + 1) +
                         " but the file has " + std::to_string(total) + " (index out of range)");
                }
            }
        }
    }
    if (faces_.empty()) throw SceneError(source_ + ": no faces (a scene object needs triangles)");

    bool everyCornerHasNormal = !normals_.empty();
    for (const Corner& corner : corners_) everyCornerHasNormal = everyCornerHasNormal && corner.normal >= 0;
    if (!normals_.empty() && !everyCornerHasNormal) {
        std::cerr << source_ << ": warning: some faces have no normals; generating smooth normals for all\n";
    }

    // One vertex per distinct (position, normal, uv) corner. Without usable file normals the normal
    // index is left out of the key so that generateNormals sees shared corners. Distinct corners
    // are found by sorting (16 bytes a corner, no hash table), in order of first use.
    struct Use {
        std::array<int32_t, 3> key;
        uint32_t order;   // position in the triangle list
    };
    std::vector<Use> uses;
    uses.reserve(size_t(triangles_) * 3);
    std::vector<uint32_t> corners;
    for (const Face& face : faces_) {
        corners.clear();
        triangulate(face, corners);
        for (uint32_t k : corners) {
            const Corner& corner = corners_[face.firstCorner + k];
            uses.push_back({{corner.position, everyCornerHasNormal ? corner.normal : -1, corner.uv}, uint32_t(uses.size())});
        }
    }
    corners_ = {};   // no longer needed: give the memory back before the mesh is built
    std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) {
        return a.key != b.key ? a.key < b.key : a.order < b.order;
    });
    Mesh mesh;
    mesh.indices.resize(uses.size());
    std::vector<std::pair<uint32_t, std::array<int32_t, 3>>> firsts;   // first use of each distinct corner
    for (size_t i = 0; i < uses.size(); ++i)
        if (i == 0 || uses[i].key != uses[i - 1].key) firsts.push_back({uses[i].order, uses[i].key});
    const uint64_t bytes = firsts.size() * sizeof(Vertex) + uses.size() * sizeof(uint32_t);
    if (bytes > budget_.gpuBytes) {
        throw SceneError(source_ + ": " + std::to_string(firsts.size()) + " vertices and " + std::to_string(uses.size() / 3) +
                         " triangles need more than the GPU memory budget; raise it with --budget gpu-mib=N");
    }
    std::sort(firsts.begin(), firsts.end());
    mesh.vertices.reserve(firsts.size());
    for (const auto& [order, key] : firsts) {
        Vertex vertex{};
        vertex.position = positions_[size_t(key[0])];
        if (everyCornerHasNormal) {
            const glm::vec3 normal = normals_[size_t(key[1])];
            const float length = glm::length(normal);
            vertex.normal = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0.0f, 1.0f, 0.0f);
        }
        if (key[2] >= 0) vertex.uv = uvs_[size_t(key[2])];
        mesh.vertices.push_back(vertex);
    }
    // Each use gets the vertex of its key: walk the uses sorted by key, finding each key's vertex
    // by its first use (firsts is sorted by that order now).
    for (size_t i = 0; i < uses.size();) {
        const auto found = std::lower_bound(firsts.begin(), firsts.end(), std::pair(uses[i].order, uses[i].key));
        const uint32_t vertex = static_cast<uint32_t>(found - firsts.begin());
        size_t j = i;
        for (; j < uses.size() && uses[j].key == uses[i].key; ++j) mesh.indices[uses[j].order] = vertex;
        i = j;
    }
    if (!everyCornerHasNormal) generateNormals(mesh);
    return mesh;
}

} // namespace

Mesh parseObj(const std::string& text, const std::string& source, const SceneBudget& budget) {
    ObjParser parser(source, budget);
    parser.parse(text);
    return parser.finish();
}

Mesh loadObj(const std::filesystem::path& path, uint64_t maxFileBytes) {
    std::string text, error;
    if (!readRegularFile(path, size_t(std::min<uint64_t>(maxFileBytes, SIZE_MAX)), text, error, "OBJ file")) {
        if (error.find("larger than") != std::string::npos) error += "; raise it with --budget file-mib=N";
        throw SceneError(error);
    }
    return parseObj(text, path.string());
}

void generateNormals(Mesh& mesh) {
    // Vertices at the same position share one normal, so uv seams do not show as creases. The
    // unnormalised cross product is twice the triangle's area: large faces weigh more than slivers.
    // Positions are grouped by sorting vertex numbers by position (8 bytes a vertex, no tree).
    std::vector<uint32_t> byPosition(mesh.vertices.size());
    for (size_t i = 0; i < byPosition.size(); ++i) byPosition[i] = static_cast<uint32_t>(i);
    auto key = [&](uint32_t v) {
        const glm::vec3& p = mesh.vertices[v].position;
        return std::array<float, 3>{p.x, p.y, p.z};
    };
    std::sort(byPosition.begin(), byPosition.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    std::vector<uint32_t> groupOfVertex(mesh.vertices.size());
    uint32_t groups = 0;
    for (size_t i = 0; i < byPosition.size(); ++i) {
        if (i > 0 && key(byPosition[i - 1]) < key(byPosition[i])) ++groups;
        groupOfVertex[byPosition[i]] = groups;
    }
    if (!byPosition.empty()) ++groups;
    std::vector<glm::vec3> sums(groups, glm::vec3(0.0f));
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
        mesh.vertices[i].normal = length > 0.0f && std::isfinite(length) ? sum / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

} // namespace shadowlab
