// Virtual shadow maps (sparse virtual shadow maps: Unreal Engine 5's default for directional
// lights; Blender EEVEE Next eevee_shadow.cc; StratusGFX Source/Shaders/vsm_*.cs; Frogfood
// data/shaders/shadows/vsm/, whose author co-wrote the GPU Zen 3 chapter). A directional light
// gets a virtual map of `virtual_size`^2 texels per clipmap level, `levels` levels of doubling
// texel size, each a window of 128 x 128-texel pages around the camera that moves in whole pages.
// Each frame, on the GPU alone (virtual_sm_pages.cpp): every visible pixel of the camera's
// depth-only pre-pass marks the page its lookup will read, at the level whose texels match its screen
// footprint (vsm_mark.comp); pages are allocated from a free list into a page table (both storage
// buffers, vsm_allocate.comp); only the newly allocated pages are cleared and drawn into a physical
// depth atlas of `physical_size`^2 texels, each caster culled against each page's light-space
// rectangle and drawn as one instance per page it touches (vsm_cull.comp, vsm_page_depth.vert).
// Pages stay cached across frames while the light, the scene and the bias stay the same (their
// content depends only on where they are in light space), so a still camera draws no page and a
// moving one draws only the pages that enter the windows. shadowTerm() (virtual_sm.glsl) reads
// through the page table with the 2x2 hardware comparison, or 3 x 3 of them (filter = pcf).
// Known artefacts: a change of sharpness where the level changes (every doubling of distance), a
// half-texel clamp at page borders (a tile's neighbour is another page), and pages missing when
// the marked pages exceed the atlas (counted as "pages failed": they read as lit).
// Spot and point lights: no virtual map; the kit's single map (physical_size) or cube (half of it
// a face), as `shadowmap` draws them.
#include <cmath>
#include <cstring>

#include <shadowlab/kit/depth_maps.h>
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>

#include "virtual_sm_pages.h"

