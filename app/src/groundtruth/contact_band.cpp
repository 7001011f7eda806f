// The contact band (see contact_band.h).
#include "groundtruth/contact_band.h"

#include <algorithm>
#include <stdexcept>
#include <thread>

namespace shadowlab {
namespace {

float meanOf(glm::vec3 v) { return (v.r + v.g + v.b) / 3.0f; }

// Class of one pixel: 1 in the band, 2 far from contact, 0 between.
uint8_t contactClass(const bvh::Bvh& bvh, glm::vec3 p, glm::vec3 n, const LightInfo& light, float distance) {
    const glm::vec3 l = directionToLight(light, p);
    if (glm::dot(n, l) < 0.0f) n = -n;
    const glm::vec3 origin = p + n * bvh.rayOffset;
    const float toLight = light.type == LightType::Directional ? 1e30f : glm::length(light.position - origin);
    // Translucent crossings merge as the reference's do (one object's two faces count once).
    const float merge = 4.0f * bvh.rayOffset;
    if (meanOf(bvh::transmittance(bvh, origin, l, std::min(distance, toLight), merge)) < 0.5f) return 1;
    if (meanOf(bvh::transmittance(bvh, origin, l, std::min(4.0f * distance, toLight), merge)) >= 1.0f) return 2;
    return 0;
}

} // namespace

std::vector<uint8_t> contactBand(const bvh::Bvh& bvh, const GBufferView& gbuffer, const std::vector<uint8_t>& mask,
                                 const LightInfo& light, float distance) {
    const size_t pixels = size_t(gbuffer.width) * size_t(gbuffer.height);
    if (mask.size() != pixels) throw std::invalid_argument("contactBand: the mask is not width * height");
    std::vector<uint8_t> band(pixels, 0);
    // Rows split over the machine's threads: short rays, but a 1080p frame has two million.
    const unsigned threads = std::max(1u, std::min(16u, std::thread::hardware_concurrency()));
    auto rows = [&](unsigned part) {
        for (int y = int(part); y < gbuffer.height; y += int(threads))
            for (int x = 0; x < gbuffer.width; ++x) {
                const size_t i = size_t(y) * size_t(gbuffer.width) + size_t(x);
                if (!mask[i]) continue;
                band[i] = contactClass(bvh, glm::vec3(gbuffer.positions[i]), glm::vec3(gbuffer.normals[i]), light, distance);
            }
    };
    std::vector<std::thread> workers;
    for (unsigned part = 1; part < threads; ++part) workers.emplace_back(rows, part);
    rows(0);
    for (std::thread& worker : workers) worker.join();
    return band;
}

ContactBandMetrics contactBandMetrics(const std::vector<uint8_t>& band, const std::vector<glm::vec3>& technique,
                                      const std::vector<glm::vec3>& reference) {
    if (technique.size() != band.size() || reference.size() != band.size())
        throw std::invalid_argument("contactBandMetrics: the images are not the band's size");
    ContactBandMetrics m;
    size_t falseLight = 0;
    for (size_t i = 0; i < band.size(); ++i) {
        if (band[i] == 2) ++m.farPixels;
        if (band[i] != 1) continue;
        ++m.bandPixels;
        if (meanOf(reference[i]) < 0.5f && meanOf(technique[i]) > 0.5f) ++falseLight;
    }
    m.falseLightRate = m.bandPixels ? double(falseLight) / double(m.bandPixels) : 0.0;
    return m;
}

} // namespace shadowlab
