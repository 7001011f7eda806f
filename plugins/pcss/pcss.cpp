// Percentage-closer soft shadows (Fernando 2005; seed 000 sections 2.2.8, 3.2.6 and 4.3.3). One
// shadow map; per pixel a blocker search averages the depths of the occluders inside the cone
// from the shaded point to the light (eq. 3.17-3.18), the penumbra width follows from similar
// triangles (eq. 3.19-3.20), and PCF with that radius filters the shadow, so shadows harden near
// contacts and soften with the caster's height. Both the search and the filter use the jittered
// disc sets of adaptive PCF (m x m sets, outer ring first, early out in the filter).
// Light size: host.light().size is a world radius for spot and point lights (eq. 3.17 as is,
// s_lw = radius, s_lf = the map's width at the near plane) and an angular radius alpha in
// radians for directional lights, whose map is orthographic and has no light position: the
// shader uses the limit of a light of radius D tan(alpha) at distance D -> infinity, i.e. a
// light-space width of tan(alpha) per unit of depth: penumbra radius (z_r - z_b) tan(alpha) world
// units, search radius (z_r - z_near) tan(alpha), both divided by the map's world width for uv.
// Deviation from eq. 3.18 (parameter search_bound, on by default): its n (the near plane) is
// replaced, per pixel, by the nearest depth stored in the search region, read from the kit's
// depth-range mips built after the shadow pass: the same cone, bounded where a blocker can
// actually be. With search_bound = depth-range (the default) the same mips' farthest depth also
// ends the pixel where the whole region is in front of it (fully shadowed, the same result). With the
// map fitted around a large ground, a spot or point light's near plane sits almost at the light
// and the printed formula spreads the n_s^2 search samples over half the map, missing the casters.
// Known artefacts: the average blocker depth flattens overlapping occluders at different heights
// (scene `overlap`: penumbrae too wide under the high plate's edge or too narrow), the search
// undersamples small or thin blockers (light leaks, popping), samples stretch outside the
// blockers' region of the map, the search and filter cost two kernels per pixel, noise from the
// jittered sets, and acne under large kernels without the cone bias. Not physically correct: it
// assumes blocker, receiver and light planar and parallel.
// The shadow map and the disc sets are the kit's (depth_map.h, disc_offset_texture.h, shared with
// pcf and adaptive-pcf); GLSL in shaders/disc_sampling.glsl.
// Point lights: the kit's cube map (kit/cube_depth_map.h) and the same three steps in cube space
// (pcss.glsl, pcssCube): offsets as tangents of angles across the ray from the light, the search
// cone and the penumbra by the same similar triangles with radial distances, and min-depth mips
// per face (a 2D array of six layers built from the cube) whose lookups may cross face seams.
#include <algorithm>
#include <cmath>

#include <shadowlab/kit/disc_offset_texture.h>
#include <shadowlab/kit/filtered_depth_maps.h>
#include <shadowlab/kit/fullscreen_pass.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "pcss_shared.h"

