// The kit's depth maps switched by light type: the 2D depth map (kit/depth_map.h) under
// directional and spot lights, the cube (kit/cube_depth_map.h) under point lights. LayeredDepthMaps
// makes the same switch with a LayeredDepthMap as its 2D map (the two-layer biases of seed 002
// ch. 5): the techniques that read the 2D map's raw depths (rbsm, edtsm) through RawDepthTechnique
// below, and the filtering techniques' FilteredDepthMaps (kit/filtered_depth_maps.h), which adds
// the depth-range mips.
#pragma once

#include <string>

#include <shadowlab/technique.h>

#include "shadowlab/kit/cube_depth_map.h"
#include "shadowlab/kit/depth_map.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/layered_depth.h"
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

// DepthMaps' switch with the two-layer biases (SHADOWLAB_TWO_LAYER_PARAMS): with `midpoint` or
// `second-depth` both layers are peeled and resolved into the one map map() returns (eq. 5.1's
// surface per texel, LayeredDepthMap::resolve()), so whatever reads a plain depth map (a
// comparison, a kernel's taps, raw texel fetches, a compute pass) reads the biased surface
// unchanged. With `offset` (the default) it is the plain depth pass, bit for bit. The peeled and
// resolved textures are allocated on the first two-layer frame (kept until unload). The cube keeps
// the offset, as shadowmap's does.
class LayeredDepthMaps {
public:
    bool create(IHost& host, std::string& error) { return map_.create(host, error, true) && cube_.create(host, error); }

    // The frame's map: the cube under a point light (false), else the 2D map with the biasing
    // method of `layered`, resolved (true).
    bool render(const FrameContext& frame, const DepthMapConfig& config, const LayeredDepthConfig& layered = {}) {
        if (frame.light.type == LightType::Point) {
            cube_.render(frame, config);
            return false;
        }
        map_.render(frame, config, layered);
        map_.resolve();
        return true;
    }

    // The map this frame rendered, with `sampling` (2D) or `cubeSampling` (cube).
    void bindMainPass(const FrameContext& frame, SamplerKind sampling, SamplerKind cubeSampling) const {
        if (frame.light.type == LightType::Point)
            cube_.bindMainPass(cubeSampling);
        else
            map().bindMainPass(sampling);
    }

    // The 2D map the main pass reads (the resolved layers under a two-layer method).
    const DepthMap& map() const { return map_.compareMap(); }
    const CubeDepthMap& cube() const { return cube_; }

private:
    LayeredDepthMap map_;
    CubeDepthMap cube_;
};

// A technique whose main pass does its own tests on the 2D map's raw depths (rbsm, edtsm), its
// parameters `Params` (a SHADOWLAB_PARAMS struct with SHADOWLAB_RAW_DEPTH_MAP_PARAMS and
// SHADOWLAB_FIT_PARAMS: the same pass, bias and fit as shadowmap, and its two-layer biases) and
// its own main-pass block `Block`: setup, the map's pass and bindMainPass are done here; the
// plugin states its block's values in configure(). The raw depths are LayeredDepthMaps' map():
// under `midpoint` and `second-depth` the resolved surface, which every texel test and compute
// pass of the technique then reads as it reads plain depths. Point lights get the cube with the
// plain comparison (offset only) and no block.
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

    // The frame's map (LayeredDepthMaps::render): true when it is the 2D map.
    bool renderMap(const FrameContext& frame, const Params& p) {
        return maps_.render(frame, depthMapConfig(p), layeredDepthConfig(p));
    }
    // The 2D map's depths the technique reads (resolved under a two-layer method).
    const DepthMap& map() const { return maps_.map(); }

private:
    LayeredDepthMaps maps_;
    UniformBlock<Block> uniforms_;
};

} // namespace shadowlab::kit
