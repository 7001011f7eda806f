// Wavefront OBJ meshes: all groups merged into one triangle mesh, the file's normals used when
// every corner has one, otherwise smooth area-weighted normals generated.
//
// tinyobjloader parses (libtinyobjloader-dev 2.0.0~rc10, the design card's choice). It trusts its
// input, and a mesh loader is fed files from anywhere, so a linear pre-scan of ours validates the
// text first and decides what tinyobjloader sees:
//   - loadObj reads the file itself (util/text_file.h: regular files only, at most the budget's file
//     size) and tinyobjloader parses from memory, ObjReader::ParseFromString(text, "", config). That
//     path (tiny_obj_loader.h, ObjReader::ParseFromString) wraps both strings in std::stringbuf and
//     reads material libraries through MaterialStreamReader from the empty string: it never touches
//     the filesystem, so `mtllib /dev/zero` or a FIFO cannot exhaust memory or block. Besides, the
//     pre-scan hands tinyobjloader only the `v`, `vt`, `vn` and `f` lines it has checked: every other
//     line (mtllib, usemtl, o, g, s, l, p, curves, and tinyobjloader's extensions `t`, whose tag
//     counts allocate up to 3 x 8192 values a line, and `vw`, whose joint ids are cast to int
//     unchecked) becomes a comment. Materials come from the scene file.
//   - Lines end where tinyobjloader ends them (\n, \r or \r\n) and words are separated by its blanks
//     (space, tab), so both read the same lines, numbers and corners.
//   - Every index is parsed as a 64-bit number and checked: tinyobjloader reads them with atoi into
//     an int, so 4294967297 would become vertex 1. 0 is refused; negative (relative) indices are
//     resolved against what comes before the line, positive ones against the file's totals at its
//     end; corners tinyobjloader cannot read ("1/", "1//") are refused by name.
//   - Every number tinyobjloader reads (x y z and w or r g b of `v`, u v of `vt`, x y z of `vn`) must
//     be a finite float of at most kMaxNumberLength characters with an exponent of at most
//     kMaxExponent: tinyobjloader's own reader turns 1e400 into inf and 0e999 into nan, reads junk as
//     0, and overflows an int on exponents beyond 2^31. Within these limits it reads what
//     std::from_chars reads, to within rounding.
//   - Faces have 3 to kMaxPolygonCorners (255) corners, counted as they are read: tinyobjloader keeps
//     a face's corner count in an unsigned char, and triangulating a concave face takes n^2 steps, so
//     no file takes quadratic time in its size.
//   - The budget's triangles are counted while scanning, before tinyobjloader allocates anything;
//     its GPU bytes are checked before the vertices are built.
// Time is linear in the file. tinyobjloader's triangulation is off: it splits every quad along the
// shorter diagonal, which runs outside a concave quad (test RobustObj.ConcaveQuadsAreSplitInside);
// faces are triangulated here as before (a fan when convex, ear clipping otherwise). What
// tinyobjloader returns is checked against the pre-scan once more (counts, indices, finiteness);
// a difference would be a bug, reported as such (the fuzz target treats it as one).
// Anything that would give a wrong mesh throws a SceneError naming the file and line.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <iostream>
#include <limits>
#include <string_view>
#include <type_traits>

#include <tiny_obj_loader.h>

#include "scene/scene.h"
#include "util/progress.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

static_assert(std::is_same_v<tinyobj::real_t, float>, "libtinyobjloader is built with float (not TINYOBJLOADER_USE_DOUBLE)");

// Longest number and largest written exponent accepted: within them tinyobjloader's number reader
// (digits accumulated in a double, times 5^e, times 2^e) is accurate; a longer mantissa loses digits
// beyond 1e-308 (0.000...1e430 reads as 0) and 5^e overflows beyond e = 441 (0e500 reads as nan).
constexpr size_t kMaxNumberLength = 64;
constexpr int64_t kMaxExponent = 400;

enum Kind { kPosition, kUv, kNormal };
const char* const kKindNames[] = {"vertex", "texture coordinate", "normal"};
const char* const kKindKeywords[] = {"v", "vt", "vn"};

// tinyobjloader's IS_SPACE: the only separators within a line.
bool isBlank(char c) { return c == ' ' || c == '\t'; }

// The next blank-separated word of `rest`, consumed; empty at the end of the line.
std::string_view word(std::string_view& rest) {
    size_t begin = 0;
    while (begin < rest.size() && isBlank(rest[begin])) ++begin;
    size_t end = begin;
    while (end < rest.size() && !isBlank(rest[end])) ++end;
    const std::string_view found = rest.substr(begin, end - begin);
    rest.remove_prefix(end);
    return found;
}