namespace {

using namespace shadowlab;

// The parameters of its own (the list below splices them with the kit's groups).
constexpr ParamDesc kSearchGrid{"search_grid", "search samples n_s", ParamType::Int, 2, 16, 6, "",
     "Blocker search: n_s x n_s jittered disc samples. Few samples miss small or thin blockers (light "
     "leaks, flickering penumbra widths); many cost n_s^2 depth reads in every pixel, lit or not.", nullptr};
constexpr ParamDesc kFilterGrid{"filter_grid", "filter samples n_f", ParamType::Int, 2, 16, 8, "",
     "Filtering: n_f x n_f jittered disc samples scaled to the estimated penumbra. Few samples give "
     "coarse, noisy penumbrae; many cost n_f^2 lookups in penumbra pixels (the outer ring decides elsewhere).",
     nullptr};
constexpr ParamDesc kBilinear{"bilinear", "bilinear taps", ParamType::Bool, 0, 1, 1, "",
     "Each filter tap compares the 2x2 nearest texels and blends them (what the texture unit's GL_LINEAR "
     "comparison does). Off: narrow penumbrae near contacts alias and the noise is coarser.", nullptr};
constexpr ParamDesc kSearchBound = kit::enumParam("search_bound", "blocker search bound", 2, "near plane|min-depth|depth-range",
     "Where the blocker search assumes the nearest blocker can be. 'near plane' is eq. 3.18 as printed: "
     "fine for a tight orthographic map, but a spot or point light whose map reaches close to the light "
     "searches half the map and misses small casters (missing or blotchy shadows). 'min-depth' narrows the "
     "search to the cone at the nearest depth stored in the region (depth-range mips, one extra pass). "
     "'depth-range' also stops, without searching, where the farthest depth stored in the region is in front "
     "of the receiver: every search and filter tap would be a blocker, so the pixel is fully shadowed (the "
     "same image as 'min-depth', fewer lookups).");

#define PCSS_PARAMS(X)                         \
    X(int, resolution, kit::resolutionParam()) \
    X(int, search_grid, kSearchGrid)           \
    X(int, filter_grid, kFilterGrid)           \
    X(int, sets, kit::discSetsParam())         \
    X(bool, bilinear, kBilinear)               \
    X(int, search_bound, kSearchBound)         \
    SHADOWLAB_PCF_COMMON_PARAMS(X)
SHADOWLAB_PARAMS(Params, PCSS_PARAMS);

class PercentageCloserSoftShadows final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        uniforms_.create(host(), "pcss uniforms");
        cubeMinDepthUniforms_.create(host(), "pcss cube min-depth uniforms");
        return maps_.create(host(), error) &&
               cubeMinDepthPass_.create(host(), "pcss_cube_min_depth.frag", "cube min-depth mips", error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        const int sets = p.sets;
        searchOffsets_.ensure(host(), p.search_grid, sets, "search disc offsets (m x m x n_s^2/2)", 2);
        filterOffsets_.ensure(host(), p.filter_grid, sets, "filter disc offsets (m x m x n_f^2/2)");
        // Raw depths: the blocker search reads them (sampled without comparison).
        if (!maps_.render(frame, kit::depthMapConfig(p), kit::layeredDepthConfig(p))) {
            // The cube path bounds its search with min-depth mips per face (search_bound >= 1).
            if (p.search_bound >= 1) {
                ensureCubeMinDepth(maps_.cube().resolution());
                buildCubeMinDepthMips();
            } else {
                cubeMinDepth_.reset();
                cubeMinDepthSize_ = 0;
            }
            return;
        }
        // The blocker search and filter discs pcss.glsl uses (eq. 3.17-3.20), for the host's kernel view.
        maps_.map().reportFilter({.kernel = FilterKernel::Pcss,
                                  .taps = filterOffsets_.n(),
                                  .bilinear = p.bilinear ? 1u : 0u,
                                  .sets = sets,
                                  .discSeed = 1,     // filterOffsets_.ensure's default
                                  .searchTaps = searchOffsets_.n(),
                                  .searchSeed = 2,   // as searchOffsets_.ensure above
                                  .searchBound = uint32_t(p.search_bound),
                                  .lightSize = lightSizeInLightSpace(frame.light),
                                  .coneBias = p.cone_bias ? 1.0f : 0.0f});
        maps_.updateDepthRange(p.search_bound >= 1);   // eq. 3.18 as printed needs no mips
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        using namespace shared::pcss;
        const Params p = Params::read(params);
        // The 2D map raw (the search reads depths); the cube compares (the bilinear taps).
        maps_.bindMainPass(frame, SamplerKind::Nearest, SamplerKind::CompareLinear);
        if (frame.light.type == LightType::Point) {
            glBindTextureUnit(kCubeRawUnit, maps_.cube().texture());
            glBindSampler(kCubeRawUnit, host().sampler(SamplerKind::Nearest));
            glBindTextureUnit(kCubeMinDepthUnit, cubeMinDepth_);
        }
        glBindTextureUnit(kSearchOffsetsUnit, searchOffsets_.texture());
        glBindTextureUnit(kFilterOffsetsUnit, filterOffsets_.texture());
        glBindTextureUnit(kCompareUnit, maps_.map().texture());
        glBindSampler(kCompareUnit, host().sampler(SamplerKind::CompareLinear));
        uniforms_.set({{}, searchOffsets_.n(), filterOffsets_.n(), p.cone_bias ? 1.0f : 0.0f,
                       lightSizeInLightSpace(frame.light), p.bilinear ? 1 : 0, p.search_bound, 0, 0});
    }

