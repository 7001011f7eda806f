// No shadows: the baseline. Every surface facing the light is lit, so this technique's frame time
// is the host's cost alone; every other technique's overhead is measured against it.
#include <shadowlab/technique.h>

namespace {
struct NoShadows final : shadowlab::IShadowTechnique {};
const shadowlab::TechniqueDesc kDescriptor{
    .id = "none", .displayName = "No shadows", .category = "baseline",
    .explanation = "Direct light without any occlusion test: every surface facing the light is lit. It is the baseline "
                   "for overhead measurements and shows how much shadows add to the reading of a scene (contact, "
                   "height above the ground, shape).",
    .shadowGlsl = "none.glsl", .debugViews = ""};   // no shadows to look at
} // namespace
SHADOWLAB_PLUGIN(NoShadows, kDescriptor)
