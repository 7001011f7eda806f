// The contact band (issue 30; docs/contact-shadows.md): where a shadow map fails at contact. A
// compared pixel is in the band when its hard shadow ray (to the light's centre) meets an opaque
// shadow caster within kContactBandDistance world units of the receiver: the shadow there is cast
// by something touching or nearly touching the surface, exactly where a map's bias lifts the
// shadow off its caster (peter panning) and a caster thinner than the bias or a texel leaks light.
// The band's false-light rate (reference shadowed, technique lit) measures those leaks alone,
// undiluted by the rest of the image. Computed on the CPU with the ray tracer's BVH (render/bvh.h)
// from the G-buffer the reference was traced for; no Embree, no GL.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "groundtruth/groundtruth.h"
#include "render/bvh.h"

namespace shadowlab {

// The test scenes are in metres with casters 0.06 to 1 m across: 50 cm covers the gap a bias
// opens under them (a few texels of a 2048 map over 24-40 m), and the shadows of `contact`'s
// casters hovering 0.25 above the ground (peter panning's look-alike), and little else.
constexpr float kContactBandDistance = 0.5f;

struct ContactBandMetrics {
    size_t bandPixels = 0;         // compared pixels in the band
    double falseLightRate = 0.0;   // of those: reference < 0.5 and technique > 0.5 (0 when none)
    size_t farPixels = 0;          // compared pixels whose ray meets nothing within 4 x the distance
};

// 1 for pixels of `mask` whose shadow ray from p + n * bvh.rayOffset towards `light` meets an
// opaque caster (transmittance below 0.5) within `distance` (and before a point or spot light);
// 2 for pixels of `mask` whose ray meets nothing within 4 * distance (far from any contact); 0
// otherwise. Throws std::invalid_argument when the mask is not width * height.
std::vector<uint8_t> contactBand(const bvh::Bvh& bvh, const GBufferView& gbuffer, const std::vector<uint8_t>& mask,
                                 const LightInfo& light, float distance = kContactBandDistance);

// The band's false-light rate and sizes from contactBand()'s classes.
ContactBandMetrics contactBandMetrics(const std::vector<uint8_t>& band, const std::vector<glm::vec3>& technique,
                                      const std::vector<glm::vec3>& reference);

} // namespace shadowlab
