// Jittered disc sample sets for adaptive PCF and PCSS (seed 000 sec. 3.2.4; Uralsky, "Efficient
// Soft-Edged Shadows Using Pixel Shader Branching", GPU Gems 2 ch. 17). GL-free so the tests can
// check the mapping and the ordering.
//
// One set: an n x n grid over [0,1]^2, one sample jittered uniformly inside each cell, mapped to
// the unit disc by eq. 3.11-3.12. x becomes the angle and y the squared radius, so one grid row
// (fixed y range) becomes one annulus and the rows with the highest y form the outer ring.
// Samples are stored row by row from the highest y down: the first n are the outer ring, which is
// what the shader tests first (and stops after when they agree).
//
// m x m such sets tile the screen (set = pixel mod m) and are stored in one RGBA16_SNORM 3D texture of
// m x m x ceil(n^2 / 2) texels: two offsets per texel (xy, zw), texel z of set (x, y) holding
// samples 2z and 2z + 1. For odd n the last texel's zw repeats the last sample (never read as a
// separate sample: the shader counts n^2 samples).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/glm.hpp>

namespace shadowlab::jittered_disk {

// seed 000 eq. 3.11-3.12: u = sqrt(y) cos(2 pi x), v = sqrt(y) sin(2 pi x).
// Area preserving up to the constant pi: with r = sqrt(y), phi = 2 pi x the area element is
// r dr dphi = (1/2) dy * 2 pi dx = pi dx dy, so equal grid cells map to equal disc areas.
inline glm::vec2 squareToDisc(glm::vec2 p) {
    const float r = std::sqrt(p.y);
    const float phi = 2.0f * std::numbers::pi_v<float> * p.x;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// Texels of one set in the 3D texture (two samples per RGBA16_SNORM texel).
inline int texelsPerSet(int n) { return (n * n + 1) / 2; }
// Texels the shader reads before it decides on the early out: the first n samples (outer ring),
// rounded up to whole texels (for odd n this includes one sample of the second ring).
inline int outerRingTexels(int n) { return (n + 1) / 2; }

struct TextureSize {
    int width, height, depth;
};
// The documented size: m x m x n^2/2 (rounded up for odd n), RGBA16_SNORM.
inline TextureSize offsetTextureSize(int n, int m) { return {m, m, texelsPerSet(n)}; }
inline size_t offsetTextureBytes(int n, int m) { return size_t(m) * size_t(m) * size_t(texelsPerSet(n)) * 16u; }

// PCG32 (O'Neill 2014): the same sets on every platform and standard library, unlike
// std::uniform_real_distribution.
class Rng {
public:
    explicit Rng(uint64_t seed) : state_(0) {
        next();
        state_ += seed;
        next();
    }
    uint32_t next() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + 1442695040888963407ull;
        const uint32_t xorShifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = uint32_t(old >> 59u);
        return (xorShifted >> rot) | (xorShifted << ((32u - rot) & 31u));
    }
    // Uniform in [0, 1).
    float uniform() { return float(next() >> 8) * (1.0f / 16777216.0f); }

private:
    uint64_t state_;
};

// Sample k of a set lies in grid row n-1 - k/n (from the top), column k mod n.
inline int rowOfSample(int k, int n) { return n - 1 - k / n; }

// One set of n*n offsets in the unit disc, outer ring first.
inline std::vector<glm::vec2> makeSet(int n, Rng& rng) {
    std::vector<glm::vec2> set;
    set.reserve(size_t(n) * size_t(n));
    for (int k = 0; k < n * n; ++k) {
        const int row = rowOfSample(k, n), column = k % n;
        const glm::vec2 cell{(float(column) + rng.uniform()) / float(n), (float(row) + rng.uniform()) / float(n)};
        set.push_back(squareToDisc(cell));
    }
    return set;
}

// The 3D texture's texels, x fastest then y then z: texel (x, y, z) at ((z * m) + y) * m + x.
inline std::vector<glm::vec4> makeOffsetTexture(int n, int m, uint64_t seed = 1) {
    const TextureSize size = offsetTextureSize(n, m);
    std::vector<glm::vec4> texels(size_t(size.width) * size_t(size.height) * size_t(size.depth));
    Rng rng(seed);
    for (int y = 0; y < m; ++y)
        for (int x = 0; x < m; ++x) {
            const std::vector<glm::vec2> set = makeSet(n, rng);
            for (int z = 0; z < size.depth; ++z) {
                const glm::vec2 a = set[size_t(2 * z)];
                const glm::vec2 b = set[size_t(std::min(2 * z + 1, n * n - 1))];
                texels[(size_t(z) * size_t(m) + size_t(y)) * size_t(m) + size_t(x)] = {a.x, a.y, b.x, b.y};
            }
        }
    return texels;
}

} // namespace shadowlab::jittered_disk