// Calls f(number, begin, end) for every line of `text` as tinyobjloader's safeGetline splits it:
// at \n, \r or \r\n; a last line without an ending counts, an empty text has no line.
template <class F>
void forEachLine(std::string_view text, F&& f) {
    size_t number = 0;
    for (size_t begin = 0; begin < text.size();) {
        size_t end = text.find_first_of("\r\n", begin);
        if (end == std::string_view::npos) end = text.size();
        f(++number, begin, end);
        if (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ++end;
        begin = end + 1;
    }
}

// Does a word look like a number to tinyobjloader's reader (so that it goes on reading it)?
bool startsLikeNumber(std::string_view w) {
    return !w.empty() && (w[0] == '+' || w[0] == '-' || w[0] == '.' || (w[0] >= '0' && w[0] <= '9'));
}

// The checking pass. Runs over the text that tinyobjloader will parse, turning every line other
// than v, vt, vn and f into a comment; throws on the first problem, in file order.
class ObjPrescan {
public:
    ObjPrescan(const std::string& source, const SceneBudget& budget) : source_(source), budget_(budget) {}

    [[noreturn]] void fail(const std::string& problem) const {
        throw SceneError(source_ + ":" + std::to_string(line_) + ": " + problem);
    }

    void run(std::string& text) {
        forEachLine(text, [&](size_t number, size_t begin, size_t end) {
            line_ = number;
            scanLine(text, begin, end);
        });
        // Positive indices may refer forward; the totals are known now. Scanned once more only when
        // one is out of range, to name the first face that is (the lines blanked already stay so).
        bool outOfRange = false;
        for (int kind = 0; kind < 3; ++kind) outOfRange = outOfRange || largest_[kind] > totals_[kind];
        if (outOfRange) {
            finalTotals_ = totals_;
            totals_ = {};
            largest_ = {};
            triangles_ = corners_ = faces_ = 0;
            locating_ = true;
            forEachLine(text, [&](size_t number, size_t begin, size_t end) {
                line_ = number;
                scanLine(text, begin, end);
            });
        }
        if (faces_ == 0) throw SceneError(source_ + ": no faces (a scene object needs triangles)");
    }

    // The line of the `ordinal`-th (0-based) v, vt or vn line of the checked text, 0 if none.
    static size_t lineOf(std::string_view text, Kind kind, uint64_t ordinal) {
        size_t found = 0;
        uint64_t seen = 0;
        forEachLine(text, [&](size_t number, size_t begin, size_t end) {
            std::string_view rest = text.substr(begin, end - begin);
            if (found == 0 && word(rest) == kKindKeywords[kind] && seen++ == ordinal) found = number;
        });
        return found;
    }

    std::array<int64_t, 3> totals() const { return totals_; }
    uint64_t triangles() const { return triangles_; }
    uint64_t corners() const { return corners_; }
    uint64_t faces() const { return faces_; }

private:
    void scanLine(std::string& text, size_t begin, size_t end) {
        std::string_view rest(text.data() + begin, end - begin);
        size_t keywordAt = begin;
        while (keywordAt < end && isBlank(text[keywordAt])) ++keywordAt;
        const std::string_view keyword = word(rest);
        if (keyword.empty() || keyword.front() == '#') return;   // tinyobjloader skips these too
        if (keyword == "v") {
            numbers(rest, 3, 3, "a vertex");
            // Then w, or r g b (vertex colours, a tinyobjloader extension): tinyobjloader reads up to
            // three more words while they look like numbers; they are checked like x y z and not used.
            for (int i = 0; i < 3; ++i) {
                std::string_view next = rest;
                const std::string_view extra = word(next);
                if (!startsLikeNumber(extra)) break;
                number(extra);
                rest = next;
            }
            count(kPosition);
        } else if (keyword == "vt") {
            numbers(rest, 2, 1, "a texture coordinate");   // a w after u v is neither read nor used
            count(kUv);
        } else if (keyword == "vn") {
            numbers(rest, 3, 3, "a normal");
            count(kNormal);
        } else if (keyword == "f") {
            face(rest);
        } else {
            // Not needed (o, g, s, usemtl, mtllib, l, p, curves, t, vw, ...): a comment for tinyobjloader.
            text[keywordAt] = '#';
        }
    }

    void count(Kind kind) {
        // tinyobjloader counts and indexes them with int.
        if (++totals_[kind] > int64_t(INT32_MAX)) {
            fail("more than " + std::to_string(INT32_MAX) + " " + kKindNames[kind] + " lines");
        }
    }

    // A number as tinyobjloader reads it: [+-]digits[.digits][(e|E)[+-]digits], or a leading '.'.
    // std::from_chars reads the same grammar (but for a leading '+', inf and nan, handled here).
    void number(std::string_view w) const {
        const std::string shown(w.substr(0, 40));
        if (w.size() > kMaxNumberLength) {
            fail("OBJ parse error: '" + shown + "...' is longer than " + std::to_string(kMaxNumberLength) + " characters");
        }
        std::string_view digits = w;
        if (!digits.empty() && digits.front() == '+') digits.remove_prefix(1);   // from_chars takes no '+'
        double value = 0.0;
        const auto result = std::from_chars(digits.data(), digits.data() + digits.size(), value);
        if (digits.empty() || (digits.size() < w.size() && digits.front() == '-') || result.ec != std::errc() ||
            result.ptr != digits.data() + digits.size() || !(std::abs(value) <= double(std::numeric_limits<float>::max()))) {
            fail("OBJ parse error: '" + shown + "' is not a finite number");
        }
        const size_t e = digits.find_first_of("eE");
        if (e != std::string_view::npos) {
            std::string_view exponent = digits.substr(e + 1);
            if (!exponent.empty() && exponent.front() == '+') exponent.remove_prefix(1);
            int64_t written = 0;
            const auto parsed = std::from_chars(exponent.data(), exponent.data() + exponent.size(), written);
            if (parsed.ec != std::errc() || written > kMaxExponent || written < -kMaxExponent) {
                fail("OBJ parse error: '" + shown + "' has an exponent beyond +-" + std::to_string(kMaxExponent));
            }
        }
    }

    // Checks up to `most` numbers of `rest` (the words tinyobjloader reads); at least `required`.
    void numbers(std::string_view& rest, int most, int required, const char* what) const {
        int read = 0;
        for (; read < most; ++read) {
            std::string_view next = rest;
            const std::string_view w = word(next);
            if (w.empty()) break;
            number(w);
            rest = next;
        }
        if (read < required) {
            fail("OBJ parse error: " + std::string(what) + " needs " + std::to_string(required) + " number" +
                 (required == 1 ? "" : "s"));
        }
    }

    // One index of a corner ("7", "-2"), checked as tinyobjloader will resolve it: negative ones
    // against the count before this line, positive ones at the end of the file.
    void index(std::string_view w, Kind kind) {
        const char* name = kKindNames[kind];
        int64_t value = 0;
        const auto result = std::from_chars(w.data(), w.data() + w.size(), value);
        if (w.empty() || result.ptr != w.data() + w.size()) {
            fail("OBJ parse error: '" + std::string(w.substr(0, 40)) + "' is not a " + name + " index");
        }
        if (result.ec == std::errc::result_out_of_range || value > int64_t(INT32_MAX) || value < -int64_t(INT32_MAX)) {
            fail("face refers to " + std::string(name) + " " + std::string(w.substr(0, 40)) + " (index out of range)");
        }
        if (value == 0) fail("OBJ parse error: " + std::string(name) + " index 0 is invalid (OBJ indices start at 1)");
        if (value < 0 && totals_[kind] + value < 0) {
            fail("face refers to " + std::string(name) + " " + std::to_string(value) + " but only " +
                 std::to_string(totals_[kind]) + " come before it (index out of range)");
        }
        if (value > 0 && locating_ && value > finalTotals_[kind]) {
            fail("face refers to " + std::string(name) + " " + std::to_string(value) + " but the file has " +
                 std::to_string(finalTotals_[kind]) + " (index out of range)");
        }
        largest_[kind] = std::max(largest_[kind], value);
    }

    void face(std::string_view rest) {
        uint64_t cornerCount = 0;
        for (std::string_view corner = word(rest); !corner.empty(); corner = word(rest)) {
            if (++cornerCount > uint64_t(kMaxPolygonCorners)) {
                fail("a face with more than " + std::to_string(kMaxPolygonCorners) + " corners (triangulate it before export)");
            }
            // The forms tinyobjloader reads: v, v/t, v//n, v/t/n.
            const size_t slash = corner.find('/');
            index(corner.substr(0, slash), kPosition);
            if (slash == std::string_view::npos) continue;
            const std::string_view tail = corner.substr(slash + 1);
            const size_t second = tail.find('/');
            const std::string_view uv = tail.substr(0, second);
            if (second == std::string_view::npos || !uv.empty()) {
                if (uv.empty()) fail("OBJ parse error: corner '" + std::string(corner.substr(0, 40)) + "' has no texture coordinate index after '/'");
                index(uv, kUv);
            }
            if (second != std::string_view::npos) {
                const std::string_view normal = tail.substr(second + 1);
                if (normal.empty()) fail("OBJ parse error: corner '" + std::string(corner.substr(0, 40)) + "' has no normal index after '/'");
                index(normal, kNormal);
            }
        }
        if (cornerCount < 3) fail("OBJ parse error: a face needs at least 3 corners");
        // The budget while reading: the triangles this file adds, before anything is stored.
        triangles_ += cornerCount - 2;
        if (triangles_ > budget_.triangles) {
            fail("more than " + std::to_string(budget_.triangles) + " triangles, the scene budget; raise it with --budget triangles=N");
        }
        if (3 * triangles_ > uint64_t(UINT32_MAX)) fail("more triangles than a mesh can index (2^32 indices)");
        corners_ += cornerCount;
        if (corners_ > uint64_t(UINT32_MAX)) fail("more face corners than a mesh can index");
        ++faces_;
    }

    const std::string& source_;
    const SceneBudget& budget_;
    size_t line_ = 0;
    std::array<int64_t, 3> totals_{}, largest_{}, finalTotals_{};
    uint64_t triangles_ = 0, corners_ = 0, faces_ = 0;
    bool locating_ = false;
};

float cross2(glm::vec2 a, glm::vec2 b, glm::vec2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); }

