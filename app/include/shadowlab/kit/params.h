// Declaring parameters once. A technique lists its ParamDesc table and derives its index enum
// from it, so the two cannot disagree (a misspelt id does not compile):
//
//   constexpr ParamDesc kParams[] = {kit::resolutionParam(2048), {"kernel", ...}};
//   enum : uint32_t { kResolution = kit::paramIndex(kParams, "resolution"), kKernel = kit::paramIndex(kParams, "kernel") };
//   const TechniqueDesc kDescriptor = kit::describe({.id = "pcf", ...}, kParams);
//
// Also the parameters several techniques declare alike (same id, range and help everywhere).
#pragma once

#include <cstdint>
#include <string_view>

#include <shadowlab/technique.h>

namespace shadowlab::kit {

template <size_t N>
consteval uint32_t paramIndex(const ParamDesc (&params)[N], std::string_view id) {
    for (size_t i = 0; i < N; ++i)
        if (std::string_view(params[i].id) == id) return uint32_t(i);
    throw "no parameter with this id";   // not a constant expression: a compile error
}

// The descriptor with its parameter table filled in.
template <size_t N>
constexpr TechniqueDesc describe(TechniqueDesc desc, const ParamDesc (&params)[N]) {
    desc.params = params;
    desc.paramCount = uint32_t(N);
    return desc;
}

// Shadow-map parameters shared by the depth-map techniques (kit/depth_map.h).
constexpr ParamDesc resolutionParam(double defaultValue = 2048) {
    return {"resolution", "resolution", ParamType::Int, 256, 8192, defaultValue, "texels",
            "Width and height of the shadow map. Low values make edges blocky and let texel steps show "
            "through a filter; memory and shadow-pass time grow with the square, and a kernel given in "
            "texels then covers less of the scene.",
            nullptr};
}
constexpr ParamDesc depthFormatParam() {
    return {"depth_format", "depth format", ParamType::Enum, 0, 2, 2, "",
            "Precision of the stored depth. 16-bit depth quantises coarsely and needs more bias.", "16|24|32F"};
}
constexpr ParamDesc constantBiasParam(double maxValue = 64) {
    return {"constant_bias", "constant bias", ParamType::Float, 0, maxValue, 2, "units",
            "glPolygonOffset units: a constant push of stored depths away from the light, in steps of the "
            "depth format's smallest difference (2^-24 of the range near depth 1 for 24-bit and 32F). Zero "
            "shows acne; large values detach shadows from their casters (peter panning).",
            nullptr};
}
constexpr ParamDesc slopeBiasParam() {
    return {"slope_bias", "slope-scaled bias", ParamType::Float, 0, 16, 2, "",
            "glPolygonOffset factor: bias growing with the caster's slope as seen from the light, where acne "
            "is worst (grazing light). Zero leaves acne on tilted surfaces; large values push shadows off "
            "grazing contacts.",
            nullptr};
}
constexpr ParamDesc cullParam(double defaultValue = 1) {
    return {"cull", "cull in shadow pass", ParamType::Enum, 0, 2, defaultValue, "",
            "Faces culled while rendering the map. 'front' stores back faces only, which moves acne to the "
            "dark side of closed objects but leaks light at thin or open geometry.",
            "none|back|front"};
}
constexpr ParamDesc hardwareFilterParam(const char* label = "hardware 2x2 filter") {
    return {"hardware_filter", label, ParamType::Bool, 0, 1, 0, "",
            "Bilinear comparison filtering by the texture unit (sampler2DShadow with GL_LINEAR): smooths the "
            "staircase over one texel at almost no cost (seed 000 Fig. 3.11c against 3.11b).",
            nullptr};
}
constexpr ParamDesc coneBiasParam() {
    return {"cone_bias", "cone bias", ParamType::Bool, 0, 1, 1, "",
            "Receiver bias growing with each sample's distance from the kernel centre, scaled by the "
            "receiver's slope against the light (seed 000 sec. 3.2.4, last paragraph). Off: wide kernels "
            "darken lit surfaces (acne, worst on tilted receivers); on: clean, with slight peter panning at "
            "contacts under wide kernels.",
            nullptr};
}

// Fitting of a single map (kit/focus.h): the `fit` and `snap` parameters of every single-map technique.
constexpr ParamDesc fitParam() {
    return {"fit", "fit", ParamType::Enum, 0, 2, 0, "",
            "What the map covers. scene: the whole scene, the same map every frame; in a large scene most "
            "texels land where the camera never looks. frustum: cropped to the camera frustum's corners in "
            "the light's view, clamped to the scene (seed 000 eq. 3.9-3.10); much sharper near the viewer, "
            "but the map moves with the camera (edges crawl: see snap) and a long far plane gives little "
            "gain. focus-body: cropped to B = ((V n S) + l) n S n L, the visible part of the scene swept "
            "towards the light (seed 002 eq. 4.2), usually the tightest; casters outside it are not drawn.",
            "scene|frustum|focus-body"};
}
constexpr ParamDesc snapParam() {
    return {"snap", "snap to texels", ParamType::Bool, 0, 1, 0, "",
            "With fit frustum or focus-body: moves the crop in whole texels and sizes it in whole texels of "
            "a fixed grid (seed 000 sec. 2.2.5), so shadow edges stay still while the camera moves instead "
            "of crawling and flickering. Costs up to one texel of coverage per side; the size still changes "
            "in small steps when the camera turns.",
            nullptr};
}

} // namespace shadowlab::kit
