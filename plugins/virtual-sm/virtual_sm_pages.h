// The GPU side of virtual-sm: page table, free list, requests and the physical atlas in storage
// buffers and one depth texture, and the passes that run on them each frame (mark, allocate,
// cull, clear, draw). The technique (virtual_sm.cpp) decides the layout and the light space;
// this class owns every GL object of the virtual map and never reads anything back but the
// statistics, through kit::ReadbackRing, frames late.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <shadowlab/kit/handles.h>
#include <shadowlab/kit/readback_ring.h>

#include "virtual_sm_shared.h"

namespace shadowlab::virtual_sm {

// One opaque caster as the cull pass and the page draws read it (vsm_objects.glsl, std430).
struct VsmObject {
    glm::vec4 lightRect{0.0f};   // light-space bounds: min x, min y, max x, max y
    uint32_t firstTriangle = 0;
    uint32_t triangleCount = 0;
    int32_t baseVertex = 0;
    uint32_t transform = 0;
};
static_assert(sizeof(VsmObject) == 32);

constexpr uint32_t kPairCapacity = 1u << 18;   // (page, object) instances a frame: 2 MiB
constexpr uint64_t kPageBytes = uint64_t(VSM_PAGE_TEXELS) * VSM_PAGE_TEXELS * 4;   // 32-bit depth

struct PageLayout {
    int levels = 1;
    int pagesPerSide = 32;   // of each level's window (virtual_size / 128)
    int atlasPages = 32;     // physical atlas width in pages (physical_size / 128)
    int atlasRows = 32;      // its height in pages (fewer where the page buffers take rows: fitRows)
    bool operator==(const PageLayout&) const = default;
    int virtualPages() const { return levels * pagesPerSide * pagesPerSide; }
    int physicalPages() const { return atlasPages * atlasRows; }
    uint64_t atlasBytes() const { return uint64_t(physicalPages()) * kPageBytes; }
    // The storage buffers beside the atlas (VirtualPages::configure): page table (16 bytes a
    // virtual page), requests (4), free list (4 a physical page), pages to draw (16), the per-page
    // caster instances and the state block.
    uint64_t bufferBytes() const {
        return uint64_t(virtualPages()) * 20 + uint64_t(physicalPages()) * 20 + uint64_t(kPairCapacity) * 8 +
               VSM_STATE_WORDS * 4;
    }
    // Budget: atlas + buffers within physical_size^2 depth texels (a square map's memory, as csm's
    // cascades are counted). A real engine sizes its page pool in pages against a memory budget
    // (UE5: r.Shadow.Virtual.MaxPhysicalPages), not as a square; so the atlas gives up whole page
    // rows to the buffers where they are at most a quarter of the budget (4096 at the default
    // virtual size: 3 rows, 96 pages). Below that they would take most of the atlas, and the
    // layout stays square (over budget by the buffers, reported in "physical MiB").
    PageLayout fitRows() const {
        PageLayout fitted = *this;
        fitted.atlasRows = atlasPages;
        const uint64_t rowBytes = uint64_t(atlasPages) * kPageBytes;
        const uint64_t reserve = (fitted.bufferBytes() + rowBytes - 1) / rowBytes;
        if (reserve * 4 <= uint64_t(atlasPages)) fitted.atlasRows = atlasPages - int(reserve);
        return fitted;
    }
};

// What the page draws need from the frame.
struct PageDraw {
    const CameraPrepass* prepass = nullptr;   // its depth (the depth-only pre-pass); null: nothing is marked
    glm::mat4 inverseViewProjection{1.0f};    // rebuilds the pixels' world positions from depth
    const AdjacencyScene* scene = nullptr;    // the casters' vertices and indices
    float constantBias = 0.0f;
    float slopeBias = 0.0f;
    int cull = 0;                             // kit::Cull
    bool levelImage = false;                  // write the "page levels" debug image
};

class VirtualPages {
public:
    bool create(IHost& host, std::string& error);
    void destroy();
    // Buffers for a layout (reallocated only when it changes), the atlas grown to hold it (never
    // shrunk); empties the cache.
    void configure(const PageLayout& layout);
    // Forgets every page (the light, the scene or the bias changed): all pages free.
    void invalidate();
    void setObjects(const std::vector<VsmObject>& objects);
    // One frame: collects finished statistics, then marks, allocates, clears and draws pages.
    void render(const PageDraw& draw);
    void bindMainPass() const;
    // The newest statistics read back (VSM_STATS_WORDS words), and whether any were.
    const std::vector<uint32_t>& statistics() const { return stats_.latest(); }
    bool hasStatistics() const { return statsRead_; }
    // Reports the layout's capacity and memory and the newest page counters (a few frames old,
    // never waited for) as the technique's statistics.
    void reportStatistics(IHost& host) const;
    // The layout's atlas (what the technique uses; the texture may be larger after a larger layout).
    uint64_t atlasBytes() const { return layout_.atlasBytes(); }
    GLuint atlas() const { return atlas_; }

private:
    void mark(const PageDraw& draw);
    void allocate();
    void drawPages(const PageDraw& draw);
    void dispatchPhase(int phase, GLuint groups);

    IHost* host_ = nullptr;
    PageLayout layout_{};
    kit::Program mark_, cull_, clear_, depth_;
    std::array<kit::Program, 5> allocate_;   // [phase - 1]
    kit::Buffer pageTable_, requests_, state_, free_, dirty_, objects_, commands_, pairs_;
    kit::Texture atlas_, levelImage_;
    kit::Framebuffer framebuffer_;
    GLuint vao_ = 0;                          // the pair attribute of the page draws
    glm::ivec2 levelImageSize_{0};
    glm::ivec2 atlasSize_{0};                 // the atlas texture's size: the largest layout's so far
    std::array<size_t, 4> capacity_{};        // bytes of pageTable_, requests_, free_, dirty_ (grow only)
    uint32_t objectCount_ = 0;
    size_t objectCapacity_ = 0;               // casters objects_ and commands_ hold
    std::vector<uint32_t> freeList_;          // invalidate()'s upload, kept between calls
    uint32_t pairCapacity_ = 0;
    kit::ReadbackRing stats_;
    bool statsRead_ = false;
};

} // namespace shadowlab::virtual_sm