// Strictly inside the counter-clockwise triangle abc.
bool insideTriangle(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    return cross2(a, b, p) > 0.0f && cross2(b, c, p) > 0.0f && cross2(c, a, p) > 0.0f;
}

// Appends the corners (0 to n - 1, indices into `face`) of the face's n - 2 triangles, keeping the
// polygon's winding. `positions` is tinyobjloader's x y z array.
void triangulate(const tinyobj::index_t* face, uint32_t n, const std::vector<float>& positions, std::vector<uint32_t>& triangles) {
    auto point = [&](uint32_t i) {
        const size_t p = 3 * size_t(face[i].vertex_index);
        return glm::vec3(positions[p], positions[p + 1], positions[p + 2]);
    };
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


// What tinyobjloader returned, checked against the pre-scan; nothing here should ever fire.
void checkAgreement(const tinyobj::ObjReader& reader, const ObjPrescan& scan, const std::string& text, const std::string& source) {
    auto differs = [&](const std::string& what, size_t line = 0) {
        throw SceneError(source + (line > 0 ? ":" + std::to_string(line) : std::string()) +
                         ": tinyobjloader read the file differently from the pre-scan (" + what + ")");
    };
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::array<const std::vector<float>*, 3> values = {&attrib.vertices, &attrib.texcoords, &attrib.normals};
    const size_t widths[] = {3, 2, 3};
    const auto totals = scan.totals();
    for (int kind = 0; kind < 3; ++kind) {
        if (values[kind]->size() != widths[kind] * size_t(totals[kind])) differs(std::string(kKindNames[kind]) + " count");
        for (size_t i = 0; i < values[kind]->size(); ++i) {
            if (!std::isfinite((*values[kind])[i])) {
                differs("a number that is not finite", ObjPrescan::lineOf(text, Kind(kind), i / widths[kind]));
            }
        }
    }
    uint64_t faces = 0, corners = 0;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        size_t first = 0;
        for (const unsigned char n : shape.mesh.num_face_vertices) {
            if (n < 3 || first + n > shape.mesh.indices.size()) differs("corners of a face");
            first += n;
        }
        if (first != shape.mesh.indices.size()) differs("corners of a face");
        for (const tinyobj::index_t& corner : shape.mesh.indices) {
            if (corner.vertex_index < 0 || corner.vertex_index >= totals[kPosition] || corner.texcoord_index < -1 ||
                corner.texcoord_index >= totals[kUv] || corner.normal_index < -1 || corner.normal_index >= totals[kNormal]) {
                differs("an index");
            }
        }
        faces += shape.mesh.num_face_vertices.size();
        corners += shape.mesh.indices.size();
    }
    if (faces != scan.faces() || corners != scan.corners()) differs("face count");
}

} // namespace

