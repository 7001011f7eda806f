// The maps of the filtering techniques on the kit's depth maps (pcf, adaptive-pcf, pcss): the 2D
// depth map under directional and spot lights, the cube under point lights (kit/cube_depth_map.h),
// and the 2D map's depth-range mips (kit/depth_range_mips.h), which bound every depth a kernel can
// read. A technique adds its kernel: reported with map().reportFilter(), its sampling chosen in
// bindMainPass().
// The 2D map is a kit::LayeredDepthMap, so the techniques have the two-layer biases of seed 002
// ch. 5 (SHADOWLAB_TWO_LAYER_PARAMS, in SHADOWLAB_PCF_COMMON_PARAMS): with `midpoint` or
// `second-depth` both layers are peeled and resolved into the one map map() returns (eq. 5.1's
// surface per texel, LayeredDepthMap::resolve()), which every tap, gather, mip and blocker search
// reads unchanged. With `offset` (the default) it is the plain depth pass, bit for bit. The cube
// keeps the offset, as shadowmap's does.
#pragma once

#include <string>

#include <shadowlab/technique.h>

#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/depth_range_mips.h"
#include "shadowlab/kit/layered_depth.h"

namespace shadowlab::kit {

class FilteredDepthMaps {
public:
    bool create(IHost& host, std::string& error) {
        return map_.create(host, error, true) && cube_.create(host, error) && depthRange_.create(host, error);
    }

    // The frame's map: the cube under a point light (false), else the 2D map with the biasing
    // method of `layered` (true: its kernel is reported and its mips updated next).
    bool render(const FrameContext& frame, const DepthMapConfig& config, const LayeredDepthConfig& layered = {}) {
        if (frame.light.type == LightType::Point) {
            cube_.render(frame, config);
            return false;
        }
        map_.render(frame, config, layered);
        map_.resolve();
        return true;
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
        if (frame.light.type == LightType::Point)
            cube_.bindMainPass(cubeSampling);
        else
            map().bindMainPass(sampling);
        depthRange_.bindMainPass();
    }

    // The 2D map the main pass compares against (the resolved layers under a two-layer method).
    const DepthMap& map() const { return map_.compareMap(); }
    const CubeDepthMap& cube() const { return cube_; }

private:
    LayeredDepthMap map_;
    CubeDepthMap cube_;
    DepthRangeMips depthRange_;
};

} // namespace shadowlab::kit
