// Binned SAH BVH for the GPU shadow tracer (bvh.h). One pass per tree level over the triangles of
// the level's nodes: bounds, 16 bins on each axis of the centroid bounds, the cheapest plane by
// the surface area heuristic, an in-place partition. Nodes are made in pairs so the right child
// is always left + 1 (one index per interior node).
#include "render/bvh.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <atomic>
#include <limits>
#include <thread>

namespace shadowlab::bvh {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

uint32_t floatBits(float f) {
    uint32_t u;
    std::memcpy(&u, &f, sizeof(u));
    return u;
}
float bitsFloat(uint32_t u) {
    float f;
    std::memcpy(&f, &u, sizeof(f));
    return f;
}

struct Box {
    glm::vec3 lo{kInf}, hi{-kInf};
    void grow(glm::vec3 p) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b) {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    float area() const {
        if (lo.x > hi.x) return 0.0f;
        const glm::vec3 d = hi - lo;
        return d.x * d.y + d.y * d.z + d.z * d.x;
    }
};

struct PrimRef {
    Box box;
    glm::vec3 centre;
    uint32_t index;
};

struct Task {
    uint32_t node;
    uint32_t begin, end;
    int depth;
};

// Binned SAH from `root` (whose node already exists in `nodes`), making nodes in pairs at the end
// of `nodes`. With `deferred`, tasks of fewer than `cutoff` triangles are left there unbuilt (their
// node made, its content not): the subtrees the threads build.
void buildNodes(std::vector<PrimRef>& refs, const BuildOptions& options, std::vector<Node>& nodes, Task root,
                std::vector<Task>* deferred, uint32_t cutoff, int& depth) {
    const int binCount = std::clamp(options.bins, 2, 64);
    std::vector<Task> stack{root};
    struct Bin {
        Box box;
        uint32_t count = 0;
    };
    std::vector<Bin> bins(size_t(3 * binCount));
    std::vector<float> rightArea(static_cast<size_t>(binCount));
    std::vector<uint32_t> rightCount(static_cast<size_t>(binCount));
    while (!stack.empty()) {
        const Task task = stack.back();
        stack.pop_back();
        depth = std::max(depth, task.depth);
        if (deferred && task.end - task.begin < cutoff) {
            deferred->push_back(task);
            continue;
        }
        Box box, centres;
        for (uint32_t i = task.begin; i < task.end; ++i) {
            box.grow(refs[i].box);
            centres.grow(refs[i].centre);
        }
        const uint32_t n = task.end - task.begin;
        auto makeLeaf = [&] {
            Node& node = nodes[task.node];
            node.lo = glm::vec4(n ? box.lo : glm::vec3(0.0f), bitsFloat(task.begin));
            node.hi = glm::vec4(n ? box.hi : glm::vec3(-1.0f), bitsFloat(n));
        };
        if (n <= uint32_t(std::max(1, options.leafSize)) || task.depth >= options.maxDepth) {
            makeLeaf();
            continue;
        }
        // Bin the centroids on every axis and sweep for the cheapest plane.
        for (Bin& bin : bins) bin = {};
        const glm::vec3 extent = centres.hi - centres.lo;
        for (uint32_t i = task.begin; i < task.end; ++i)
            for (int axis = 0; axis < 3; ++axis) {
                if (!(extent[axis] > 0.0f)) continue;
                const float f = (refs[i].centre[axis] - centres.lo[axis]) / extent[axis];
                const int b = std::min(binCount - 1, int(f * float(binCount)));
                Bin& bin = bins[size_t(axis * binCount + b)];
                bin.box.grow(refs[i].box);
                ++bin.count;
            }
        float bestCost = kInf;
        int bestAxis = -1, bestSplit = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (!(extent[axis] > 0.0f)) continue;
            const Bin* axisBins = &bins[size_t(axis * binCount)];
            Box right;
            uint32_t rc = 0;
            for (int b = binCount - 1; b > 0; --b) {
                right.grow(axisBins[b].box);
                rc += axisBins[b].count;
                rightArea[size_t(b)] = right.area();
                rightCount[size_t(b)] = rc;
            }
            Box left;
            uint32_t lc = 0;
            for (int b = 0; b < binCount - 1; ++b) {
                left.grow(axisBins[b].box);
                lc += axisBins[b].count;
                if (lc == 0 || rightCount[size_t(b + 1)] == 0) continue;
                const float cost = left.area() * float(lc) + rightArea[size_t(b + 1)] * float(rightCount[size_t(b + 1)]);
                if (cost < bestCost) {
                    bestCost = cost;
                    bestAxis = axis;
                    bestSplit = b + 1;
                }
            }
        }
        // SAH: traversal cost 1, intersection cost 1 per triangle, relative to the node's area.
        const float leafCost = box.area() * float(n);
        uint32_t middle = task.begin;
        if (bestAxis >= 0) {
            if (bestCost + box.area() >= leafCost && n <= uint32_t(options.maxLeafSize)) {
                makeLeaf();
                continue;
            }
            const float lo = centres.lo[bestAxis], ext = extent[bestAxis];
            middle = uint32_t(std::partition(refs.begin() + task.begin, refs.begin() + task.end,
                                             [&](const PrimRef& r) {
                                                 const float f = (r.centre[bestAxis] - lo) / ext;
                                                 return std::min(binCount - 1, int(f * float(binCount))) < bestSplit;
                                             }) -
                              refs.begin());
        }
        if (middle == task.begin || middle == task.end) {
            // Every centroid in one place (or one bin): split the range in two halves.
            if (n <= uint32_t(options.maxLeafSize)) {
                makeLeaf();
                continue;
            }
            middle = task.begin + n / 2;
        }
        const uint32_t left = uint32_t(nodes.size());
        nodes.push_back({});
        nodes.push_back({});
        Node& node = nodes[task.node];
        node.lo = glm::vec4(box.lo, bitsFloat(left));
        node.hi = glm::vec4(box.hi, bitsFloat(0u));
        stack.push_back({left + 1, middle, task.end, task.depth + 1});
        stack.push_back({left, task.begin, middle, task.depth + 1});
    }

}

} // namespace

