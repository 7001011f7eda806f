// Triangles with adjacency (see mesh_adjacency.h).
#include "render/mesh_adjacency.h"

#include <algorithm>
#include <cstring>
#include <unordered_map>

namespace shadowlab {
namespace {

struct PositionKey {
    uint32_t x, y, z;
    bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
    size_t operator()(const PositionKey& k) const {
        return size_t(k.x) * 73856093u ^ size_t(k.y) * 19349663u ^ size_t(k.z) * 83492791u;
    }
};

PositionKey keyOf(const glm::vec3& p) {
    // Bit patterns (with -0 folded into +0): exact welding, as the geometry stage compares exactly.
    PositionKey key{};
    const glm::vec3 q = p + glm::vec3(0.0f);
    std::memcpy(&key.x, &q.x, 4);
    std::memcpy(&key.y, &q.y, 4);
    std::memcpy(&key.z, &q.z, 4);
    return key;
}

} // namespace

MeshAdjacency buildMeshAdjacency(const Mesh& mesh) {
    MeshAdjacency out;
    const size_t triangles = mesh.indices.size() / 3;
    // Welded id of every vertex.
    std::vector<uint32_t> weld(mesh.vertices.size());
    std::unordered_map<PositionKey, uint32_t, PositionHash> ids;
    ids.reserve(mesh.vertices.size());
    for (size_t v = 0; v < mesh.vertices.size(); ++v)
        weld[v] = ids.try_emplace(keyOf(mesh.vertices[v].position), uint32_t(ids.size())).first->second;
    // Directed edges (welded from, welded to) -> the triangles' corner opposite each, and how many.
    struct Use {
        uint32_t opposite = 0;   // vertex index (unwelded) opposite the edge
        uint32_t count = 0;
    };
    std::unordered_map<uint64_t, Use> directed;
    directed.reserve(triangles * 3);
    auto edgeKey = [](uint32_t a, uint32_t b) { return uint64_t(a) << 32 | b; };
    // Triangles with two corners welded together (the poles of a sphere) have no area and no
    // edges: they cast nothing and do not open the mesh.
    auto degenerate = [&](size_t t) {
        const uint32_t a = weld[mesh.indices[t * 3]], b = weld[mesh.indices[t * 3 + 1]], c = weld[mesh.indices[t * 3 + 2]];
        return a == b || b == c || c == a;
    };
    for (size_t t = 0; t < triangles; ++t)
        for (int e = 0; e < 3 && !degenerate(t); ++e) {
            const uint32_t a = mesh.indices[t * 3 + size_t(e)], b = mesh.indices[t * 3 + size_t((e + 1) % 3)],
                           c = mesh.indices[t * 3 + size_t((e + 2) % 3)];
            Use& use = directed[edgeKey(weld[a], weld[b])];
            use.opposite = c;
            ++use.count;
        }
    out.indices.resize(triangles * 6);
    for (size_t t = 0; t < triangles; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = mesh.indices[t * 3 + size_t(e)], b = mesh.indices[t * 3 + size_t((e + 1) % 3)],
                           c = mesh.indices[t * 3 + size_t((e + 2) % 3)];
            if (degenerate(t)) {
                out.indices[t * 6 + size_t(e) * 2] = a;
                out.indices[t * 6 + size_t(e) * 2 + 1] = c;
                continue;
            }
            const auto forward = directed.find(edgeKey(weld[a], weld[b]));
            const auto backward = directed.find(edgeKey(weld[b], weld[a]));
            // Manifold and consistently wound: this edge once each way.
            const bool neighbour = backward != directed.end() && backward->second.count == 1 && forward->second.count == 1;
            out.indices[t * 6 + size_t(e) * 2] = a;
            out.indices[t * 6 + size_t(e) * 2 + 1] = neighbour ? backward->second.opposite : c;
            if (!neighbour) ++out.openEdges;
        }
    out.closed = triangles > 0 && out.openEdges == 0;
    return out;
}

} // namespace shadowlab
