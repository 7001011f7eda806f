// The host's screen-space contact shadows (issue 30; docs/contact-shadows.md), declared once for
// the C++ (render/renderer.cpp, tests) and the GLSL (shaders/contact_shadows.frag, main.frag).
//
// A shadow map misses the shadow right at a caster's foot: the bias that keeps a lit surface from
// shadowing itself lifts the caster's depth off the receiver (peter panning), and a caster thinner
// than a texel or than the bias is not in the map at all. Contact shadows close that gap from the
// other side, with the camera's depth buffer, which has neither bias nor texels in light space:
// from each visible pixel a short ray is marched towards the light, and where a sample of the ray
// lies behind the depth buffer's surface by less than a thickness, something the camera sees is
// between the pixel and the light: the pixel is in shadow. The main pass takes the minimum of this
// term and the technique's (min, not product: the two see the same occluder, which must not darken
// twice). What the depth buffer cannot tell is shown in docs/contact-shadows.md: casters outside
// the view, or hidden behind other surfaces, cast nothing; every surface is assumed `thickness`
// deep behind what the camera sees.
#ifndef SHADOWLAB_CONTACT_SHADOWS_SHARED_H
#define SHADOWLAB_CONTACT_SHADOWS_SHARED_H
#include "shadowlab/kit/shared.h"

SHADOWLAB_SHARED_BEGIN(contact_shadows)
// The march reads the camera pre-pass's depth on unit 0; the main pass reads the contact term on
// unit 0 too (units 1-3 are the materials' and the eye-space blur's there).
SHADOWLAB_TEXTURE_UNIT(kContactDepthUnit, 0)
SHADOWLAB_TEXTURE_UNIT(kContactTermUnit, 0)
SHADOWLAB_SHARED_END

// Host uniform locations (0-15 are the host's; main.frag: 6 eye blur, 7 lighting).
#define SHADOWLAB_CONTACT_READ_LOCATION 8        // main pass: 1 take min(term, contact term), 0 not
#define SHADOWLAB_CONTACT_INVERSE_VP_LOCATION 8  // march: inverse(view projection)
#define SHADOWLAB_CONTACT_PARAMS_LOCATION 9      // march: length, thickness, steps, jitter
#define SHADOWLAB_CONTACT_MAX_STEPS 64

// Samples of the march that fall within kContactStartPixels pixels of the start are skipped:
// there the depth buffer holds the receiver itself, and its depth read at a neighbouring pixel
// centre differs from the ray's by the surface's slope, not by an occluder.
#define kContactStartPixels 1.5
// A sample is occluded only when it lies more than this many pixel footprints (the world size of
// one pixel at the sample's view depth) behind the surface: the same slope error one pixel away.
#define kContactBiasPixels 0.25

#endif
