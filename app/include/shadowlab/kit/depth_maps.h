// The kit's depth maps switched by light type: the 2D depth map (kit/depth_map.h) under
// directional and spot lights, the cube (kit/cube_depth_map.h) under point lights. The techniques
// that read the 2D map's raw depths (rbsm, edtsm) through RawDepthTechnique below. The filtering
// techniques' FilteredDepthMaps (kit/filtered_depth_maps.h) makes the same switch with a
// LayeredDepthMap as its 2D map (the two-layer biases) and adds the depth-range mips.
#pragma once

#include <string>

#include <shadowlab/technique.h>

#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/depth_map.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/technique_base.h"

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

// A technique whose main pass does its own tests on the 2D map's raw depths (rbsm, edtsm), its
// parameters `Params` (a SHADOWLAB_PARAMS struct with SHADOWLAB_DEPTH_MAP_PARAMS and
// SHADOWLAB_FIT_PARAMS: the same pass, bias and fit as shadowmap) and its own main-pass block
// `Block`: setup, the map's pass and bindMainPass are done here; the plugin states its block's
// values in configure(). Point lights get the cube with the plain comparison and no block.
template <class Params, class Block>
class RawDepthTechnique : public TechniqueBase {
protected:
    // The technique's block for this frame (directional and spot lights).
    virtual Block configure(const Params& p) const = 0;

    bool setup(std::string& error) override {
        uniforms_.create(host(), "technique uniforms");
        return maps_.create(host(), error);
    }
    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        renderMap(frame, Params::read(params));
    }
    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        maps_.bindMainPass(frame, SamplerKind::Nearest, SamplerKind::CompareNearest);
        if (frame.light.type != LightType::Point) uniforms_.set(configure(Params::read(params)));
    }

    // The frame's map (DepthMaps::render): true when it is the 2D map.
    bool renderMap(const FrameContext& frame, const Params& p) { return maps_.render(frame, depthMapConfig(p)); }
    const DepthMap& map() const { return maps_.map(); }

private:
    DepthMaps maps_;
    UniformBlock<Block> uniforms_;
};

} // namespace shadowlab::kit
