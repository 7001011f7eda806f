// Declaring parameters once. A technique lists its parameters in ONE X-macro list; the kit
// expands it into the ParamDesc table, an index per parameter and a struct of typed values read
// from ParamValues, so the three cannot disagree:
//
//   #define PCF_PARAMS(X) X(int, resolution, kit::resolutionParam()) \  (one line a parameter)
//                         X(int, kernel, {"kernel", "kernel size n", ...}) ... SHADOWLAB_PCF_COMMON_PARAMS(X)
//   SHADOWLAB_PARAMS(Params, PCF_PARAMS);
//   constexpr TechniqueDesc kDescriptor = kit::describe({.id = "pcf", ...}, Params::table);
//   ...
//   const Params p = Params::read(params);   // p.kernel, p.constant_bias, ...; Params::Id::kernel
//
// X(type, id, descriptor...): `type` is the C++ type of the value (int for Int and Enum, float,
// bool, or an enum class read from the int), `id` the parameter's id spelt as an identifier (it
// must equal the descriptor's id: a static_assert checks it; a duplicated id redeclares an
// enumerator and a member, which does not compile either), `descriptor` a ParamDesc expression.
// Groups that several techniques declare alike (same id, range and help everywhere) are lists
// too (SHADOWLAB_DEPTH_MAP_PARAMS, SHADOWLAB_FIT_PARAMS, ...), spliced into a technique's list;
// kit::depthMapConfig(values) (depth_map.h) turns whichever of them a technique has into the
// kit's config.
#pragma once

#include <cstdint>
#include <string_view>
#include <type_traits>

#include <shadowlab/kit/descriptor.h>
#include <shadowlab/technique.h>

namespace shadowlab::kit {

// The index of parameter `id` in a table (a compile error when there is none).
template <size_t N>
consteval uint32_t paramIndex(const ParamDesc (&params)[N], std::string_view id) {
    for (size_t i = 0; i < N; ++i)
        if (std::string_view(params[i].id) == id) return uint32_t(i);
    throw "no parameter with this id";   // not a constant expression: a compile error
}

// A parameter's value as the type its list declares.
template <class T>
T readParam(const ParamValues& params, uint32_t index) {
    if constexpr (std::is_same_v<T, bool>) return params.asBool(index);
    else if constexpr (std::is_floating_point_v<T>) return T(params.asFloat(index));
    else if constexpr (std::is_enum_v<T>) return T(params.asInt(index));
    else return T(params.asInt(index));
}

consteval bool sameId(const ParamDesc& desc, std::string_view id) { return std::string_view(desc.id) == id; }

} // namespace shadowlab::kit