namespace {

using namespace shadowlab;
using virtual_sm::PageLayout;
using virtual_sm::VsmObject;

constexpr ParamDesc kVirtualSize{"virtual_size", "virtual size", ParamType::Int, 4096, 32768, 16384, "texels",
     "Width and height of each clipmap level of the virtual map (16384: 128 x 128 pages of 128 texels, "
     "UE5's default). Larger levels reach farther at each texel size, so fewer pixels fall to coarse levels, "
     "at the cost of a larger page table; rounded down to whole pages.",
     nullptr};
constexpr ParamDesc kPhysicalSize{"physical_size", "physical atlas", ParamType::Int, 1024, 8192, 4096, "texels",
     "The memory budget, a 32-bit depth map of this side: the atlas the resident pages live in and its page "
     "buffers together. 4096 is 64 MiB, csm 4 x 2048's memory: an atlas of 928 pages (4096 x 3712) and 5 MiB "
     "of buffers. When a view marks more pages than fit, the excess read as lit (the statistic 'pages failed').",
     nullptr};
constexpr ParamDesc kLevels{"levels", "clipmap levels", ParamType::Int, 1, 16, 10, "",
     "Levels of doubling texel size; the coarsest window holds the whole scene. More levels give finer texels "
     "near the camera (the finest is the coarsest's / 2^(levels - 1)).",
     nullptr};
constexpr ParamDesc kLevelBias{"level_bias", "level bias", ParamType::Float, -3, 4, -1, "levels",
     "Added to the level each pixel's footprint asks for (level 0: texels at most the pixel's size): -1, the "
     "default, gives texels of a half to one pixel, as UE5's directional lights (LOD bias -1.5); positive "
     "values read coarser pages (fewer pages, blurrier edges), negative ones finer (four times the pages a level).",
     nullptr};
constexpr ParamDesc kFilter = kit::enumParam("filter", "filter", 0, "hardware|pcf",
     "hardware: one 2x2 bilinear comparison by the texture unit; pcf: 3 x 3 of them, one texel apart (each tap "
     "through the page table), a ramp about three texels wide.");
constexpr ParamDesc kNormalOffset{"normal_offset", "normal offset", ParamType::Float, 0, 4, 0.5, "texels",
     "The lookup point moves along the surface normal by this many texels of its level: removes acne on "
     "surfaces lit at grazing angles, which constant and slope bias cannot reach at every level.",
     nullptr};
constexpr ParamDesc kDebugLevels{"debug_levels", "page levels tint", ParamType::Bool, 0, 1, 0, "",
     "Tints each pixel by the clipmap level it reads (red, green, blue, yellow, ...): bright where its page was "
     "drawn this frame, dimmer where it came from the cache.",
     nullptr};
constexpr ParamDesc kDebugImages{"debug_images", "debug images", ParamType::Bool, 0, 1, 0, "",
     "Writes the 'page levels' image (each pixel's level as marked) for the debug views; the 'physical atlas' "
     "image is always there.",
     nullptr};

#define VIRTUAL_SM_PARAMS(X)               \
    X(int, virtual_size, kVirtualSize)     \
    X(int, physical_size, kPhysicalSize)   \
    X(int, levels, kLevels)                \
    X(float, level_bias, kLevelBias)       \
    X(int, filter, kFilter)                \
    X(float, normal_offset, kNormalOffset) \
    X(bool, debug_levels, kDebugLevels)    \
    X(bool, debug_images, kDebugImages)    \
    SHADOWLAB_BIAS_PARAMS(X, 64, 1)
SHADOWLAB_PARAMS(Params, VIRTUAL_SM_PARAMS);

using VsmUniforms = shared::virtual_sm::VsmUniforms;

// Everything a cached page's content depends on: when any of it changes, every page is redrawn.
struct CacheKey {
    glm::vec3 lightDirection{0.0f};
    Bounds scene;
    uint32_t objects = 0, indices = 0;
    PageLayout layout;
    float constantBias = 0.0f, slopeBias = 0.0f;
    int cull = 0;
    float pixelAngle = 0.0f;   // 2 tan(fovY / 2) / height: sets the coarsest level's texel
    bool operator==(const CacheKey& o) const {
        return pixelAngle == o.pixelAngle && lightDirection == o.lightDirection && scene.min == o.scene.min && scene.max == o.scene.max &&
               objects == o.objects && indices == o.indices && layout == o.layout && constantBias == o.constantBias &&
               slopeBias == o.slopeBias && cull == o.cull;
    }
};

class VirtualShadowMaps final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        uniforms_.create(host(), "virtual-sm uniforms");
        return pages_.create(host(), error) && maps_.create(host(), error);
    }
    void shutdown() override { pages_.destroy(); }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        const Params p = Params::read(params);
        if (frame.light.type != LightType::Directional) {
            // One map (a cube of half the side for point lights): what `shadowmap` draws.
            const int side = frame.light.type == LightType::Point ? p.physical_size / 2 : p.physical_size;
            maps_.render(frame, {.resolution = side, .constantBias = p.constant_bias, .slopeBias = p.slope_bias,
                                 .cull = kit::Cull(p.cull)});
            return;
        }
        const Adjacency* adjacency = static_cast<const Adjacency*>(host().extension(SHADOWLAB_EXT_ADJACENCY));
        const AdjacencyScene* casters = adjacency ? adjacency->scene(adjacency->context) : nullptr;
        const PageLayout layout = PageLayout{.levels = std::clamp(p.levels, 1, VSM_MAX_LEVELS),
                                .pagesPerSide = std::max(1, p.virtual_size / VSM_PAGE_TEXELS),
                                .atlasPages = std::max(1, p.physical_size / VSM_PAGE_TEXELS)}
                                   .fitRows();
        const CacheKey key{frame.light.direction, host().bounds(DrawSet::All), host().objectCount(),
                           casters ? casters->indices : 0u, layout, p.constant_bias, p.slope_bias, p.cull,
                           2.0f / (frame.camera.projection[1][1] * float(std::max(1, frame.camera.viewport.y)))};
        if (!(key == key_)) {
            key_ = key;
            pages_.configure(layout);
            pages_.invalidate();
            fitLightSpace(frame.light.direction, layout, casters, key.pixelAngle);
        }
        writeUniforms(frame, p, layout);
        GpuPass pass(host(), "shadow map");
        pages_.render({.prepass = static_cast<const CameraPrepass*>(host().extension(SHADOWLAB_EXT_CAMERA_PREPASS)),
                       .inverseViewProjection = glm::inverse(frame.camera.viewProjection),
                       .scene = casters, .constantBias = p.constant_bias, .slopeBias = p.slope_bias, .cull = p.cull,
                       .levelImage = p.debug_images});
        pages_.reportStatistics(host());
    }

    void bindMainPass(const FrameContext& frame, const ParamValues&) override {
        if (frame.light.type != LightType::Directional)
            return maps_.bindMainPass(frame, SamplerKind::CompareLinear, SamplerKind::CompareLinear);
        uniforms_.bind();
        pages_.bindMainPass();
    }

    // The light's orthographic space (a fixed basis: page contents never depend on the camera),
    // the levels' texel sizes (powers of two, so every page edge is exact in float) and the
    // casters' light-space rectangles for the cull pass.
    void fitLightSpace(glm::vec3 direction, const PageLayout& layout, const AdjacencyScene* casters, float pixelAngle) {
        const glm::vec3 z = glm::normalize(direction);
        const glm::vec3 hint = std::abs(z.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::vec3 x = glm::normalize(glm::cross(z, hint)), y = glm::cross(x, z);
        lightView_ = glm::transpose(glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), glm::vec4(0, 0, 0, 1)));
        auto lightRect = [&](const Bounds& b, glm::vec2& zRange) {
            glm::vec4 rect(1e30f, 1e30f, -1e30f, -1e30f);
            for (int c = 0; c < 8; ++c) {
                const glm::vec3 corner((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y, (c & 4) ? b.max.z : b.min.z);
                const glm::vec3 l = glm::vec3(lightView_ * glm::vec4(corner, 1.0f));
                rect = {std::min(rect.x, l.x), std::min(rect.y, l.y), std::max(rect.z, l.x), std::max(rect.w, l.y)};
                zRange = {std::min(zRange.x, l.z), std::max(zRange.y, l.z)};
            }
            return rect;
        };
        glm::vec2 zRange(1e30f, -1e30f);
        const glm::vec4 scene = lightRect(host().bounds(DrawSet::All), zRange);
        const float slack = 1e-3f * std::max(1.0f, zRange.y - zRange.x);
        depthRange_ = {zRange.x - slack, zRange.y + slack};
        // The coarsest window (its pages around the camera) spans at least twice the scene, so it holds
        // all of it; and its texels are at least the footprint of a pixel as far away as the scene's
        // diagonal, so no pixel asks for coarser texels than exist (clamped to the coarsest level,
        // a far pixel would need many texels, and the whole view's pages: dense at small sizes).
        const float extent = std::max({scene.z - scene.x, scene.w - scene.y, 1e-3f});
        const float farthest = pixelAngle * glm::length(host().bounds(DrawSet::All).max - host().bounds(DrawSet::All).min);
        const float coarsest = std::exp2(std::ceil(std::log2(
            std::max(2.0f * extent / float(layout.pagesPerSide * VSM_PAGE_TEXELS), farthest))));
        finestTexel_ = coarsest / std::exp2(float(layout.levels - 1));
        std::vector<VsmObject> objects;
        const ObjectInfo* info = host().objects();
        for (uint32_t b = 0; casters && b < casters->batchCount; ++b) {
            const AdjacencyBatch& batch = casters->batches[b];
            for (uint32_t o = batch.firstObject; o < batch.firstObject + batch.objectCount; ++o) {
                if (!info[o].castsShadow() || info[o].translucent()) continue;
                glm::vec2 ignored(1e30f, -1e30f);
                objects.push_back({lightRect(info[o].bounds, ignored), batch.firstTriangle, batch.triangleCount,
                                   batch.baseVertex, o});
            }
        }
        pages_.setObjects(objects);
        objectCount_ = uint32_t(objects.size());
    }

    void writeUniforms(const FrameContext& frame, const Params& p, const PageLayout& layout) {
        VsmUniforms u{};
        u.uLightView = lightView_;
        const glm::vec2 camera(lightView_ * glm::vec4(frame.camera.position, 1.0f));
        for (int level = 0; level < layout.levels; ++level) {
            const float texel = finestTexel_ * std::exp2(float(level));
            const float page = texel * float(VSM_PAGE_TEXELS);
            // The window's first page: centred on the camera, moved in whole pages.
            const glm::vec2 first = glm::floor(camera / page) - float(layout.pagesPerSide / 2);
            u.uLevel[level] = {first.x, first.y, page, texel};
        }
        u.uVsmDepth = {depthRange_.x, 1.0f / (depthRange_.y - depthRange_.x), p.normal_offset, p.level_bias};
        u.uVsmSizes = {layout.levels, layout.pagesPerSide, layout.atlasPages, std::clamp(p.filter, 0, 1)};
        u.uVsmOptions = {p.debug_levels ? 1 : 0, int(objectCount_), layout.physicalPages(),
                         int(frame.frameIndex & 0x7FFFFFFFu)};
        uniforms_.set(u);
    }

    virtual_sm::VirtualPages pages_;
    kit::UniformBlock<VsmUniforms> uniforms_;
    kit::DepthMaps maps_;   // spot and point lights
    CacheKey key_;
    glm::mat4 lightView_{1.0f};
    glm::vec2 depthRange_{0.0f, 1.0f};
    float finestTexel_ = 1.0f;
    uint32_t objectCount_ = 0;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::Family{TranslucencyModel::Ignore, kit::views::kNone},
    {.id = "virtual-sm",
     .displayName = "Virtual shadow maps",
     .category = "hard",
     .explanation = "One huge shadow map per clipmap level around the camera, split into 128 x 128 pages, of which "
                    "only the pages the visible pixels need are rendered, into a fixed atlas. The camera's depth marks "
                    "pages at the level each pixel's screen size asks for, so texels are as fine as pixels near and far. "
                    "Pages stay cached while the light and scene stand still: a still camera draws nothing. Turn on the "
                    "page levels tint and move the camera.",
     .shadowGlsl = "virtual_sm.glsl",
     .flags = kTechniqueNeedsCameraDepth},   // the mark pass rebuilds positions from depth alone
    Params::table);

} // namespace

SHADOWLAB_PLUGIN(VirtualShadowMaps, kDescriptor)
