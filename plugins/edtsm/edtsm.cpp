// Euclidean distance transform shadow mapping (after Macedo and Apolinario, "Euclidean Distance
// Transform Soft Shadow Mapping", SIBGRAPI 2017, and "Improved anti-aliasing for Euclidean distance
// transform shadow mapping", Computers & Graphics 2017: seed 004's first research slide;
// docs/anti-aliased-edges.md says how this light-space version departs from their screen-space one).
// A plain shadow map (kit/depth_map.h), then compute passes (edtsm.comp): the seed pass marks the
// map's depth edges, texels beside a neighbour more than `edge depth` farther from (caster side)
// or nearer to (background side) the light, and jump flooding spreads each kind of site over
// `reach` texels, giving every texel its nearest site of each kind. The main pass (edtsm.glsl)
// turns the receiver's distances to the two into a signed distance to the rebuilt edge and a ramp
// `width` texels wide across it, wherever the two sites straddle the receiver's own depth test.
// Point lights: the kit's cube map with the plain test.
#include <algorithm>
#include <array>

#include <shadowlab/kit/depth_maps.h>
#include <shadowlab/kit/params.h>

#include "edtsm_shared.h"

namespace {

using namespace shadowlab;
using shared::edtsm::EdtPassUniforms;

constexpr ParamDesc kWidth{"width", "transition width", ParamType::Float, 0.05, 4, 0.25, "texels",
     "Width of the ramp across the rebuilt edge, in map texels. Small: a sharp edge that follows the "
     "distance transform's bisector (staircase corners cut); 1 and more: a smooth edge, but every texel of a "
     "caster only a texel or two wide in the map turns partly lit (against a hard reference the error grows "
     "with the width: 0.25 gave the least on cube and spheres).",
     nullptr};
constexpr ParamDesc kReach{"reach", "reach", ParamType::Int, 1, 32, 4, "texels",
     "How far the distance transform floods from the edge texels: ceil(log2(reach)) + 2 compute passes over "
     "the map. Receivers farther from any edge keep the plain test, which is what they get anyway.",
     nullptr};
constexpr ParamDesc kEdgeDepth{"edge_depth", "edge depth", ParamType::Float, 0.001, 10, 0.5, "world units",
     "Depth step between neighbouring texels that marks a caster's silhouette in the map, and how far in "
     "front of a receiver the caster must lie. Too small: a surface steep to the light is taken for edges "
     "all over; too large: casters close to their receivers keep the plain, jagged edge.",
     nullptr};

#define EDTSM_PARAMS(X)                                 \
    SHADOWLAB_DEPTH_MAP_PARAMS(X, 1024, 200000, 1)      \
    X(float, width, kWidth)                             \
    X(int, reach, kReach)                               \
    X(float, edge_depth, kEdgeDepth)                    \
    SHADOWLAB_FIT_PARAMS(X)
SHADOWLAB_PARAMS(Params, EDTSM_PARAMS);

// The jump steps for a reach: the largest power of two not above it, halving to 1, then 1 again
// (the extra round of "JFA+1" fixes most of jump flooding's rare misses).
int edtJumpSteps(int reach, std::array<int, 8>& steps) {
    int step = 1, count = 0;
    while (step * 2 <= reach) step *= 2;
    for (; step >= 1; step /= 2) steps[size_t(count++)] = step;
    steps[size_t(count++)] = 1;
    return count;
}

class DistanceTransformShadows final : public kit::RawDepthTechnique<Params, shared::edtsm::EdtMainUniforms> {
    bool setup(std::string& error) override {
        for (auto& block : passUniforms_) block.create(host(), "edtsm pass");
        return RawDepthTechnique::setup(error) && passes_.build(host(), {.computeFile = "edtsm.comp"}, error);
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        if (renderMap(frame, p)) distanceTransform(p);   // 2D maps only
    }

    shared::edtsm::EdtMainUniforms configure(const Params& p) const override {
        return {{}, p.width, float(p.reach) + 1.0f, p.edge_depth, 0.0f};
    }

    void bindMainPass(const FrameContext& frame, const ParamValues& params) override {
        RawDepthTechnique::bindMainPass(frame, params);
        if (frame.light.type == LightType::Point) return;
        glBindTextureUnit(shared::edtsm::kEdtSitesUnit, sites_[result_]);
        glBindSampler(shared::edtsm::kEdtSitesUnit, 0);
    }

    // Seeds into sites_[0], then each jump reads one texture and writes the other. Image stores
    // reach the next pass's fetches only after a barrier; the last one also covers the main pass.
    void distanceTransform(const Params& p) {
        ensureSites(map().resolution());
        GpuPass pass(host(), "distance transform");
        std::array<int, 8> steps{};
        const int jumps = edtJumpSteps(p.reach, steps);
        map().bindMainPass(SamplerKind::Nearest);   // raw depths and the light's depth range (block 1)
        passes_.use();
        const GLuint groups = GLuint(size_ + 7) / 8u;   // edtsm.comp's 8 x 8 groups
        for (int k = 0; k <= jumps; ++k) {
            const int target = k % 2;
            passUniforms_[size_t(k)].set({{}, k == 0 ? 0 : steps[size_t(k - 1)], 0, p.edge_depth, 0.0f});
            glBindTextureUnit(shared::edtsm::kEdtSitesUnit, k == 0 ? 0u : GLuint(sites_[1 - target]));
            glBindImageTexture(shared::edtsm::kEdtSitesImageUnit, sites_[target], 0, GL_FALSE, 0, GL_WRITE_ONLY,
                               GL_RGBA32F);
            glDispatchCompute(groups, groups, 1);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            result_ = target;
        }
        glBindImageTexture(shared::edtsm::kEdtSitesImageUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindTextureUnit(shared::edtsm::kEdtSitesUnit, 0);
    }

    // Two site textures the map's size, reallocated with it only.
    void ensureSites(int resolution) {
        if (sites_[0] && resolution == size_) return;
        size_ = resolution;
        for (auto& sites : sites_) {
            sites = kit::makeTexture(host(), {.internalFormat = GL_RGBA32F, .width = size_, .height = size_,
                                              .label = "edtsm nearest sites"});
            glTextureParameteri(sites, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(sites, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
    }

    kit::Program passes_;
    kit::Texture sites_[2];
    int size_ = 0;
    int result_ = 0;
    kit::UniformBlock<EdtPassUniforms> passUniforms_[9];   // the seed and up to 8 jumps (reach 32: 32..1, 1)
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kOpaqueFittedMap,
    {.id = "edtsm",
     .displayName = "Distance transform shadow mapping",
     .category = "hard",
     .explanation = "A plain shadow map whose casters' silhouettes (depth edges) are found in compute and spread "
                    "over a few texels by jump flooding, a Euclidean distance transform on the GPU. Each receiver "
                    "near an edge takes its distances to the nearest occluding and the nearest background edge "
                    "texel as a signed distance to the edge, and a ramp a fraction of a texel wide replaces the "
                    "staircase. Edges that are not depth edges (a receiver shadowing itself) stay hard.",
     .shadowGlsl = "edtsm.glsl"},
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(DistanceTransformShadows, kDescriptor)
