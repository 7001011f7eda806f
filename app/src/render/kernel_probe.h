// The filter kernel's footprint around one pixel (the `kernel` view, `--probe X,Y`): what the
// technique's shadowTerm() reads there, re-evaluated on the CPU from the parameters it reported
// (SHADOWLAB_EXT_FILTER_FOOTPRINT) and the raw depths of its map. No GL here: the caller gives a
// depth fetch; tests/test_kernel_probe.cpp checks it against hand-made maps.
//
//   Box   pcf: n x n taps `spacing` texels apart (shaders/box_pcf.glsl), optionally bilinear, with
//         the cone bias (seed 000 sec. 3.2.4).
//   Disc  adaptive-pcf: the pixel's jittered disc set (pixel mod m; seed 000 eq. 3.11-3.12), the
//         outer ring first and the early out when it agrees (per pixel, or per 2x2 quad:
//         shaders/disc_sampling.glsl's adaptiveDiscPcf).
//   Pcss  pcss: the search region (eq. 3.17-3.18, bounded by the nearest depth under it as the
//         depth-range mips do), the blocker search over n_s x n_s disc samples, the penumbra
//         estimate (eq. 3.19-3.20) and the adaptive disc filter with that radius (plugins/pcss/pcss.glsl).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <shadowlab/technique.h>

namespace shadowlab {

struct KernelTap {
    enum class Stage { Box, Ring, Inner, Search } stage = Stage::Box;
    glm::vec2 uv{0.0f};    // map uv of the tap
    float lit = 0.0f;      // its comparison (Search: 1 = not a blocker)
    bool taken = true;     // false: after the early out, not read
};

struct KernelProbe {
    bool valid = false;
    std::string problem;                // why not valid: "no geometry", "outside the map", ...
    FilterKernel kernel = FilterKernel::None;
    glm::vec3 world{0.0f}, normal{0.0f};
    glm::vec3 coord{0.0f};              // map uv and stored depth of the point
    float resolution = 0.0f;            // map texels across
    int n = 0;                          // Box: n x n taps; Disc / Pcss: the filter's n x n samples
    glm::vec2 boxMin{0.0f}, boxMax{0.0f};   // Box: the texels read, map uv
    float kernelTexels = 0.0f;          // Box: width of the texels read; Disc / Pcss: the filter disc's diameter
    float filterRadiusTexels = 0.0f;    // Disc / Pcss: the filter disc's radius
    std::vector<KernelTap> taps;        // every sample, taken or not
    int samplesTaken = 0;               // lookups the shader makes (search and filter)
    bool earlyOut = false;              // Disc / Pcss filter: stopped after the outer ring
    float lit = 1.0f;                   // the filtered result
    // Pcss
    float searchRadiusTexels = 0.0f;
    float searchNear = 0.0f;            // linear depth the search cone is taken at (near plane or nearest stored)
    int searchSamples = 0;
    int blockers = 0;
    float receiverDepth = 0.0f;         // linear
    float averageBlockerDepth = 0.0f;   // linear; 0 without blockers
    float penumbraWorld = 0.0f;         // estimated penumbra width at the receiver, world units
    std::string decision;               // Pcss: "searched", "no blocker", "nothing nearer the light", "fully blocked"
};

// Stored depth of map texel (x, y), clamped to the edge by the callee.
using DepthFetch = std::function<float(int x, int y)>;
// The G-buffer of the 2x2 quad around the pixel (for a coherent early out): position (w = 1 where
// drawn) and normal of pixel (quad.x + i, quad.y + j) at [j * 2 + i], GL pixel coordinates.
struct ProbeQuad {
    glm::ivec2 origin{0};
    glm::vec4 position[4];
    glm::vec3 normal[4];
};

// `pixel` in GL coordinates (origin bottom left), inside `quad`.
KernelProbe probeKernel(const FilterFootprint& footprint, const ShadowMapInfo& map, const ProbeQuad& quad,
                        glm::ivec2 pixel, const DepthFetch& depth);

// One line of numbers for logs and the panel.
std::string describeProbe(const KernelProbe& probe);

// A point of the map (uv) on the receiver's tangent plane at the probed point: where the light ray
// through that map position meets it (for drawing the footprint in the camera view).
glm::vec3 onReceiverPlane(const ShadowMapInfo& map, const KernelProbe& probe, glm::vec2 uv);
// How far the kernel's footprint reaches from the probed point on screen, in pixels of a view
// `camera` draws at `viewport` (the box's corners, the discs' rims): the kernel view's inset
// magnifies that much around the probe.
float kernelPixelRadius(const ShadowMapInfo& map, const KernelProbe& probe, const glm::mat4& viewProjection, glm::ivec2 viewport);

} // namespace shadowlab