#define SHADOWLAB_PARAM_ID_(type, id, ...) id,
#define SHADOWLAB_PARAM_DESC_(type, id, ...) __VA_ARGS__,
#define SHADOWLAB_PARAM_FIELD_(type, id, ...) type id{};
#define SHADOWLAB_PARAM_READ_(type, id, ...) values.id = ::shadowlab::kit::readParam<type>(params, Id::id);
#define SHADOWLAB_PARAM_CHECK_(type, id, ...) \
    static_assert(::shadowlab::kit::sameId(table[Id::id], #id), "parameter " #id ": the descriptor's id differs");

// struct Name { struct Id { enum : uint32_t {...}; }; static constexpr ParamDesc table[]; fields...;
//               static Name read(const ParamValues&); } from an X-macro list (see the top).
#define SHADOWLAB_PARAMS(Name, LIST)                                                            \
    struct Name {                                                                               \
        struct Id {                                                                             \
            enum : uint32_t { LIST(SHADOWLAB_PARAM_ID_) count };                                \
        };                                                                                      \
        static constexpr ::shadowlab::ParamDesc table[] = {LIST(SHADOWLAB_PARAM_DESC_)};         \
        LIST(SHADOWLAB_PARAM_CHECK_)                                                            \
        LIST(SHADOWLAB_PARAM_FIELD_)                                                            \
        static Name read(const ::shadowlab::ParamValues& params) {                              \
            Name values;                                                                        \
            LIST(SHADOWLAB_PARAM_READ_)                                                         \
            return values;                                                                      \
        }                                                                                       \
    }

// Groups spliced into a technique's list. The shadow map of the depth-map techniques
// (kit/depth_map.h): resolution, depth format, bias and culling.
// The polygon offset alone (constant and slope-scaled), for maps drawn without a culling choice
// (kit/translucent_maps.h, stochastic-sm's map); SHADOWLAB_BIAS_PARAMS adds the culling.
#define SHADOWLAB_OFFSET_BIAS_PARAMS(X, constantBiasMax)                            \
    X(float, constant_bias, ::shadowlab::kit::constantBiasParam(constantBiasMax))  \
    X(float, slope_bias, ::shadowlab::kit::slopeBiasParam())
#define SHADOWLAB_BIAS_PARAMS(X, constantBiasMax, cullDefault) \
    SHADOWLAB_OFFSET_BIAS_PARAMS(X, constantBiasMax)           \
    X(int, cull, ::shadowlab::kit::cullParam(cullDefault))
#define SHADOWLAB_DEPTH_MAP_PARAMS(X, resolutionDefault, constantBiasMax, cullDefault) \
    X(int, resolution, ::shadowlab::kit::resolutionParam(resolutionDefault))           \
    X(int, depth_format, ::shadowlab::kit::depthFormatParam())                         \
    SHADOWLAB_BIAS_PARAMS(X, constantBiasMax, cullDefault)
// Fitting of a single map (kit/focus.h): fit and snap.
#define SHADOWLAB_FIT_PARAMS(X)                     \
    X(int, fit, ::shadowlab::kit::fitParam())       \
    X(bool, snap, ::shadowlab::kit::snapParam())
// The tail of the PCF family (pcf, adaptive-pcf, pcss): cone bias, the map's bias (culling off:
// every face casts, open and single-sided casters too), the two-layer biases (kit/layered_depth.h,
// which defines that group; kit::FilteredDepthMaps includes it) and the fit.
#define SHADOWLAB_PCF_COMMON_PARAMS(X)                  \
    X(bool, cone_bias, ::shadowlab::kit::coneBiasParam()) \
    SHADOWLAB_BIAS_PARAMS(X, 64, 0)                     \
    SHADOWLAB_TWO_LAYER_PARAMS(X)                       \
    SHADOWLAB_FIT_PARAMS(X)
// The map of the techniques that read its raw depths (rbsm, edtsm; kit::RawDepthTechnique in
// kit/depth_maps.h, which includes kit/layered_depth.h): shadowmap's resolution, format, bias and
// culling, and the two-layer biases.
#define SHADOWLAB_RAW_DEPTH_MAP_PARAMS(X)               \
    SHADOWLAB_DEPTH_MAP_PARAMS(X, 1024, 200000, 1)      \
    SHADOWLAB_TWO_LAYER_PARAMS(X)

namespace shadowlab::kit {

// A kit parameter (its id, label, type, range and default stated once, below) with the help text
// of a technique where it means more, e.g. a bias the shader adds or a resolution paid N times.
constexpr ParamDesc withHelp(ParamDesc desc, const char* help) {
    desc.help = help;
    return desc;
}

// An Enum parameter: its values are the indices of `options` ("a|b|c"), so the options alone
// state its range (0 to their count - 1), which a written-out range could contradict.
constexpr double enumOptionCount(std::string_view options) {
    double count = 1;
    for (const char c : options) count += c == '|' ? 1 : 0;
    return count;
}
constexpr ParamDesc enumParam(const char* id, const char* label, double defaultValue, const char* options,
                              const char* help) {
    return {id, label, ParamType::Enum, 0, enumOptionCount(options) - 1, defaultValue, "", help, options};
}

// Shadow-map parameters shared by the depth-map techniques (kit/depth_map.h).
constexpr ParamDesc resolutionParam(double defaultValue = 2048, double maxValue = 8192) {
    return {"resolution", "resolution", ParamType::Int, 256, maxValue, defaultValue, "texels",
            "Width and height of the shadow map. Low values make edges blocky and let texel steps show "
            "through a filter; memory and shadow-pass time grow with the square, and a kernel given in "
            "texels then covers less of the scene.",
            nullptr};
}
constexpr ParamDesc depthFormatParam() {
    return enumParam("depth_format", "depth format", 2, "16|24|32F",
            "Precision of the stored depth. 16-bit depth quantises coarsely and needs more bias.");
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
    return enumParam("cull", "cull in shadow pass", defaultValue, "none|back|front",
            "Faces culled while rendering the map. 'front' stores back faces only, which moves acne to the "
            "dark side of closed objects but leaks light at thin or open geometry.");
}
constexpr ParamDesc hardwareFilterParam(const char* label = "hardware 2x2 filter") {
    return {"hardware_filter", label, ParamType::Bool, 0, 1, 0, "",
            "Bilinear comparison filtering by the texture unit (sampler2DShadow with GL_LINEAR): smooths the "
            "staircase over one texel at almost no cost (seed 000 Fig. 3.11c against 3.11b).",
            nullptr};
}
// `hardware_filter` of the kernels that take it per tap (pcf, adaptive-pcf).
constexpr ParamDesc bilinearTapsParam() {
    return {"hardware_filter", "bilinear taps", ParamType::Bool, 0, 1, 0, "",
            "Each tap is the texture unit's 2x2 bilinear comparison, which removes the banding of plain taps "
            "and smooths penumbrae at small kernels for almost no cost (seed 000 Fig. 3.11c against 3.11b); off "
            "shows the n^2 + 1 discrete shades and the texel steps. Fractional taps rarely agree exactly, so "
            "adaptive-pcf's early out is taken less often.",
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
    return enumParam("fit", "fit", 0, "scene|frustum|focus-body",
            "What the map covers. scene: the whole scene, the same map every frame; in a large scene most "
            "texels land where the camera never looks. frustum: cropped to the camera frustum's corners in "
            "the light's view, clamped to the scene (seed 000 eq. 3.9-3.10); much sharper near the viewer, "
            "but the map moves with the camera (edges crawl: see snap) and a long far plane gives little "
            "gain. focus-body: cropped to B = ((V n S) + l) n S n L, the visible part of the scene swept "
            "towards the light (seed 002 eq. 4.2), usually the tightest; casters outside it are not drawn.");
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