float referenceRayOffset(const Scene& scene) {
    glm::vec3 lower(kInf), upper(-kInf);
    for (const SceneObject& object : scene.objects) {
        if (object.mesh >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[object.mesh];
        if (mesh.indices.size() < 3) continue;
        for (const Vertex& v : mesh.vertices) {
            const glm::vec3 p(object.transform * glm::vec4(v.position, 1.0f));
            lower = glm::min(lower, p);
            upper = glm::max(upper, p);
        }
    }
    if (!(lower.x <= upper.x)) return 1e-4f;
    const float extent = std::max(glm::length(upper - lower), std::max(glm::length(lower), glm::length(upper)));
    return 1e-4f * std::max(extent, 1e-3f);
}

Bvh build(const Scene& scene, const BuildOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    Bvh out;
    out.rayOffset = referenceRayOffset(scene);

    // Materials and their transmission textures.
    std::vector<int64_t> texelStart(scene.textures.size(), -1);
    for (const Material& material : scene.materials) {
        MaterialRecord record{glm::vec4(material.transmission, material.alpha), glm::uvec4(0u)};
        record.info.x = material.translucent() ? 0u : kMaterialOpaque;
        const int t = material.transmissionTexture;
        if (!material.translucent()) {
        } else if (t >= 0 && size_t(t) < scene.textures.size() && scene.textures[size_t(t)].width > 0 &&
                   scene.textures[size_t(t)].height > 0) {
            const Texture& texture = scene.textures[size_t(t)];
            if (texelStart[size_t(t)] < 0) {
                texelStart[size_t(t)] = int64_t(out.texels.size());
                const size_t count = size_t(texture.width) * size_t(texture.height);
                for (size_t i = 0; i < count; ++i) {
                    const uint8_t* c = &texture.rgba[4 * i];
                    out.texels.push_back(uint32_t(c[0]) | uint32_t(c[1]) << 8 | uint32_t(c[2]) << 16 | uint32_t(c[3]) << 24);
                }
            }
            record.info.y = uint32_t(texelStart[size_t(t)]);
            record.info.z = uint32_t(texture.width);
            record.info.w = uint32_t(texture.height);
        }
        out.materials.push_back(record);
    }
    if (out.materials.empty()) out.materials.push_back({glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::uvec4(kMaterialOpaque, 0, 0, 0)});
    if (out.texels.empty()) out.texels.push_back(0xFFFFFFFFu);

    // World-space triangles of the casters.
    std::vector<Triangle> triangles;
    std::vector<UvRecord> uvs;
    size_t count = 0;
    for (const SceneObject& object : scene.objects)
        if (object.castsShadow && object.mesh < scene.meshes.size()) count += scene.meshes[object.mesh].indices.size() / 3;
    triangles.reserve(count);
    for (size_t o = 0; o < scene.objects.size(); ++o) {
        const SceneObject& object = scene.objects[o];
        if (!object.castsShadow || object.mesh >= scene.meshes.size()) continue;
        const Mesh& mesh = scene.meshes[object.mesh];
        const uint32_t material = object.material < out.materials.size() ? object.material : 0u;
        const bool textured = out.materials[material].info.z > 0;
        std::vector<glm::vec3> world(mesh.vertices.size());
        for (size_t v = 0; v < mesh.vertices.size(); ++v) world[v] = glm::vec3(object.transform * glm::vec4(mesh.vertices[v].position, 1.0f));
        for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
            const uint32_t a = mesh.indices[i], b = mesh.indices[i + 1], c = mesh.indices[i + 2];
            if (a >= world.size() || b >= world.size() || c >= world.size()) continue;
            uint32_t uv = kNoUv;
            if (textured) {
                uv = uint32_t(uvs.size());
                uvs.push_back({glm::vec4(mesh.vertices[a].uv, mesh.vertices[b].uv), glm::vec4(mesh.vertices[c].uv, 0.0f, 0.0f)});
            }
            triangles.push_back({glm::vec4(world[a], bitsFloat(material)), glm::vec4(world[b], bitsFloat(uv)),
                                 glm::vec4(world[c], bitsFloat(uint32_t(o)))});
        }
    }
    out.uvs = uvs.empty() ? std::vector<UvRecord>(1) : std::move(uvs);

    std::vector<PrimRef> refs(triangles.size());
    for (size_t i = 0; i < triangles.size(); ++i) {
        PrimRef& r = refs[i];
        r.box.grow(glm::vec3(triangles[i].v0));
        r.box.grow(glm::vec3(triangles[i].v1));
        r.box.grow(glm::vec3(triangles[i].v2));
        r.centre = 0.5f * (r.box.lo + r.box.hi);
        r.index = uint32_t(i);
    }

    // The top of the tree on this thread, down to subtrees of about 1 / (8 threads) of the
    // triangles; those are built in parallel into their own arrays, then appended in order (the
    // tree does not depend on the thread count or the schedule).
    out.nodes.reserve(refs.empty() ? 1 : 2 * refs.size() / size_t(std::max(1, options.leafSize)) + 1);
    out.nodes.push_back({});
    const unsigned threads = std::clamp(std::thread::hardware_concurrency(), 1u, 64u);
    const uint32_t cutoff = threads > 1 ? std::max<uint32_t>(65536u, uint32_t(refs.size() / (8u * threads))) : 0u;
    std::vector<Task> subtrees;
    buildNodes(refs, options, out.nodes, {0, 0, uint32_t(refs.size()), 0}, cutoff ? &subtrees : nullptr, cutoff, out.depth);
    if (!subtrees.empty()) {
        std::vector<std::vector<Node>> local(subtrees.size());
        std::vector<int> depths(subtrees.size(), 0);
        std::atomic<size_t> next{0};
        auto work = [&] {
            for (size_t i; (i = next++) < subtrees.size();) {
                local[i].push_back({});
                buildNodes(refs, options, local[i], {0, subtrees[i].begin, subtrees[i].end, subtrees[i].depth}, nullptr, 0,
                           depths[i]);
            }
        };
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < std::min<unsigned>(threads, unsigned(subtrees.size())); ++t) pool.emplace_back(work);
        work();
        for (std::thread& thread : pool) thread.join();
        // Local node 0 is the subtree's root (node subtrees[i].node); local c >= 1 goes to offset + c - 1.
        for (size_t i = 0; i < subtrees.size(); ++i) {
            const uint32_t offset = uint32_t(out.nodes.size());
            auto place = [&](Node node) {
                if (floatBits(node.hi.w) == 0u) node.lo.w = bitsFloat(offset + floatBits(node.lo.w) - 1u);
                return node;
            };
            out.nodes[subtrees[i].node] = place(local[i][0]);
            for (size_t c = 1; c < local[i].size(); ++c) out.nodes.push_back(place(local[i][c]));
            out.depth = std::max(out.depth, depths[i]);
        }
    }

    // No caster: one leaf holding the zero triangle, which no ray hits (its determinant is 0), so
    // the traversal needs no special case (an empty leaf reads as an interior node).
    if (refs.empty()) out.nodes[0] = {glm::vec4(0.0f, 0.0f, 0.0f, bitsFloat(0u)), glm::vec4(0.0f, 0.0f, 0.0f, bitsFloat(1u))};
    out.triangleCount = triangles.size();
    out.triangles.resize(std::max<size_t>(1, triangles.size()));
    for (size_t i = 0; i < refs.size(); ++i) out.triangles[i] = triangles[refs[i].index];
    out.buildSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

