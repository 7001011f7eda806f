// Traced references kept by what they depend on, so that every technique measured on the same
// frame shares one trace (issue 32): the same camera over the same opaque scene gives the same
// G-buffer for every technique, and the reference depends on nothing else but the light, the
// scene's geometry (its load generation) and the reference options (mode, rays, seed, model,
// adaptivity; not the thread count, which changes no sample).
//
// The key is two independent 64-bit hashes of all of that (the G-buffer's every byte included), so
// a different frame or setting misses; a hit returns the stored image and statistics, which are
// those the trace gave, bit for bit. Entries are dropped oldest first beyond kMaxEntries or
// kMaxBytes. Not thread-safe: the render thread's App owns it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "groundtruth/groundtruth.h"

namespace shadowlab {

class ReferenceCache {
public:
    struct Key {
        uint64_t a = 0, b = 0;
        bool operator==(const Key&) const = default;
    };
    static constexpr size_t kMaxEntries = 8;
    static constexpr size_t kMaxBytes = size_t(1) << 30;

    static Key keyOf(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
                     uint64_t sceneGeneration);

    // The stored trace for `key`, or null. The pointers live until the next insert() or clear().
    const std::vector<glm::vec3>* find(const Key& key, const ReferenceStats** stats = nullptr);
    void insert(const Key& key, const std::vector<glm::vec3>& visibility, const ReferenceStats& stats);
    void clear() { entries_.clear(); }

    bool enabled = true;
    uint64_t hits = 0;
    uint64_t misses = 0;

private:
    struct Entry {
        Key key;
        std::vector<glm::vec3> visibility;
        ReferenceStats stats;
        size_t bytes() const { return visibility.size() * sizeof(glm::vec3) + stats.sampleError.size() * sizeof(float); }
    };
    std::deque<Entry> entries_;   // oldest first
};

} // namespace shadowlab
