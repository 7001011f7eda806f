// Euclidean distance transform shadow mapping (after Macedo and Apolinario, "Euclidean Distance
// Transform Soft Shadow Mapping", SIBGRAPI 2017, and "Improved anti-aliasing for Euclidean distance
// transform shadow mapping", Computers & Graphics 2017: seed 004's first research slide;
// docs/anti-aliased-edges.md says how this light-space version departs from their screen-space one).
// shadowmap's map (kit::RawDepthTechnique: the same pass, bias and fit; with `bias_method` midpoint
// or second-depth, seed 002 eq. 5.1, both layers resolved into the one map of depths that the
// compute passes and the main pass read), then compute passes (edtsm.comp): the seed pass marks the
// map's depth edges, texels beside a neighbour more than `edge depth` farther from (caster side)
// or nearer to (background side) the light, and jump flooding spreads each kind of site over
// `reach` texels, giving every texel its nearest site of each kind (over the tiles near edges
// only: the seed pass flags them, a pass lists them for an indirect dispatch). The main pass (edtsm.glsl)
// turns the receiver's distances to the two into a signed distance to the rebuilt edge and a ramp
// `width` texels wide across it, wherever the two sites straddle the receiver's own depth test.
// Point lights: the kit's cube map with the plain test and the offset.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <string>
#include <vector>

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
     "the 16 x 16 tiles near edges. Receivers farther from any edge keep the plain test, which is what they "
     "get anyway.",
     nullptr};
constexpr ParamDesc kEdgeDepth{"edge_depth", "edge depth", ParamType::Float, 0.001, 10, 0.5, "world units",
     "Depth step between neighbouring texels that marks a caster's silhouette in the map, and how far in "
     "front of a receiver the caster must lie. Too small: a surface steep to the light is taken for edges "
     "all over; too large: casters close to their receivers keep the plain, jagged edge.",
     nullptr};

#define EDTSM_PARAMS(X)                                 \
    SHADOWLAB_RAW_DEPTH_MAP_PARAMS(X)                   \
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

// How far a site can travel in the flood (each pass moves it at most one step, per axis): the
// texels beyond it from every edge texel hold no site after the dense flood either.
int edtFloodSpan(const std::array<int, 8>& steps, int count) {
    int span = 0;
    for (int k = 0; k < count; ++k) span += steps[size_t(k)];
    return span;
}

class DistanceTransformShadows final : public kit::RawDepthTechnique<Params, shared::edtsm::EdtMainUniforms> {
    bool setup(std::string& error) override {
        for (auto& block : passUniforms_) block.create(host(), "edtsm pass");
        const char* dense = std::getenv("SHADOWLAB_EDTSM_DENSE");
        dense_ = dense && std::string(dense) == "1";
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

    // Seeds into both site textures, lists the tiles within the flood's reach of an edge, then
    // each jump reads one texture and writes the other, over the listed tiles only (edtsm.comp).
    // Image and storage writes reach the next pass only after a barrier (the indirect arguments
    // after the command barrier); the last one also covers the main pass. No readback: the count
    // stays on the GPU. SHADOWLAB_EDTSM_DENSE=1 (read at setup) floods the whole map instead, the
    // reference the sparse flood must match bit for bit (tests/test_anti_aliased_edges.cpp).
    void distanceTransform(const Params& p) {
        using namespace shared::edtsm;
        ensureSites(map().resolution());
        GpuPass pass(host(), "distance transform");
        std::array<int, 8> steps{};
        const int jumps = edtJumpSteps(p.reach, steps);
        map().bindMainPass(SamplerKind::Nearest);   // raw depths and the light's depth range (block 1)
        passes_.use();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEdtTileMaskBinding, tileMask_);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kEdtTileListBinding, tileList_);
        const GLuint tiles = GLuint(size_ + int(kEdtTile) - 1) / kEdtTile;
        passUniforms_[0].set({{}, 0, 0, p.edge_depth, 0.0f});
        glBindTextureUnit(kEdtSitesUnit, 0);
        glBindImageTexture(kEdtSitesImageUnit, sites_[0], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(kEdtSeedCopyImageUnit, sites_[1], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(tiles, tiles, 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                        GL_SHADER_STORAGE_BARRIER_BIT);
        if (!dense_) listTiles(edtFloodSpan(steps, jumps), tiles);
        result_ = 0;
        for (int k = 1; k <= jumps; ++k) {
            const int target = k % 2;
            passUniforms_[size_t(k + 1)].set({{}, steps[size_t(k - 1)], dense_ ? 0 : 1, p.edge_depth, 0.0f});
            glBindTextureUnit(kEdtSitesUnit, sites_[1 - target]);
            glBindImageTexture(kEdtSitesImageUnit, sites_[target], 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
            if (dense_)
                glDispatchCompute(tiles, tiles, 1);
            else
                glDispatchComputeIndirect(0);
            glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
            result_ = target;
        }
        glBindImageTexture(kEdtSitesImageUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindImageTexture(kEdtSeedCopyImageUnit, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glBindTextureUnit(kEdtSitesUnit, 0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }

    // The tile list: the count zeroed (its 1, 1 stay from creation), one invocation per tile
    // appends those within `span` texels' worth of tiles of an edge tile, and the count becomes
    // the jumps' indirect dispatch. The barrier also orders next frame's clear after the atomics.
    void listTiles(int span, GLuint tiles) {
        using namespace shared::edtsm;
        const GLuint zero = 0;
        glClearNamedBufferSubData(tileList_, GL_R32UI, 0, sizeof(GLuint), GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &zero);
        passUniforms_[1].set({{}, -1, (span + int(kEdtTile) - 1) / int(kEdtTile), 0.0f, 0.0f});
        glDispatchCompute((tiles + kEdtTile - 1) / kEdtTile, (tiles + kEdtTile - 1) / kEdtTile, 1);
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, tileList_);
    }

    // Two site textures the map's size, the tile flags and the tile list (three words of
    // indirect arguments, a pad, a word per tile), reallocated with the map only.
    void ensureSites(int resolution) {
        if (sites_[0] && resolution == size_) return;
        size_ = resolution;
        for (auto& sites : sites_) {
            sites = kit::makeTexture(host(), {.internalFormat = GL_RGBA32F, .width = size_, .height = size_,
                                              .label = "edtsm nearest sites"});
            glTextureParameteri(sites, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(sites, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        }
        const size_t tiles = size_t((size_ + int(shared::edtsm::kEdtTile) - 1) / int(shared::edtsm::kEdtTile));
        tileMask_ =
            kit::Buffer(host(), host().createBuffer(tiles * tiles * sizeof(GLuint), nullptr, 0, "edtsm tile flags"));
        std::vector<GLuint> list(4 + tiles * tiles, 0u);
        list[1] = list[2] = 1u;
        tileList_ = kit::Buffer(host(), host().createBuffer(list.size() * sizeof(GLuint), list.data(), 0,
                                                            "edtsm active tiles"));
    }

    kit::Program passes_;
    kit::Texture sites_[2];
    kit::Buffer tileMask_, tileList_;
    bool dense_ = false;   // SHADOWLAB_EDTSM_DENSE=1: jump over the whole map (the sparse path's reference)
    int size_ = 0;
    int result_ = 0;
    kit::UniformBlock<EdtPassUniforms> passUniforms_[10];   // seeds, tile list, up to 8 jumps (reach 32: 32..1, 1)
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
