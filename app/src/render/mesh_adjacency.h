// Triangles with adjacency (GL_TRIANGLES_ADJACENCY) for techniques that work on a mesh's edges
// (shadow volumes' silhouettes): built once per scene load, on the first request, by the renderer.
//
// Vertices are welded by position (meshes repeat a corner once per normal and uv), then every
// triangle (a, b, c) becomes (a, n_ab, b, n_bc, c, n_ca), n_xy the vertex opposite edge xy in the
// one other triangle that has the edge as (y, x): a manifold, consistently wound neighbour. An
// edge without such a neighbour (an open boundary, an edge of three or more triangles, a
// neighbour wound the other way) gets the triangle's own opposite vertex instead (n_ab = c), which
// a geometry stage recognises as "no neighbour". A mesh is closed when no edge lacks a neighbour.
// Indices are the mesh's own (the renderer adds the mesh's base vertex).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace shadowlab {

struct MeshAdjacency {
    std::vector<uint32_t> indices;   // 6 a triangle
    bool closed = false;             // every edge has its neighbour
    uint32_t openEdges = 0;          // edges without one
};

MeshAdjacency buildMeshAdjacency(const Mesh& mesh);

} // namespace shadowlab