Mesh parseObj(const std::string& text, const std::string& source, const SceneBudget& budget) {
    // The pre-scan checks a copy, which is what tinyobjloader parses: the lines it does not need
    // turned into comments.
    std::string checked = text;
    ObjPrescan scan(source, budget);
    scan.run(checked);

    tinyobj::ObjReaderConfig config;
    config.triangulate = false;    // triangulated below
    config.vertex_color = false;   // no default colours for vertices without
    tinyobj::ObjReader reader;
    // From memory, with an empty material library: never opens a file (see the top of this file).
    if (!reader.ParseFromString(checked, /*mtl text*/ "", config)) {
        const std::string& error = reader.Error();
        throw SceneError(source + ": tinyobjloader read the file differently from the pre-scan (" +
                         error.substr(0, error.find('\n')) + ")");
    }
    checkAgreement(reader, scan, checked, source);
    checked = std::string();   // no longer needed: give the memory back before the mesh is built
    const tinyobj::attrib_t& attrib = reader.GetAttrib();
    const std::vector<tinyobj::shape_t>& shapes = reader.GetShapes();   // one: every g, o and usemtl is a comment

    bool everyCornerHasNormal = !attrib.normals.empty();
    for (const tinyobj::shape_t& shape : shapes)
        for (const tinyobj::index_t& corner : shape.mesh.indices) everyCornerHasNormal = everyCornerHasNormal && corner.normal_index >= 0;
    if (!attrib.normals.empty() && !everyCornerHasNormal) {
        std::cerr << source << ": warning: some faces have no normals; generating smooth normals for all\n";
    }

    // One vertex per distinct (position, normal, uv) corner. Without usable file normals the normal
    // index is left out of the key so that generateNormals sees shared corners. Distinct corners
    // are found by sorting (16 bytes a corner, no hash table), in order of first use.
    struct Use {
        std::array<int32_t, 3> key;
        uint32_t order;   // position in the triangle list
    };
    std::vector<Use> uses;
    uses.reserve(size_t(scan.triangles()) * 3);
    std::vector<uint32_t> corners;
    for (const tinyobj::shape_t& shape : shapes) {
        size_t first = 0;
        for (const unsigned char n : shape.mesh.num_face_vertices) {
            const tinyobj::index_t* face = shape.mesh.indices.data() + first;
            first += n;
            corners.clear();
            triangulate(face, n, attrib.vertices, corners);
            for (uint32_t k : corners) {
                const tinyobj::index_t& corner = face[k];
                uses.push_back({{corner.vertex_index, everyCornerHasNormal ? corner.normal_index : -1, corner.texcoord_index},
                                uint32_t(uses.size())});
            }
        }
    }
    std::sort(uses.begin(), uses.end(), [](const Use& a, const Use& b) {
        return a.key != b.key ? a.key < b.key : a.order < b.order;
    });
    Mesh mesh;
    mesh.indices.resize(uses.size());
    std::vector<std::pair<uint32_t, std::array<int32_t, 3>>> firsts;   // first use of each distinct corner
    for (size_t i = 0; i < uses.size(); ++i)
        if (i == 0 || uses[i].key != uses[i - 1].key) firsts.push_back({uses[i].order, uses[i].key});
    const uint64_t bytes = firsts.size() * sizeof(Vertex) + uses.size() * sizeof(uint32_t);
    if (bytes > budget.gpuBytes) {
        throw SceneError(source + ": " + std::to_string(firsts.size()) + " vertices and " + std::to_string(uses.size() / 3) +
                         " triangles need more than the GPU memory budget; raise it with --budget gpu-mib=N");
    }
    std::sort(firsts.begin(), firsts.end());
    mesh.vertices.reserve(firsts.size());
    for (const auto& [order, key] : firsts) {
        Vertex vertex{};
        const size_t p = 3 * size_t(key[0]);
        vertex.position = {attrib.vertices[p], attrib.vertices[p + 1], attrib.vertices[p + 2]};
        if (everyCornerHasNormal) {
            const size_t n = 3 * size_t(key[1]);
            const glm::vec3 normal{attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]};
            const float length = glm::length(normal);
            vertex.normal = length > 0.0f && std::isfinite(length) ? normal / length : glm::vec3(0.0f, 1.0f, 0.0f);
        }
        if (key[2] >= 0) {
            const size_t t = 2 * size_t(key[2]);
            vertex.uv = {attrib.texcoords[t], attrib.texcoords[t + 1]};
        }
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
    // Three passes (the sort is most of the time): their progress on a large mesh, and Ctrl-C.
    Progress progress("computing the normals of " + std::to_string(mesh.vertices.size()) + " vertices", 3, "passes");
    std::sort(byPosition.begin(), byPosition.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    progress.stepOrThrow(1);
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
    progress.stepOrThrow(2);
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        const glm::vec3 sum = sums[groupOfVertex[i]];
        const float length = glm::length(sum);
        // A vertex of degenerate triangles only still needs a unit normal for lighting.
        mesh.vertices[i].normal = length > 0.0f && std::isfinite(length) ? sum / length : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    progress.step(3);
}

} // namespace shadowlab
