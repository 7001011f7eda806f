// Descriptor pieces from the kit. A technique on the kit writes its TechniqueDesc with
// kit::describe(), which fills in the parameter table (kit/params.h), the flag conditions with
// their count, and the fields a family of techniques shares: how its maps treat translucent
// casters and which of the host's debug views they feed. The technique states only its own
// fields (id, names, explanation, GLSL file, the flags no condition covers):
//
//   constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
//       {.id = "shadowmap", .displayName = ..., .category = "hard", .explanation = ..., .shadowGlsl = ...},
//       Params::table);
#pragma once

#include <cstddef>
#include <cstdint>

#include <shadowlab/technique.h>

namespace shadowlab::kit {

// The host's debug views (TechniqueDesc::debugViews) the kit's maps feed.
namespace views {
// A 2D map reported with kit/shadow_map_report.h: texel footprint, texel grid, the map's coverage.
inline constexpr const char kMap[] = "footprint|texel-grid|coverage";
// ... fitted by kit/focus.h, whose `fit = focus-body` body the host can draw.
inline constexpr const char kFittedMap[] = "footprint|texel-grid|coverage|focus-body";
// ... that also reports the filter kernel it reads (DepthMap::reportFilter).
inline constexpr const char kFilteredMap[] = "kernel|footprint|texel-grid|coverage|focus-body";
// None of them: no map the host can inspect (its own debug images are listed as it reports them).
inline constexpr const char kNone[] = "";
} // namespace views

// What a family of techniques states alike in its descriptor.
struct Family {
    TranslucencyModel translucencyModel;
    const char* debugViews;
};
// Maps of the opaque casters only (DrawSet::OpaqueCasters): translucent casters cast nothing.
inline constexpr Family kOpaqueMap{TranslucencyModel::Ignore, views::kMap};
inline constexpr Family kOpaqueFittedMap{TranslucencyModel::Ignore, views::kFittedMap};
inline constexpr Family kOpaqueFilteredMap{TranslucencyModel::Ignore, views::kFilteredMap};
// Maps translucent casters write into too, each judged by the model its casters implement.
// kit/translucent_maps.h's D_o, D_t and C: the modified model (M3) whichever variant writes C.
inline constexpr Family kTranslucentMap{TranslucencyModel::ModifiedTranslucent, views::kMap};
// kit/stochastic_light_pass.h, a depth map keeping each translucent fragment with probability
// alpha: coverage (M1); a colour map of per-channel depths where photons stop: physical (M2).
inline constexpr Family kStochasticMap{TranslucencyModel::Coverage, views::kMap};
inline constexpr Family kStochasticColourMap{TranslucencyModel::Physical, views::kMap};
// No map the host's views can read (their own debug images are listed as they report them):
// maps of the opaque casters kept to themselves (area-reference's N maps a frame); the casters'
// geometry itself, translucent casters blocking like opaque ones (planar projection, shadow
// volumes); rays through the scene's triangles, transmission coloured (raytraced).
inline constexpr Family kOpaqueMapsUnviewed{TranslucencyModel::Ignore, views::kNone};
inline constexpr Family kCasterGeometry{TranslucencyModel::Opaque, views::kNone};
inline constexpr Family kTracedRays{TranslucencyModel::Physical, views::kNone};

// The descriptor with its parameter table filled in.
template <size_t N>
constexpr TechniqueDesc describe(TechniqueDesc desc, const ParamDesc (&params)[N]) {
    desc.params = params;
    desc.paramCount = uint32_t(N);
    return desc;
}

// ... and with the flags that hold only for some parameter values (count from the array). Each
// condition's flags join `flags` (what the technique may ask for), so a flag is named once.
template <size_t N, size_t C>
constexpr TechniqueDesc describe(TechniqueDesc desc, const ParamDesc (&params)[N], const FlagCondition (&conditions)[C]) {
    desc.flagConditions = conditions;
    desc.flagConditionCount = uint32_t(C);
    for (const FlagCondition& condition : conditions) desc.flags |= condition.flags;
    return describe(desc, params);
}

// ... and with a family's translucency model and debug views.
template <size_t N, class... Conditions>
constexpr TechniqueDesc describe(const Family& family, TechniqueDesc desc, const ParamDesc (&params)[N],
                                 const Conditions&... conditions) {
    desc.translucencyModel = family.translucencyModel;
    desc.debugViews = family.debugViews;
    return describe(desc, params, conditions...);
}

} // namespace shadowlab::kit
