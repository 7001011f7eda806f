// The frame of a single map focused on B and then warped (lispsm, tsm): the view-depth range
// (kit/receiver_range.h, `range`), the focus (kit/focus.h, always the focus body, `snap` for the
// uniform fallback), the technique's warp, and the depth pass of kit::LayeredDepthMap (fragment
// bias, linear depth, two layers). A technique derives from WarpedMapTechnique<Params> and gives
// its warp; its Params hold resolution, SHADOWLAB_WARPED_MAP_PARAMS (range, the bias group,
// hardware_filter, snap) and the two-layer group. Under a point light a technique that gives
// faceWarp() (lispsm) gets one map per cube face instead (kit/warped_faces.h), each warped or
// focused on its face's body; its GLSL reads warpedOrFacesShadow() (shaders/warped_faces.glsl).
#pragma once

#include <optional>

#include <shadowlab/kit/layered_depth.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/receiver_range.h>
#include <shadowlab/kit/technique_base.h>
#include <shadowlab/kit/warped_faces.h>

// What the warped map reads besides resolution and the two layers: the view depths to warp for,
// the bias (constant bias up to 65536 units; front faces culled, back faces stored by default:
// seed 002 sec. 9.3, Fig. 5.6), the hardware 2x2 filter and snap (the uniform fallback's).
#define SHADOWLAB_WARPED_MAP_PARAMS(X)                                     \
    X(int, range, ::shadowlab::kit::warpRangeParam())                      \
    SHADOWLAB_BIAS_PARAMS(X, 65536, 2)                                     \
    X(bool, hardware_filter, ::shadowlab::kit::hardwareFilterParam())      \
    X(bool, snap, ::shadowlab::kit::snapParam())

namespace shadowlab::kit {

template <class Params>
class WarpedMapTechnique : public TechniqueBase {
protected:
    // The whole matrix (world -> clip, projective) of the map focused by `focused`, or none: the
    // focused uniform map. `range`: the view depths to warp for.
    virtual std::optional<glm::mat4> warp(const FrameContext& frame, const Params& p, const FocusedLightSpace& focused,
                                          const DepthRange& range) = 0;
    // Whether the map stores linear depth along the light (else the matrix's own z).
    virtual bool linearDepth(const Params& p) const = 0;
    // Whether point lights get one map per cube face (faceWarp()); else one focused map (the host's
    // frustum, at most 160 degrees, as for a spot light).
    virtual bool warpsCubeFaces() const { return false; }
    // A point light's matrix for one face (world -> clip, projective), or none: the face's map
    // focused on its body B_f.
    virtual std::optional<glm::mat4> faceWarp(const FrameContext&, const Params&, const CubeFaceFocus&, const DepthRange&) {
        return std::nullopt;
    }

private:
    // The faces' program and block only for a technique that draws them (tsm never does).
    bool setup(std::string& error) override {
        return maps_.create(host(), error) && range_.create(host(), error) && (!warpsCubeFaces() || faces_.create(host(), error));
    }
    void shutdown() override { range_.destroy(); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const DepthMapConfig config = depthMapConfig(p);
        // Before the map's timer scope: the receivers' reduction is a pass of its own.
        const DepthRange range = range_.range(frame, p.range == 1);
        GpuPass pass(host(), "shadow map");
        pointFaces_ = frame.light.type == LightType::Point && warpsCubeFaces();
        if (pointFaces_) {
            renderFaces(frame, p, config, range);
            return;
        }
        if (warpsCubeFaces()) faces_.deactivate();
        const FocusedLightSpace focused = focusLightSpace(host(), frame, {Fit::FocusBody, bool(p.snap)}, config.resolution);
        maps_.drawWarped(focused, warp(frame, p, focused, range), config, layeredDepthConfig(p), linearDepth(p));
    }

    // The faces that see a visible point, each warped by faceWarp() or focused on B_f.
    void renderFaces(const FrameContext& frame, const Params& p, const DepthMapConfig& config, const DepthRange& range) {
        const Bounds scene = host().bounds(DrawSet::All);
        const auto warpOf = [&](const CubeFaceFocus& face) { return faceWarp(frame, p, face, range); };
        const int resolution = faces_.faceResolution(config.resolution);
        const std::vector<FaceMap> maps =
            faceMaps(cubeFaceFocus(frame.camera, frame.light, scene), warpOf, scene, bool(p.snap), resolution);
        faces_.setLight(frame.light.position);
        faces_.draw(maps, config, layeredDepthConfig(p), linearDepth(p), scene);
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        const SamplerKind sampling = Params::read(params).hardware_filter ? SamplerKind::CompareLinear : SamplerKind::CompareNearest;
        maps_.bindMainPass(sampling);
        if (pointFaces_) faces_.bindMainPass(sampling);
        else if (warpsCubeFaces()) faces_.bindInactive();
    }

    LayeredDepthMap maps_;
    WarpedFaceMaps faces_;
    bool pointFaces_ = false;   // this frame's map is the faces
    ReceiverRange range_;
};

} // namespace shadowlab::kit
