// The maps of the filtering techniques on the kit's depth map (pcf, adaptive-pcf, pcss): the 2D
// depth map under directional and spot lights, the cube under point lights (kit/depth_maps.h), and
// the 2D map's depth-range mips (kit/depth_range_mips.h), which bound every depth a kernel can read. A technique adds its kernel: reported with map().reportFilter(), its
// sampling chosen in bindMainPass().
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

    // The frame's map: the cube under a point light (false), else the 2D map (true: its kernel is
    // reported and its mips updated next).
    bool render(const FrameContext& frame, const DepthMapConfig& config) { return maps_.render(frame, config); }

    // After render() of the 2D map: its depth-range mips built when `wanted` (allocated on first use
    // and when the resolution changes), freed otherwise. The cube path leaves them as they are.
    void updateDepthRange(bool wanted) {
        if (wanted)
            depthRange_.build(maps_.map().texture(), maps_.map().resolution(), "depth-range mips");
        else
            depthRange_.reset();
    }

    // The map this frame rendered, with `sampling` (2D) or `cubeSampling` (cube), and the mips.
    void bindMainPass(const FrameContext& frame, SamplerKind sampling, SamplerKind cubeSampling) const {
        maps_.bindMainPass(frame, sampling, cubeSampling);
        depthRange_.bindMainPass();
    }

    const DepthMap& map() const { return maps_.map(); }
    const CubeDepthMap& cube() const { return maps_.cube(); }

private:
    DepthMaps maps_;
    DepthRangeMips depthRange_;
};

} // namespace shadowlab::kit
