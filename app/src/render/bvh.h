// The GPU ray tracer's acceleration structure (issue 27): a binary BVH over the world-space
// triangles of a scene's shadow casters, built on the CPU with binned SAH (Wald 2007, "On fast
// construction of SAH-based bounding volume hierarchies"), in the layout shaders/ray_trace.glsl
// traverses. No GL here: the renderer uploads the arrays (Renderer::rayTracing()), tests build
// and traverse them on the CPU.
//
// Layout (std430, every array a run of vec4):
//   Node, 32 bytes: lo.xyz, hi.xyz the box; lo.w and hi.w are uint bits. Interior: lo.w = the
//     left child (the right one follows it), hi.w = 0. Leaf: lo.w = first triangle, hi.w = count.
//     Node 0 is the root.
//   Triangle, 48 bytes: v0, v1, v2 world positions; v0.w = material index, v1.w = uv record
//     (0xFFFFFFFF when the material has no transmission texture), v2.w = object index (uint bits).
//     Ordered so that each leaf's triangles are contiguous.
//   UvRecord, 32 bytes: the three texture coordinates of a textured triangle, (uv0, uv1), (uv2, 0).
//   MaterialRecord, 32 bytes: (transmission rgb, alpha), info = (flags, first texel, width,
//     height) as uint bits; flags bit 0: opaque.
//   Texels: every transmission texture, RGBA8 packed in one uint per texel (r in the low byte),
//     rows bottom-up as Texture::rgba.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace shadowlab::bvh {

struct Node {
    glm::vec4 lo;
    glm::vec4 hi;
};
static_assert(sizeof(Node) == 32);

struct Triangle {
    glm::vec4 v0, v1, v2;
};
static_assert(sizeof(Triangle) == 48);

struct UvRecord {
    glm::vec4 uv01;   // uv0.xy, uv1.xy
    glm::vec4 uv2;    // uv2.xy, 0, 0
};

struct MaterialRecord {
    glm::vec4 transmission;   // rgb = t, a = alpha (the material's; a texture replaces both per texel)
    glm::uvec4 info;          // x flags (kMaterialOpaque), y first texel, z width, w height (0: no texture)
};
constexpr uint32_t kMaterialOpaque = 1u;
constexpr uint32_t kNoUv = 0xFFFFFFFFu;

struct BuildOptions {
    int bins = 16;          // SAH bins per axis
    int leafSize = 4;       // a node of at most this many triangles always becomes a leaf
    int maxLeafSize = 16;   // a larger node is split even where SAH prefers a leaf
    int maxDepth = 60;      // ray_trace.glsl's stack holds 64 entries: deeper nodes become leaves
};

struct Bvh {
    std::vector<Node> nodes;
    std::vector<Triangle> triangles;
    std::vector<UvRecord> uvs;
    std::vector<MaterialRecord> materials;
    std::vector<uint32_t> texels;
    size_t triangleCount = 0;      // caster triangles (triangles holds one dummy when there are none)
    int depth = 0;                 // longest root-to-leaf path in edges (the root alone: 0)
    float rayOffset = 1e-4f;       // as the Embree reference: 1e-4 * the scene's extent (groundtruth)
    double buildSeconds = 0.0;     // the whole build: gathering, SAH, reordering
    size_t bytes() const {
        return nodes.size() * sizeof(Node) + triangles.size() * sizeof(Triangle) + uvs.size() * sizeof(UvRecord) +
               materials.size() * sizeof(MaterialRecord) + texels.size() * sizeof(uint32_t);
    }
};

// The BVH of every shadow-casting object of `scene` (objects with castsShadow = false are left
// out; every material is listed, indexed as Scene::materials). An empty scene gives one empty
// leaf. O(n log n): each level of the tree bins and partitions its triangles once.
Bvh build(const Scene& scene, const BuildOptions& options = {});

// The reference's ray offset (embree_groundtruth.cpp, setScene): 1e-4 times the larger of the
// diagonal of every drawn object's world bounds and the farthest corner's distance from the origin.
float referenceRayOffset(const Scene& scene);

// ---------------------------------------------------------------------------------------------
// CPU mirror of shaders/ray_trace.glsl (tests, and the reference check of the layout).

// Watertight ray-triangle test (Woop, Benthin and Wald 2013): t of the hit in (0, tMax), or a
// negative number. Both sides count (shadow rays have no back-face culling).
float intersectTriangle(glm::vec3 origin, glm::vec3 direction, const Triangle& triangle, float tMax);

// What one crossing of `triangle` at world point `p` lets through under the physical model:
// 0 for an opaque material, else (1 - a) + a t (a, t from its texture at p's uv where it has one).
glm::vec3 crossing(const Bvh& bvh, const Triangle& triangle, glm::vec3 p);

struct TraceCounters {
    uint64_t nodes = 0;       // nodes whose children's boxes were tested
    uint64_t triangles = 0;   // triangle tests
};
// What reaches the end of the ray (origin + tMax * direction) under the physical model: the
// product of (1 - a) + a t over every translucent caster crossed, 0 at an opaque one (any hit).
// Textured materials are sampled at the hit's uv as sampleTexture does. Translucent crossings of
// one object less than `merge` apart along the ray count once (a shared edge; ray_trace.glsl).
glm::vec3 transmittance(const Bvh& bvh, glm::vec3 origin, glm::vec3 direction, float tMax, float merge,
                        TraceCounters* counters = nullptr);

} // namespace shadowlab::bvh
