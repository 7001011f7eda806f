// Ray-traced ground truth: the light visibility a shadow technique should have produced, for each
// pixel of the exact view the rasteriser drew. The host reads back its main pass's G-buffer
// (world positions and normals), hands it to trace(), and compares what the technique rendered
// with the result (metrics.h).
//
// The implementation (Embree 3 on the CPU, app/src/groundtruth/embree/embree_groundtruth.cpp) is a module,
// libshadowlab_groundtruth.so, opened on demand by loadGroundTruth(): the host starts, and times
// techniques, on machines without Embree. Nothing in this header names an Embree type.
//
// Bump SHADOWLAB_GROUNDTRUTH_ABI_VERSION whenever anything in this file (or in scene.h, which the
// module reads through setScene) changes layout or meaning.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

#define SHADOWLAB_GROUNDTRUTH_ABI_VERSION 1u
#define SHADOWLAB_GROUNDTRUTH_ENTRY_SYMBOL "shadowlab_create_groundtruth"
#define SHADOWLAB_GROUNDTRUTH_MODULE "libshadowlab_groundtruth.so"

namespace shadowlab {

// A G-buffer as the host reads it back (or as tracePrimary() makes it). Row-major, width * height
// texels, row 0 first; rows are treated uniformly, so GL's bottom-up order needs no flip.
struct GBufferView {
    int width = 0;
    int height = 0;
    const glm::vec4* positions = nullptr; // world space; w = 1 where geometry was drawn, 0 background
    const glm::vec4* normals = nullptr;   // world-space unit shading normals (xyz; w ignored)
};

struct ReferenceOptions {
    // Hard: one shadow ray per pixel, to the light's centre (size ignored).
    // Soft: samplesPerPixel stratified rays over the emitter (disc of radius light.size, or a
    //       cone of angular radius light.size for directional lights); visibility is the visible
    //       fraction of the emitter's area (solid angle for directional lights), unweighted by
    //       cosine or distance, i.e. what PCSS-like techniques estimate.
    enum class Mode { Hard, Soft } mode = Mode::Hard;
    int samplesPerPixel = 64;
    uint32_t seed = 1;         // with the pixel index, fixes every sample: same image for any thread count
    bool transmission = false; // coloured: product over the caster surfaces crossed of
                               // (1 - alpha) + alpha * transmission colour, 0 at the first opaque
                               // one; otherwise every caster, translucent or not, blocks
    int threads = 0;           // 0 = std::thread::hardware_concurrency()
};

class IGroundTruth {
public:
    virtual ~IGroundTruth() = default;

    // Builds the BVH of `scene` (all objects; those with castsShadow = false are seen by primary
    // rays only). Call once per scene and keep the instance across frames and techniques; a
    // second call replaces the BVH. The scene is copied: it may be destroyed afterwards.
    // Throws std::runtime_error on an invalid scene or an Embree failure.
    virtual void setScene(const Scene& scene) = 0;

    // Visibility of `light` for every texel of `gbuffer`, resized to width * height: grey
    // (v, v, v) in [0, 1], or the rgb transmittance with options.transmission. Texels outside
    // compareMask() (background, N.L <= 0, outside a spot cone) are 0.
    virtual void trace(const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
                       std::vector<glm::vec3>& visibility) = 0;

    // A CPU G-buffer of the view: one ray per pixel centre from cameraPos through the point that
    // inverse(viewProjection) maps the pixel to (row 0 = bottom, as GL). Positions as GBufferView
    // (w = 0 where the ray escapes); normals are the interpolated vertex normals, as the main
    // pass writes them. For tests, benchmarks and for checking the rasteriser's G-buffer.
    virtual void tracePrimary(const glm::mat4& viewProjection, glm::vec3 cameraPos, int width, int height,
                              std::vector<glm::vec4>& positions, std::vector<glm::vec4>& normals) = 0;

    // World-space distance shadow-ray origins are pushed off the surface (see the module).
    virtual float rayOffset() const = 0;
};

// Deletes the instance inside the module, then drops its reference to the module handle, so the
// library outlives every instance it created.
struct GroundTruthDeleter {
    std::shared_ptr<void> module;
    void operator()(IGroundTruth* groundTruth) const noexcept { delete groundTruth; }
};
using GroundTruthPtr = std::unique_ptr<IGroundTruth, GroundTruthDeleter>;

// Opens libshadowlab_groundtruth.so: beside the executable, then beside the plugin directory
// (pluginDir()/..), then by plain name (LD_LIBRARY_PATH). Null with `error` set when it is
// missing, fails to load or was built for another ABI version.
GroundTruthPtr loadGroundTruth(std::string& error);

// ---------------------------------------------------------------------------------------------
// Which pixels have a defined answer, shared by the module (which traces only these) and the
// metrics (which compare only these).

// Unit vector from `p` towards the light's centre.
inline glm::vec3 directionToLight(const LightInfo& light, glm::vec3 p) {
    if (light.type == LightType::Directional) return -light.direction;
    const glm::vec3 toLight = light.position - p;
    const float length = glm::length(toLight);
    return length > 0.0f ? toLight / length : -light.direction;
}

// Drawn geometry whose (unflipped) normal faces the light, inside the cone of a spot light.
inline bool facesLight(const glm::vec4& position, const glm::vec4& normal, const LightInfo& light) {
    if (position.w == 0.0f) return false;
    const glm::vec3 p(position);
    const glm::vec3 l = directionToLight(light, p);
    if (glm::dot(glm::vec3(normal), l) <= 0.0f) return false;
    if (light.type == LightType::Spot && glm::dot(-l, light.direction) <= std::cos(light.spotOuterAngle))
        return false;
    return true;
}

} // namespace shadowlab

// The module's only export. Returns null for a mismatched abiVersion.
//   extern "C" shadowlab::IGroundTruth* shadowlab_create_groundtruth(uint32_t abiVersion);
