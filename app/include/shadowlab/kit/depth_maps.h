// The kit's depth maps switched by light type: the 2D depth map (kit/depth_map.h) under
// directional and spot lights, the cube (kit/cube_depth_map.h) under point lights. shadowmap uses
// them as they are; the filtering techniques through FilteredDepthMaps (kit/filtered_depth_maps.h),
// which adds the 2D map's depth-range mips.
#pragma once

#include <string>

#include <shadowlab/technique.h>

#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/depth_map.h"

namespace shadowlab::kit {

class DepthMaps {
public:
    bool create(IHost& host, std::string& error) { return map_.create(host, error) && cube_.create(host, error); }

    // The frame's map: the cube under a point light (false), else the 2D map (true).
    bool render(const FrameContext& frame, const DepthMapConfig& config) {
        if (frame.light.type == LightType::Point) {
            cube_.render(frame, config);
            return false;
        }
        map_.render(frame, config);
        return true;
    }

    // The map this frame rendered, with `sampling` (2D) or `cubeSampling` (cube).
    void bindMainPass(const FrameContext& frame, SamplerKind sampling, SamplerKind cubeSampling) const {
        if (frame.light.type == LightType::Point)
            cube_.bindMainPass(cubeSampling);
        else
            map_.bindMainPass(sampling);
    }

    const DepthMap& map() const { return map_; }
    const CubeDepthMap& cube() const { return cube_; }

private:
    DepthMap map_;
    CubeDepthMap cube_;
};

} // namespace shadowlab::kit
