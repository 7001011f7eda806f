// Composited translucent shadows (seed 001 sec. 4.2.3, the report's own technique; timed in
// sec. 5.3.1, Figs. 5.3.E/F; judged in sec. 5.3.3, Fig. 5.3.3.A). It builds on translucent shadows
// (kit/translucent_maps.h: D_o, D_t, C and visibility = o (t + (1 - t) C)):
//   - the opaque geometry is shaded exactly as translucent shadows shade it, with maps of every
//     translucent caster (renderShadows);
//   - the translucent geometry is partitioned, and each partition is shaded with maps of only the
//     translucent casters that can shadow it, then composited back to front over the opaque image
//     with ordinary alpha blending. The partition is the seed's ("Leveraging sorted geometry"):
//     one partition per translucent mesh, drawn in the host's back-to-front camera order; before
//     each mesh m, D_t and C are rebuilt from the translucent casters nearer the light than m by
//     their bounds' centres (the seed's light sort), D_o kept. Two passes per mesh, each drawing up
//     to all the others: O(N^2) draws, so real time only for small N (Fig. 5.3.F).
// The host's translucent-draws hook (SHADOWLAB_EXT_TRANSLUCENT_DRAWS) runs before each translucent
// mesh, in the main pass and in the evaluation's translucent layers alike.
//
// The partition's two requirements (sec. 4.2.3): (1) no mesh in the same partition as a mesh it
// occludes from the light: met per mesh, as long as the centre order agrees with occlusion; it
// fails for meshes that interleave from the light (a mesh partly in front of and partly behind
// another), or a large mesh whose centre lies behind a small one it covers; (2) partitions
// composite correctly: met because each is a single mesh drawn in the camera order, failing only
// where the camera order itself fails (intersecting or interleaved meshes).
// Why depth peeling failed as a partition (sec. 4.2.3, Figs. 5.2.3.B/C): peeled from the light,
// one layer can hold two meshes that a third lies between as seen from the camera, so the layers
// cannot be composited (requirement 2); peeled from the camera, one layer can hold two meshes one of
// which hides the other from the light, so it shades itself (requirement 1).
#include <algorithm>
#include <vector>

#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>
#include <shadowlab/kit/translucent_maps.h>

namespace {

using namespace shadowlab;

class CompositedTranslucent final : public kit::TechniqueBase {
    bool setup(std::string& error) override {
        if (!allCasters_.setup(host(), "composited: all casters", error)) return false;
        if (!perMesh_.setup(host(), "composited: per mesh", error, &allCasters_)) return false;
        const auto* draws = static_cast<const TranslucentDraws*>(host().extension(SHADOWLAB_EXT_TRANSLUCENT_DRAWS));
        if (!draws || !draws->install) {
            error = "the host lacks " SHADOWLAB_EXT_TRANSLUCENT_DRAWS ", which composited shadows need";
            return false;
        }
        TranslucentDrawHook hook;
        hook.user = this;
        hook.beforeObject = [](void* user, const FrameContext& frame, const ParamValues& params, uint32_t object) {
            static_cast<CompositedTranslucent*>(user)->beforeTranslucentObject(frame, params, object);
        };
        draws->install(draws->context, &hook);
        return true;
    }

    void renderShadows(const FrameContext& frame, const ParamValues& params) override {
        // The opaque receivers' maps are translucent shadows' own; the per-mesh ones share their
        // D_o and light space.
        const kit::FocusedLightSpace focused = allCasters_.renderAllCasters(frame, params);
        settings_ = kit::TranslucentMaps::settings(params);
        perMesh_.ensure(settings_.resolution);
        perMesh_.setLightSpace(focused.light, settings_.resolution);
        sortCastersFromLight(frame.light);
        current_ = kTranslucentDrawsDone;
    }

    void bindMainPass(const FrameContext&, const ParamValues& params) override {
        (current_ == kTranslucentDrawsDone ? allCasters_ : perMesh_).bind(params);
    }

    // Before translucent mesh `object`: D_t and C of the casters nearer the light than it.
    void beforeTranslucentObject(const FrameContext&, const ParamValues&, uint32_t object) {
        current_ = object;
        if (object == kTranslucentDrawsDone || object >= host().objectCount()) {
            current_ = kTranslucentDrawsDone;
            return;
        }
        const float key = lightKey(host().objects()[object]);
        nearer_.clear();
        for (const auto& [casterKey, caster] : castersFromLight_) {
            if (casterKey >= key) break;
            if (caster != object) nearer_.push_back(caster);
        }
        perMesh_.renderTranslucent(settings_, [&](GLuint program) {
            for (const uint32_t caster : nearer_) host().drawObject(caster, program);
        });
    }

    // Distance from the light by the bounds' centre, as kit::frontToBackFromLight sorts.
    float lightKey(const ObjectInfo& info) const {
        return light_.type == LightType::Directional ? glm::dot(info.center, light_.direction)
                                                     : glm::length(info.center - light_.position);
    }

    void sortCastersFromLight(const LightInfo& light) {
        light_ = light;
        castersFromLight_.clear();
        const ObjectInfo* objects = host().objects();
        for (uint32_t i = 0; objects && i < host().objectCount(); ++i)
            if (objects[i].translucent() && objects[i].castsShadow()) castersFromLight_.push_back({lightKey(objects[i]), i});
        std::stable_sort(castersFromLight_.begin(), castersFromLight_.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
    }

    kit::TranslucentMaps allCasters_;     // every translucent caster: the opaque receivers' maps
    kit::TranslucentMaps perMesh_;   // rebuilt before each translucent mesh; shares allCasters_'s D_o
    kit::TranslucentMapSettings settings_;
    LightInfo light_;
    std::vector<std::pair<float, uint32_t>> castersFromLight_;   // translucent casters, front to back
    std::vector<uint32_t> nearer_;
    uint32_t current_ = kTranslucentDrawsDone;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kTranslucentMap,
    {.id = "composited-translucent",
     .displayName = "Composited translucent shadows",
     .category = "coloured",
     .explanation = "Translucent shadows for the opaque surfaces, then every translucent mesh shaded on its own: "
                    "before it is drawn (back to front from the camera), the nearest translucent depth and the "
                    "shadow colour are rebuilt from only the translucent meshes nearer the light than it, so a "
                    "glass pane is tinted by the panes in front of it and never by itself or those behind (seed "
                    "001's composited translucent shadows, sec. 4.2.3). Right where translucent shadows tint "
                    "every layer alike, noise-free unlike CSSM2, but two passes per mesh, each over the meshes "
                    "in front: the cost grows with the square of the mesh count (real time only for a handful).",
     .shadowGlsl = "composited-translucent.glsl"},
    kit::kTranslucentMapParams);

} // namespace

SHADOWLAB_PLUGIN(CompositedTranslucent, kDescriptor)