// ---------------------------------------------------------------------------------------------

float intersectTriangle(glm::vec3 origin, glm::vec3 direction, const Triangle& tri, float tMax) {
    const glm::vec3 absDir = glm::abs(direction);
    int kz = absDir.x > absDir.y ? (absDir.x > absDir.z ? 0 : 2) : (absDir.y > absDir.z ? 1 : 2);
    int kx = (kz + 1) % 3, ky = (kx + 1) % 3;
    if (direction[kz] < 0.0f) std::swap(kx, ky);
    const float sx = direction[kx] / direction[kz], sy = direction[ky] / direction[kz], sz = 1.0f / direction[kz];
    const glm::vec3 a = glm::vec3(tri.v0) - origin, b = glm::vec3(tri.v1) - origin, c = glm::vec3(tri.v2) - origin;
    const float ax = a[kx] - sx * a[kz], ay = a[ky] - sy * a[kz];
    const float bx = b[kx] - sx * b[kz], by = b[ky] - sy * b[kz];
    const float cx = c[kx] - sx * c[kz], cy = c[ky] - sy * c[kz];
    float u = cx * by - cy * bx, v = ax * cy - ay * cx, w = bx * ay - by * ax;
    if (u == 0.0f || v == 0.0f || w == 0.0f) {
        u = float(double(cx) * double(by) - double(cy) * double(bx));
        v = float(double(ax) * double(cy) - double(ay) * double(cx));
        w = float(double(bx) * double(ay) - double(by) * double(ax));
    }
    if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return -1.0f;
    const float det = u + v + w;
    if (det == 0.0f) return -1.0f;
    const float t = (u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz]) / det;
    return t > 0.0f && t < tMax ? t : -1.0f;
}

