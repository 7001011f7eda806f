// The maps of the filtering techniques on the kit's depth maps (pcf, adaptive-pcf, pcss): the 2D
// depth map under directional and spot lights, the cube under point lights (kit/cube_depth_map.h),
// and the 2D map's depth-range mips (kit/depth_range_mips.h), which bound every depth a kernel can
// read. A technique adds its kernel: reported with map().reportFilter(), its sampling chosen in
// bindMainPass().
// The 2D map and the cube are kit::LayeredDepthMaps (kit/depth_maps.h), so the techniques have the
// two-layer biases of seed 002 ch. 5 (SHADOWLAB_TWO_LAYER_PARAMS, in SHADOWLAB_PCF_COMMON_PARAMS):
// with `midpoint` or `second-depth` both layers are resolved into the one map map() returns (eq.
// 5.1's surface per texel), which every tap, gather, mip and blocker search reads unchanged. With
// `offset` (the default) it is the plain depth pass, bit for bit. The cube keeps the offset.
#pragma once

#include <string>

#include <shadowlab/technique.h>

#include "shadowlab/kit/depth_maps.h"
#include "shadowlab/kit/depth_range_mips.h"

namespace shadowlab::kit {

class FilteredDepthMaps {
public:
    bool create(IHost& host, std::string& error) {
        return maps_.create(host, error) && depthRange_.create(host, error);
    }

    // The frame's map: the cube under a point light (false), else the 2D map with the biasing
    // method of `layered` (true: its kernel is reported and its mips updated next).
    bool render(const FrameContext& frame, const DepthMapConfig& config, const LayeredDepthConfig& layered = {}) {
        return maps_.render(frame, config, layered);
    }

    // After render() of the 2D map: its depth-range mips built when `wanted` (allocated on first use
    // and when the resolution changes), freed otherwise. The cube path leaves them as they are.
    void updateDepthRange(bool wanted) {
        if (wanted)
            depthRange_.build(map().texture(), map().resolution(), "depth-range mips");
        else
            depthRange_.reset();
    }

    // The map this frame rendered, with `sampling` (2D) or `cubeSampling` (cube), and the mips.
    void bindMainPass(const FrameContext& frame, SamplerKind sampling, SamplerKind cubeSampling) const {
        maps_.bindMainPass(frame, sampling, cubeSampling);
        depthRange_.bindMainPass();
    }

    // The 2D map the main pass compares against (the resolved layers under a two-layer method).
    const DepthMap& map() const { return maps_.map(); }
    const CubeDepthMap& cube() const { return maps_.cube(); }

private:
    LayeredDepthMaps maps_;
    DepthRangeMips depthRange_;
};

} // namespace shadowlab::kit
