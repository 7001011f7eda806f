// Depth-range mips of a depth map: level 0 is half the map's size, each texel the minimum (r) and
// maximum (g) of (a little more than) the 2 x 2 texels below it, built after the shadow pass by
// one full-screen draw per level (shaders/depth_range_mips.frag). Read with depthRangeIn
// (shaders/depth_range.glsl) to bound every depth in a kernel's region with at most four fetches:
// pcss narrows its blocker search with the minimum and stops where the whole region blocks;
// adaptive-pcf decides lit and shadowed pixels before its ring of taps, pcf before its n x n kernel
// (depthRangeInTexels). Reallocated with the map only.
#pragma once

#include <algorithm>
#include <string>

#include <glad/gl.h>
#include <shadowlab/technique.h>

#include "shadowlab/kit/depth_range_mips_shared.h"
#include "shadowlab/kit/fullscreen_pass.h"
#include "shadowlab/kit/handles.h"

namespace shadowlab::kit {

class DepthRangeMips {
public:
    bool create(IHost& host, std::string& error) {
        host_ = &host;
        for (auto& level : levelUniforms_) level.create(host, "depth-range level");
        return pass_.create(host, "depth_range_mips.frag", "depth-range mips", error);
    }

    // Builds the mips of `depthMap` (resolution x resolution, level 0), allocating them first when
    // the size changed. `label` names them in the memory table and the debug images.
    void build(GLuint depthMap, int resolution, const char* label) {
        ensure(resolution, label);
        GpuPass pass(*host_, label);
        pass_.begin();
        glBindSampler(shared::depth_range::kDepthRangeSourceUnit, 0);   // raw depths, whatever a main pass left bound
        for (int level = 0; level < levels_ && level < kMaxLevels; ++level) {
            pass_.attach(mips_, level);
            const int size = std::max(size_ >> level, 1);
            // Level 0 reads the depth map (its level 0); level k reads level k - 1 of the same
            // texture by explicit lod: written by the previous draw (made visible by the barrier),
            // disjoint from the level being written.
            if (level == 0) {
                glBindTextureUnit(shared::depth_range::kDepthRangeSourceUnit, depthMap);
            } else {
                glTextureBarrier();
                glBindTextureUnit(shared::depth_range::kDepthRangeSourceUnit, mips_);
            }
            levelUniforms_[size_t(level)].bind();
            pass_.draw({size, size});
        }
        glBindTextureUnit(shared::depth_range::kDepthRangeSourceUnit, 0);
    }

    void bindMainPass() const { glBindTextureUnit(shared::depth_range::kDepthRangeMipsUnit, mips_); }
    // Frees the mips (a technique that stops using them).
    void reset() {
        mips_.reset();
        size_ = 0;
    }
    GLuint texture() const { return mips_; }

private:
    void ensure(int resolution, const char* label) {
        const int size = std::max(resolution / 2, 1);
        if (mips_ && size == size_) return;
        size_ = size;
        levels_ = 1;
        while ((size >> levels_) > 0) ++levels_;
        mips_ = makeTexture(*host_, {.internalFormat = GL_RG32F, .width = size, .height = size, .levels = levels_,
                                     .label = label});
        glTextureParameteri(mips_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTextureParameteri(mips_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        host_->registerDebugImage(label, mips_, DebugImageKind::Depth);
        for (int level = 0; level < kMaxLevels; ++level)
            levelUniforms_[size_t(level)].update({{}, std::max(level - 1, 0), level == 0 ? 1 : 0, 0, 0});
    }

    static constexpr int kMaxLevels = 16;   // maps up to 2^17 texels wide
    IHost* host_ = nullptr;
    FullscreenPass pass_;
    Texture mips_;
    int size_ = 0;
    int levels_ = 0;
    // One block per level, written once per allocation: the source level (level - 1; level 0 of
    // the depth map for the first) and whether the source is the map.
    UniformBlock<shared::depth_range::DepthRangeLevelUniforms> levelUniforms_[kMaxLevels];
};

} // namespace shadowlab::kit