namespace {

// Bilinear, repeat: sampleTexture (scene.h) on the packed texels.
glm::vec4 sampleTexels(const Bvh& bvh, const glm::uvec4& info, glm::vec2 uv) {
    const int width = int(info.z), height = int(info.w);
    const glm::vec2 st = uv * glm::vec2(float(width), float(height)) - 0.5f;
    const glm::vec2 base = glm::floor(st), f = st - base;
    auto wrap = [](float i, int n) {
        const long long k = static_cast<long long>(i) % n;
        return size_t(k < 0 ? k + n : k);
    };
    auto texel = [&](float dx, float dy) {
        const uint32_t t = bvh.texels[info.y + wrap(base.y + dy, height) * size_t(width) + wrap(base.x + dx, width)];
        return glm::vec4(float(t & 255u), float(t >> 8 & 255u), float(t >> 16 & 255u), float(t >> 24)) * (1.0f / 255.0f);
    };
    return glm::mix(glm::mix(texel(0, 0), texel(1, 0), f.x), glm::mix(texel(0, 1), texel(1, 1), f.x), f.y);
}

// Ray against box with the slab test; tMax widened by 2 gamma(3) (Ize 2013) so a box is never
// missed by rounding where the triangle inside it is hit.
bool hitsBox(const Node& node, glm::vec3 origin, glm::vec3 inverse, float tMax) {
    const glm::vec3 t0 = (glm::vec3(node.lo) - origin) * inverse, t1 = (glm::vec3(node.hi) - origin) * inverse;
    const glm::vec3 near = glm::min(t0, t1), far = glm::max(t0, t1);
    const float enter = std::max(std::max(near.x, near.y), std::max(near.z, 0.0f));
    const float leave = std::min(std::min(far.x, far.y), std::min(far.z, tMax)) * 1.0000004f;
    return enter <= leave;
}

} // namespace

