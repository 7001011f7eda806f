// Procedural meshes for scenes: plane, box, sphere, capped cylinder, torus and a simple tree.
// All are in object space with y up, wound counter-clockwise seen from outside, with outward unit
// normals and uv in [0, 1]. Closed shapes are closed once seam vertices are welded by position
// (seams are duplicated only so that uv can wrap), so shadow volumes and back-face tricks work.
#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "util/progress.h"

namespace shadowlab {
namespace {

// A grid generator's progress: its vertex rows, then its index rows (util/progress.h; a 4096 x
// 4096 sphere takes seconds on its own). Ctrl-C throws Interrupted: a half-made mesh is no result.
class GridProgress {
public:
    GridProgress(const char* shape, int columns, int rows)
        : rows_(uint64_t(rows) + 1), progress_(std::string("generating a ") + shape + " of " + std::to_string(columns) + " x " +
                                                    std::to_string(rows),
                                                2 * uint64_t(rows) + 1, "rows") {}
    void vertexRow(int row) { progress_.stepOrThrow(uint64_t(row) + 1); }
    void indexRow(uint32_t row) { progress_.stepOrThrow(rows_ + row + 1); }

private:
    uint64_t rows_;
    Progress progress_;
};

constexpr float kTwoPi = glm::two_pi<float>();

uint32_t nextIndex(const Mesh& mesh) { return static_cast<uint32_t>(mesh.vertices.size()); }

void addTriangle(Mesh& mesh, uint32_t a, uint32_t b, uint32_t c) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

void append(Mesh& into, const Mesh& part) {
    const uint32_t offset = nextIndex(into);
    into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (uint32_t index : part.indices) into.indices.push_back(index + offset);
}

// A disc of `radius` at height y facing up (+y) or down (-y): a centre vertex and a fan.
void addDisc(Mesh& mesh, float radius, float y, bool facingUp, int segments) {
    const glm::vec3 normal{0.0f, facingUp ? 1.0f : -1.0f, 0.0f};
    const uint32_t centre = nextIndex(mesh);
    mesh.vertices.push_back({{0.0f, y, 0.0f}, normal, {0.5f, 0.5f}});
    for (int s = 0; s <= segments; ++s) {
        const float phi = kTwoPi * static_cast<float>(s) / static_cast<float>(segments);
        const float c = std::cos(phi), sn = std::sin(phi);
        mesh.vertices.push_back({{radius * c, y, radius * sn}, normal, {0.5f + 0.5f * c, 0.5f + 0.5f * sn}});
    }
    // With phi running from +x towards +z, (centre, s, s+1) faces -y.
    for (int s = 0; s < segments; ++s) {
        const uint32_t current = centre + 1 + static_cast<uint32_t>(s);
        if (facingUp) addTriangle(mesh, centre, current + 1, current);
        else addTriangle(mesh, centre, current, current + 1);
    }
}

// The side of a cone (topRadius 0) or cylinder between heights y0 and y1, without caps.
void addSide(Mesh& mesh, float bottomRadius, float topRadius, float y0, float y1, int segments) {
    const float height = y1 - y0;
    const bool cone = topRadius == 0.0f;
    const uint32_t first = nextIndex(mesh);
    for (int s = 0; s <= segments; ++s) {
        const float u = static_cast<float>(s) / static_cast<float>(segments);
        // A cone's apex gets one vertex per segment, at the middle of the segment, so its normal
        // is that of the face it belongs to.
        const float phiBottom = kTwoPi * u;
        const float phiTop = cone ? kTwoPi * (static_cast<float>(s) + 0.5f) / static_cast<float>(segments) : phiBottom;
        // Normal of a frustum side: perpendicular to the slope (bottomRadius - topRadius, height).
        const float slope = bottomRadius - topRadius;
        auto normalAt = [&](float phi) {
            return glm::normalize(glm::vec3(height * std::cos(phi), slope, height * std::sin(phi)));
        };
        mesh.vertices.push_back({{bottomRadius * std::cos(phiBottom), y0, bottomRadius * std::sin(phiBottom)},
                                 normalAt(phiBottom), {u, 0.0f}});
        mesh.vertices.push_back({{topRadius * std::cos(phiTop), y1, topRadius * std::sin(phiTop)},
                                 normalAt(phiTop), {u, 1.0f}});
    }
    for (int s = 0; s < segments; ++s) {
        const uint32_t bottom = first + 2 * static_cast<uint32_t>(s), top = bottom + 1;
        const uint32_t nextBottom = bottom + 2, nextTop = bottom + 3;
        addTriangle(mesh, bottom, top, nextBottom);
        if (!cone) addTriangle(mesh, top, nextTop, nextBottom);
    }
}

} // namespace

Mesh makePlane(float sizeX, float sizeZ, int subdivisions) {
    const int cells = std::max(subdivisions, 1);
    Mesh mesh;
    mesh.vertices.reserve(size_t(cells + 1) * size_t(cells + 1));
    mesh.indices.reserve(size_t(cells) * size_t(cells) * 6);
    GridProgress progress("plane", cells, cells);
    for (int j = 0; j <= cells; ++j) {
        progress.vertexRow(j);
        for (int i = 0; i <= cells; ++i) {
            const glm::vec2 uv{static_cast<float>(i) / static_cast<float>(cells),
                               static_cast<float>(j) / static_cast<float>(cells)};
            mesh.vertices.push_back({{(uv.x - 0.5f) * sizeX, 0.0f, (uv.y - 0.5f) * sizeZ}, {0.0f, 1.0f, 0.0f}, uv});
        }
    }
    const uint32_t row = static_cast<uint32_t>(cells) + 1;
    for (uint32_t j = 0; j < static_cast<uint32_t>(cells); ++j) {
        progress.indexRow(j);
        for (uint32_t i = 0; i < static_cast<uint32_t>(cells); ++i) {
            const uint32_t a = j * row + i;
            // (i, j), (i, j+1), (i+1, j) is counter-clockwise seen from +y.
            addTriangle(mesh, a, a + row, a + 1);
            addTriangle(mesh, a + 1, a + row, a + row + 1);
        }
    }
    return mesh;
}

Mesh makeBox(glm::vec3 size) {
    const glm::vec3 half = size * 0.5f;
    // Each face: outward normal n and axes u, v with cross(u, v) = n, so the corners
    // -u-v, +u-v, +u+v, -u+v run counter-clockwise seen from outside.
    struct Face { glm::vec3 n, u, v; };
    const Face faces[] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    const glm::vec2 corners[] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    Mesh mesh;
    for (const Face& face : faces) {
        const uint32_t first = nextIndex(mesh);
        for (const glm::vec2& corner : corners) {
            const glm::vec3 position = (face.n + corner.x * face.u + corner.y * face.v) * half;
            mesh.vertices.push_back({position, face.n, corner * 0.5f + 0.5f});
        }
        addTriangle(mesh, first, first + 1, first + 2);
        addTriangle(mesh, first, first + 2, first + 3);
    }
    return mesh;
}

Mesh makeSphere(float radius, int segments, int rings) {
    segments = std::max(segments, 3);
    rings = std::max(rings, 2);
    Mesh mesh;
    mesh.vertices.reserve(size_t(rings + 1) * size_t(segments + 1));
    mesh.indices.reserve(size_t(rings) * size_t(segments) * 6);
    GridProgress progress("sphere", segments, rings);
    // theta from the north pole (+y) down, phi around y from +x towards +z.
    for (int r = 0; r <= rings; ++r) {
        progress.vertexRow(r);
        const float theta = glm::pi<float>() * static_cast<float>(r) / static_cast<float>(rings);
        for (int s = 0; s <= segments; ++s) {
            const float phi = kTwoPi * static_cast<float>(s) / static_cast<float>(segments);
            glm::vec3 normal{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
            float u = static_cast<float>(s);
            // A pole vertex belongs to one triangle (below: north vertex s with segment s-1, south
            // vertex s with segment s), so it takes the middle of that segment in u.
            if (r == 0) u = std::max(u - 0.5f, 0.0f);
            if (r == rings) u = std::min(u + 0.5f, static_cast<float>(segments));
            if (r == 0 || r == rings) normal = {0.0f, r == 0 ? 1.0f : -1.0f, 0.0f};
            const float v = 1.0f - static_cast<float>(r) / static_cast<float>(rings);
            mesh.vertices.push_back({radius * normal, normal, {u / static_cast<float>(segments), v}});
        }
    }
    const uint32_t row = static_cast<uint32_t>(segments) + 1;
    for (uint32_t r = 0; r < static_cast<uint32_t>(rings); ++r) {
        progress.indexRow(r);
        for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
            const uint32_t a = r * row + s;
            // Going +phi then +theta is counter-clockwise seen from outside; at the poles one of
            // the two triangles of the quad would be degenerate and is left out.
            if (r != 0) addTriangle(mesh, a, a + 1, a + row);
            if (r != static_cast<uint32_t>(rings) - 1) addTriangle(mesh, a + 1, a + row + 1, a + row);
        }
    }
    return mesh;
}

Mesh makeCylinder(float radius, float height, int segments) {
    segments = std::max(segments, 3);
    Mesh mesh;
    addSide(mesh, radius, radius, 0.0f, height, segments);
    addDisc(mesh, radius, height, true, segments);
    addDisc(mesh, radius, 0.0f, false, segments);
    return mesh;
}

Mesh makeTorus(float majorRadius, float minorRadius, int segments, int sides) {
    // Centred at the origin, ring in the xz plane (the one generator not resting on y = 0).
    segments = std::max(segments, 3);
    sides = std::max(sides, 3);
    Mesh mesh;
    mesh.vertices.reserve(size_t(segments + 1) * size_t(sides + 1));
    mesh.indices.reserve(size_t(segments) * size_t(sides) * 6);
    GridProgress progress("torus", sides, segments);
    for (int i = 0; i <= segments; ++i) {
        progress.vertexRow(i);
        const float u = static_cast<float>(i) / static_cast<float>(segments);
        const float phi = kTwoPi * u;   // around the ring
        for (int j = 0; j <= sides; ++j) {
            const float v = static_cast<float>(j) / static_cast<float>(sides);
            const float psi = kTwoPi * v;   // around the tube
            const glm::vec3 normal{std::cos(psi) * std::cos(phi), std::sin(psi), std::cos(psi) * std::sin(phi)};
            const glm::vec3 centre{majorRadius * std::cos(phi), 0.0f, majorRadius * std::sin(phi)};
            mesh.vertices.push_back({centre + minorRadius * normal, normal, {u, v}});
        }
    }
    const uint32_t row = static_cast<uint32_t>(sides) + 1;
    for (uint32_t i = 0; i < static_cast<uint32_t>(segments); ++i) {
        progress.indexRow(i);
        for (uint32_t j = 0; j < static_cast<uint32_t>(sides); ++j) {
            const uint32_t a = i * row + j;
            // +psi then +phi is counter-clockwise seen from outside the tube.
            addTriangle(mesh, a, a + 1, a + row);
            addTriangle(mesh, a + 1, a + row + 1, a + row);
        }
    }
    return mesh;
}

Mesh makeTree(float height, float crownRadius, int segments) {
    // A stylised conifer: a thin capped trunk and a cone crown that overlaps its top. Two closed
    // parts in one mesh; enough to throw a tree-shaped shadow, nothing more.
    segments = std::max(segments, 3);
    const float trunkRadius = 0.15f * crownRadius;
    const float trunkHeight = 0.35f * height;
    const float crownBase = 0.25f * height;
    Mesh tree = makeCylinder(trunkRadius, trunkHeight, segments);
    Mesh crown;
    addSide(crown, crownRadius, 0.0f, crownBase, height, segments);
    addDisc(crown, crownRadius, crownBase, false, segments);
    append(tree, crown);
    return tree;
}

float terrainHeight(float x, float z, float amplitude, float wavelength) {
    // Two crossed swells of different lengths: hills without a visible period at forest scale.
    const float k = kTwoPi / std::max(wavelength, 1e-3f);
    return amplitude * 0.5f * (std::sin(k * x) * std::cos(0.77f * k * z) + 0.5f * std::sin(2.3f * k * (0.7f * x + 0.9f * z)));
}

Mesh makeTerrain(float sizeX, float sizeZ, int subdivisions, float amplitude, float wavelength) {
    Mesh mesh = makePlane(sizeX, sizeZ, subdivisions);
    for (Vertex& v : mesh.vertices) v.position.y = terrainHeight(v.position.x, v.position.z, amplitude, wavelength);
    generateNormals(mesh);
    return mesh;
}

Mesh makeBumpySphere(float radius, float amplitude, float frequency, int segments) {
    // Same topology as makeSphere (closed, poles included); each vertex moves along its normal by
    // two crossed ridge patterns, then normals are recomputed from the displaced surface.
    Mesh mesh = makeSphere(radius, segments, std::max(segments / 2, 2));
    for (Vertex& v : mesh.vertices) {
        const glm::vec3 d = glm::normalize(v.position);
        const float ridges = std::sin(frequency * d.x * 3.1f + 1.3f * std::sin(frequency * d.z)) *
                                 std::cos(frequency * d.y * 2.3f) +
                             0.5f * std::sin(2.7f * frequency * d.z + 2.0f * d.y);
        v.position = d * radius * (1.0f + amplitude * ridges);
    }
    generateNormals(mesh);
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// Sizes, from the arguments alone (tests/test_scene.cpp checks each against the generated mesh).

namespace {

MeshSize sized(uint64_t vertices, uint64_t triangles, glm::vec3 low, glm::vec3 high) {
    return {vertices, 3 * triangles, {low, high}};
}

uint64_t count(int value, int minimum) { return static_cast<uint64_t>(std::max(value, minimum)); }

} // namespace

MeshSize planeSize(float sizeX, float sizeZ, int subdivisions) {
    const uint64_t cells = count(subdivisions, 1);
    const glm::vec3 half{0.5f * sizeX, 0.0f, 0.5f * sizeZ};
    return sized((cells + 1) * (cells + 1), 2 * cells * cells, -half, half);
}

MeshSize boxSize(glm::vec3 size) { return sized(24, 12, -0.5f * size, 0.5f * size); }

MeshSize sphereSize(float radius, int segments, int rings) {
    const uint64_t s = count(segments, 3), r = count(rings, 2);
    return sized((r + 1) * (s + 1), s * (2 * r - 2), glm::vec3(-radius), glm::vec3(radius));
}

MeshSize cylinderSize(float radius, float height, int segments) {
    const uint64_t s = count(segments, 3);
    return sized(4 * s + 6, 4 * s, {-radius, 0.0f, -radius}, {radius, height, radius});
}

MeshSize torusSize(float majorRadius, float minorRadius, int segments, int sides) {
    const uint64_t s = count(segments, 3), t = count(sides, 3);
    const float outer = majorRadius + minorRadius;
    return sized((s + 1) * (t + 1), 2 * s * t, {-outer, -minorRadius, -outer}, {outer, minorRadius, outer});
}

MeshSize treeSize(float height, float crownRadius, int segments) {
    const uint64_t s = count(segments, 3);
    return sized(7 * s + 10, 6 * s, {-crownRadius, 0.0f, -crownRadius}, {crownRadius, height, crownRadius});
}

MeshSize bumpySphereSize(float radius, float amplitude, int segments) {
    // The ridges lie in [-1.5, 1.5], so |p| <= radius * (1 + 1.5 amplitude).
    const MeshSize sphere = sphereSize(radius, segments, std::max(segments / 2, 2));
    const float extent = radius * (1.0f + 1.5f * amplitude);
    return {sphere.vertices, sphere.indices, {glm::vec3(-extent), glm::vec3(extent)}};
}

MeshSize terrainSize(float sizeX, float sizeZ, int subdivisions, float amplitude) {
    MeshSize size = planeSize(sizeX, sizeZ, subdivisions);
    size.bounds.min.y = -0.75f * amplitude;   // terrainHeight is within +-0.75 amplitude
    size.bounds.max.y = 0.75f * amplitude;
    return size;
}

// The teapot's stand-in (seed 001's teapot scene when ../shared/assets has no teapot.obj): a body,
// spout, handle and knob in the proportions of the Utah teapot as teapot.obj has it (x -3 to 3.4,
// y 0 to 3.15, z -2 to 2 at size 1). One mesh of four closed parts, resting on y = 0.
namespace {
void appendTransformed(Mesh& into, const Mesh& part, const glm::mat4& transform) {
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    const uint32_t base = static_cast<uint32_t>(into.vertices.size());
    for (const Vertex& v : part.vertices)
        into.vertices.push_back({glm::vec3(transform * glm::vec4(v.position, 1.0f)), glm::normalize(normalMatrix * v.normal), v.uv});
    for (uint32_t index : part.indices) into.indices.push_back(base + index);
}
struct TeapotParts {
    int segments, rings;
};
TeapotParts teapotParts(int segments) { return {std::max(segments, 8), std::max(segments, 8) / 2}; }
} // namespace

Mesh makeTeapotStandIn(float size, int segments) {
    const TeapotParts p = teapotParts(segments);
    const glm::mat4 scale = glm::scale(glm::mat4(1.0f), glm::vec3(size));
    Mesh mesh;
    appendTransformed(mesh, makeSphere(1.0f, p.segments, p.rings),
                      scale * glm::scale(glm::translate(glm::mat4(1.0f), {0.0f, 1.5f, 0.0f}), {2.0f, 1.5f, 2.0f}));
    appendTransformed(mesh, makeCylinder(0.25f, 1.8f, p.segments),
                      scale * glm::rotate(glm::translate(glm::mat4(1.0f), {1.6f, 1.0f, 0.0f}), glm::radians(-50.0f), {0, 0, 1}));
    appendTransformed(mesh, makeTorus(0.7f, 0.15f, p.segments, p.rings),
                      scale * glm::rotate(glm::translate(glm::mat4(1.0f), {-2.0f, 1.7f, 0.0f}), glm::radians(90.0f), {1, 0, 0}));
    appendTransformed(mesh, makeSphere(0.25f, p.segments, p.rings), scale * glm::translate(glm::mat4(1.0f), {0.0f, 3.05f, 0.0f}));
    return mesh;
}

MeshSize teapotStandInSize(float size, int segments) {
    const TeapotParts p = teapotParts(segments);
    const MeshSize parts[] = {sphereSize(1.0f, p.segments, p.rings), cylinderSize(0.25f, 1.8f, p.segments),
                              torusSize(0.7f, 0.15f, p.segments, p.rings), sphereSize(0.25f, p.segments, p.rings)};
    MeshSize total;
    for (const MeshSize& part : parts) {
        total.vertices += part.vertices;
        total.indices += part.indices;
    }
    // Loose but never too small: the parts above lie within it.
    total.bounds = {glm::vec3(-3.0f, 0.0f, -2.0f) * size, glm::vec3(3.4f, 3.4f, 2.0f) * size};
    return total;
}

MeshSize sizeOf(const Mesh& mesh) {
    MeshSize size{mesh.vertices.size(), mesh.indices.size(), {glm::vec3(0.0f), glm::vec3(0.0f)}};
    if (mesh.vertices.empty()) return size;
    size.bounds = {mesh.vertices.front().position, mesh.vertices.front().position};
    for (const Vertex& v : mesh.vertices) {
        size.bounds.min = glm::min(size.bounds.min, v.position);
        size.bounds.max = glm::max(size.bounds.max, v.position);
    }
    return size;
}

} // namespace shadowlab
