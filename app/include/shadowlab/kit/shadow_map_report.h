// Telling the host which shadow maps shadowTerm() reads this frame (SHADOWLAB_EXT_SHADOW_MAPS):
// what the host's texel-footprint measure and debug views (light frustum, texel grid, cascade
// colours) are drawn from. Call once a frame after the maps are rendered; a host without the
// extension ignores it.
#pragma once

#include <initializer_list>
#include <vector>

#include <shadowlab/technique.h>

namespace shadowlab::kit {

inline void reportShadowMaps(IHost& host, const ShadowMapInfo* maps, uint32_t count) {
    const auto* report = static_cast<const ShadowMapReport*>(host.extension(SHADOWLAB_EXT_SHADOW_MAPS));
    if (report && report->report) report->report(report->context, maps, count);
}

// One map over every view depth (a single shadow map, or a warped one whose matrix is given).
// `bodyEdges`: the focus body B's edges as point pairs (kit::bodyEdges), when the map was fitted to it.
inline void reportShadowMap(IHost& host, const glm::mat4& worldToClip, glm::ivec2 size, const char* label = nullptr,
                            const std::vector<glm::vec3>* bodyEdges = nullptr) {
    ShadowMapInfo map;
    map.worldToClip = worldToClip;
    map.size = size;
    map.label = label;
    if (bodyEdges && !bodyEdges->empty()) {
        map.focusBodyEdges = bodyEdges->data();
        map.focusBodyEdgeCount = uint32_t(bodyEdges->size() / 2);
    }
    reportShadowMaps(host, &map, 1);
}

// What shadowTerm() filters over (SHADOWLAB_EXT_FILTER_FOOTPRINT), once a frame after the maps are
// rendered; the host's kernel view and --probe draw and measure it. A host without it ignores it.
inline void reportFilterFootprint(IHost& host, const FilterFootprint& footprint) {
    const auto* report = static_cast<const FilterFootprintReport*>(host.extension(SHADOWLAB_EXT_FILTER_FOOTPRINT));
    if (report && report->report) report->report(report->context, &footprint);
}

} // namespace shadowlab::kit