glm::vec3 crossing(const Bvh& bvh, const Triangle& tri, glm::vec3 p) {
    const MaterialRecord& material = bvh.materials[floatBits(tri.v0.w)];
    if (material.info.x & kMaterialOpaque) return glm::vec3(0.0f);
    glm::vec4 ta = material.transmission;
    if (material.info.z > 0) {
        // Barycentrics of the hit point.
        const glm::vec3 e1 = glm::vec3(tri.v1 - tri.v0), e2 = glm::vec3(tri.v2 - tri.v0), q = p - glm::vec3(tri.v0);
        const float d00 = glm::dot(e1, e1), d01 = glm::dot(e1, e2), d11 = glm::dot(e2, e2);
        const float d20 = glm::dot(q, e1), d21 = glm::dot(q, e2), den = d00 * d11 - d01 * d01;
        const float v = den != 0.0f ? (d11 * d20 - d01 * d21) / den : 0.0f;
        const float w = den != 0.0f ? (d00 * d21 - d01 * d20) / den : 0.0f;
        const UvRecord& uv = bvh.uvs[floatBits(tri.v1.w)];
        const glm::vec2 st = (1.0f - v - w) * glm::vec2(uv.uv01.x, uv.uv01.y) + v * glm::vec2(uv.uv01.z, uv.uv01.w) +
                             w * glm::vec2(uv.uv2.x, uv.uv2.y);
        ta = sampleTexels(bvh, material.info, st);
    }
    const float a = glm::clamp(ta.a, 0.0f, 1.0f);
    return (1.0f - a) + a * glm::clamp(glm::vec3(ta), 0.0f, 1.0f);
}

glm::vec3 transmittance(const Bvh& bvh, glm::vec3 origin, glm::vec3 direction, float tMax, float merge, TraceCounters* counters) {
    float crossedT[4] = {};
    uint32_t crossedObject[4] = {};
    int crossed = 0;
    glm::vec3 inverse;
    for (int k = 0; k < 3; ++k) {
        const float d = std::abs(direction[k]) < 1e-20f ? std::copysign(1e-20f, direction[k]) : direction[k];
        inverse[k] = 1.0f / d;
    }
    glm::vec3 throughput(1.0f);
    if (bvh.nodes.empty() || !hitsBox(bvh.nodes[0], origin, inverse, tMax)) return throughput;
    uint32_t stack[64];
    int top = 0;
    uint32_t current = 0;
    for (;;) {
        const Node& node = bvh.nodes[current];
        const uint32_t count = floatBits(node.hi.w), first = floatBits(node.lo.w);
        if (count > 0) {
            for (uint32_t i = first; i < first + count; ++i) {
                if (counters) ++counters->triangles;
                const Triangle& tri = bvh.triangles[i];
                const float t = intersectTriangle(origin, direction, tri, tMax);
                if (t < 0.0f) continue;
                const glm::vec3 factor = crossing(bvh, tri, origin + t * direction);
                if (factor == glm::vec3(0.0f)) return factor;
                // ray_trace.glsl's merge: one object's crossings closer than `merge` count once.
                const uint32_t object = floatBits(tri.v2.w);
                bool again = false;
                for (int j = 0; j < std::min(crossed, 4); ++j)
                    again = again || (crossedObject[j] == object && std::abs(crossedT[j] - t) < merge);
                if (again) continue;
                crossedT[crossed % 4] = t;
                crossedObject[crossed % 4] = object;
                ++crossed;
                throughput *= factor;
                if (throughput == glm::vec3(0.0f)) return throughput;
            }
        } else {
            if (counters) ++counters->nodes;
            const bool hitLeft = hitsBox(bvh.nodes[first], origin, inverse, tMax);
            const bool hitRight = hitsBox(bvh.nodes[first + 1], origin, inverse, tMax);
            if (hitLeft && hitRight) {
                stack[top++] = first + 1;
                current = first;
                continue;
            }
            if (hitLeft || hitRight) {
                current = hitLeft ? first : first + 1;
                continue;
            }
        }
        if (top == 0) break;
        current = stack[--top];
    }
    return throughput;
}

} // namespace shadowlab::bvh
