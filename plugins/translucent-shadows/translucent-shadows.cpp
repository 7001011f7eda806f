// Translucent shadows (Filion and McNaughton 2008, "StarCraft II: Effects & Techniques"; seed 001
// sec. 2.1.3 for the algorithm, sec. 4.2.1 for the modified colour and the front-to-back sort,
// sec. 5.3.1 Fig. 5.3.B for its timing with 2x2 hardware PCF, sec. 5.3.3 for its failure). Three
// passes from the light (kit/translucent_maps.h, shared with composited-translucent):
//   1. D_o: the depth of the opaque casters (an ordinary shadow map);
//   2. D_t: the nearest translucent caster's depth (LEQUAL, depth writes);
//   3. C: a colour buffer cleared to white, multiplied (blend DST_COLOR, ZERO) by every translucent
//      caster in front of D_o (depth-tested against it without writing), drawn front to back from
//      the light by the objects' bounds centres (seed 001 sorts per mesh by its bounding box's
//      centre). The original writes the surface colour; `modified` (1 - a) t (sec. 4.2.1).
// Lookup: visibility = o (t + (1 - t) C) with o = [z <= D_o] and t = [z <= D_t].
// Reference model: `modified` is M3, (1 - a) t per crossing, exact on opaque receivers; `original`
// has no reference model of its own (its factor is the surface colour, not a transmission), so it
// is judged against M3 as well and the difference shows.
// Known artefacts: every point behind the nearest translucent surface gets all of C, so translucent
// surfaces shadow themselves and layers far from the light tint those nearer it (Figs. 2.1.3.A,
// 5.3.3.A); the bounds sort breaks for objects of different sizes or interleaved objects (harmless
// with this commutative blend); original: a surface's own colour does not darken a receiver of that
// colour (a green plane over a green pot, Fig. 4.2.1.A); modified: (1 - a) t does not tend to 1
// as a -> 0 (it is 1 - a only where t = 1), so it differs from the physical model even under one
// layer ("only superficially corrected", sec. 2.1.3 footnote 1).
#include <shadowlab/kit/params.h>
#include <shadowlab/kit/technique_base.h>
#include <shadowlab/kit/translucent_maps.h>

namespace {

using namespace shadowlab;

class TranslucentShadows final : public kit::TechniqueBase {
    bool setup(std::string& error) override { return maps_.setup(host(), "translucent shadows", error); }
    void renderShadows(const FrameContext& frame, const ParamValues& params) override { maps_.renderAllCasters(frame, params); }
    void bindMainPass(const FrameContext&, const ParamValues& params) override { maps_.bind(params); }

    kit::TranslucentMaps maps_;
};

constexpr TechniqueDesc kDescriptor = kit::describe(kit::kTranslucentMap,
    {.id = "translucent-shadows",
     .displayName = "Translucent shadows (StarCraft II)",
     .category = "coloured",
     .explanation = "Three maps from the light: the opaque casters' depth, the nearest translucent caster's "
                    "depth, and a colour buffer, white at first, that every translucent caster in front of the "
                    "opaque depth multiplies by what it lets through. A point behind an opaque caster is dark; "
                    "behind the nearest translucent one it gets the whole colour buffer. Noise-free, cheap, and "
                    "right on opaque receivers; but translucent surfaces behind the first are tinted by every "
                    "layer, themselves and those farther from the light included. The modified variant writes "
                    "(1 - alpha) t and is judged by that model; the original writes the surface colour, which "
                    "has no reference model of its own (it is judged by the modified one). Compare the two on "
                    "teapot-glass's green pot.",
     .shadowGlsl = "translucent-shadows.glsl"},
    kit::kTranslucentMapParams);

} // namespace

SHADOWLAB_PLUGIN(TranslucentShadows, kDescriptor)