    // What pcss.glsl's uLightSize holds: the world radius for a perspective map (spot, point); for
    // an orthographic map (directional light) tan(angular radius), the light's width per unit of
    // depth in the limit described at the top of this file. Capped below 90 degrees.
    float lightSizeInLightSpace(const LightInfo& light) const {
        if (light.type == LightType::Point || maps_.map().lightSpace().perspective) return light.size;
        return std::tan(std::min(light.size, 1.4f));
    }

    // The cube's min-depth mips: a 2D array of six layers (face i of the cube in layer i), level 0
    // half the face's size; reallocated with the cube only.
    void ensureCubeMinDepth(int resolution) {
        const int size = std::max(resolution / 2, 1);
        if (cubeMinDepth_ && size == cubeMinDepthSize_) return;
        cubeMinDepthSize_ = size;
        cubeMinDepthLevels_ = 1;
        while ((size >> cubeMinDepthLevels_) > 0) ++cubeMinDepthLevels_;
        cubeMinDepth_ = kit::makeTexture(host(), {.target = GL_TEXTURE_2D_ARRAY, .internalFormat = GL_R32F, .width = size,
                                                  .height = size, .depth = 6, .levels = cubeMinDepthLevels_,
                                                  .label = "min-depth mips (cube faces)"});
        glTextureParameteri(cubeMinDepth_, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
        glTextureParameteri(cubeMinDepth_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }

    // Level by level, face by face (one draw into one layer of one level each: 6 per level); the
    // source level and face are the pass's block (PcssCubeMinDepthUniforms), written before each draw.
    void buildCubeMinDepthMips() {
        GpuPass pass(host(), "min-depth mips");
        cubeMinDepthPass_.begin();
        cubeMinDepthUniforms_.bind();
        glBindTextureUnit(shared::pcss::kCubeMinDepthSourceUnit, maps_.cube().texture());
        glBindSampler(shared::pcss::kCubeMinDepthSourceUnit, host().sampler(SamplerKind::Nearest));
        glBindTextureUnit(shared::pcss::kMinDepthSourceUnit, cubeMinDepth_);
        glBindSampler(shared::pcss::kMinDepthSourceUnit, 0);
        for (int level = 0; level < cubeMinDepthLevels_; ++level) {
            // Level k reads level k - 1 by explicit lod, written by the previous draws (see
            // buildMinDepthMips), disjoint from the level being written.
            if (level > 0) glTextureBarrier();
            const int size = std::max(cubeMinDepthSize_ >> level, 1);
            for (int face = 0; face < 6; ++face) {
                cubeMinDepthPass_.attach(cubeMinDepth_, level, face);
                cubeMinDepthUniforms_.update({{}, level - 1, face, maps_.cube().resolution(), 0});
                cubeMinDepthPass_.draw({size, size});
            }
        }
        glBindTextureUnit(shared::pcss::kCubeMinDepthSourceUnit, 0);
        glBindSampler(shared::pcss::kCubeMinDepthSourceUnit, 0);
        glBindTextureUnit(shared::pcss::kMinDepthSourceUnit, 0);
    }

    kit::FilteredDepthMaps maps_;
    kit::FullscreenPass cubeMinDepthPass_;   // pcss_cube_min_depth.frag into one face's layer of a level
    kit::Texture cubeMinDepth_;
    int cubeMinDepthSize_ = 0;
    int cubeMinDepthLevels_ = 0;
    jittered_disk::DiscOffsetTexture searchOffsets_;
    jittered_disk::DiscOffsetTexture filterOffsets_;
    kit::UniformBlock<shared::pcss::PcssUniforms> uniforms_;
    kit::UniformBlock<shared::pcss::PcssCubeMinDepthUniforms> cubeMinDepthUniforms_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFilteredMap,
    {.id = "pcss",
     .displayName = "Percentage-closer soft shadows",
     .category = "soft",
     .explanation = "Soft shadows from one shadow map: each pixel first searches the map for occluders between it and the "
                   "light, averages their depth, estimates the penumbra width from the light's size by similar triangles, "
                   "and then filters with a kernel of that width (PCF). Shadows are hard where a caster touches the "
                   "receiver and soften with distance (contact hardening). The light size comes from the scene "
                   "(--light-size). Plausible rather than correct: overlapping blockers at different depths are averaged.",
     .shadowGlsl = "pcss.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(PercentageCloserSoftShadows, kDescriptor)
