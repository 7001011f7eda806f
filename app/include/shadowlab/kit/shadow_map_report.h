// Telling the host which shadow maps shadowTerm() reads this frame (SHADOWLAB_EXT_SHADOW_MAPS):
// what the host's texel-footprint measure and debug views (light frustum, texel grid, cascade
// colours) are drawn from. Call once a frame after the maps are rendered; a host without the
// extension ignores it.
#pragma once

#include <initializer_list>

#include <shadowlab/technique.h>

namespace shadowlab::kit {

inline void reportShadowMaps(IHost& host, const ShadowMapInfo* maps, uint32_t count) {
    const auto* report = static_cast<const ShadowMapReport*>(host.extension(SHADOWLAB_EXT_SHADOW_MAPS));
    if (report && report->report) report->report(report->context, maps, count);
}

// One map over every view depth (a single shadow map, or a warped one whose matrix is given).
inline void reportShadowMap(IHost& host, const glm::mat4& worldToClip, glm::ivec2 size, const char* label = nullptr) {
    ShadowMapInfo map;
    map.worldToClip = worldToClip;
    map.size = size;
    map.label = label;
    reportShadowMaps(host, &map, 1);
}

} // namespace shadowlab::kit
