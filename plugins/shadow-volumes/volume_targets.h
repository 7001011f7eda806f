// shadow-volumes: the screen-sized targets the volumes are counted into, and the counters of that
// stencil pass. Both are per view: reallocated when the camera pre-pass's size changes, never
// per frame.
#pragma once

#include <array>
#include <cstdint>

#include <shadowlab/kit/handles.h>
#include <shadowlab/technique.h>

namespace shadow_volumes {

// The framebuffer the volumes are counted in (the host pre-pass's depth and stencil, attached
// each frame: attachPrepass), the mask image of the debug view, and the two other debug images
// (registered with the host as "volume mask", "volume overdraw" and "silhouette edges").
struct VolumeTargets {
    // Every target at `size`; false when a framebuffer is incomplete (the host has said why).
    bool allocate(shadowlab::IHost& host, glm::ivec2 size);
    // The pre-pass's depth-stencil on `framebuffer` (checked once for each texture it is given).
    bool attachPrepass(shadowlab::IHost& host, const shadowlab::CameraPrepass& prepass);

    shadowlab::kit::Texture mask, overdraw, edgeImage;
    shadowlab::kit::Framebuffer framebuffer, debugFramebuffer;   // pre-pass depth-stencil + mask; a debug image
    glm::ivec2 size{0};
    uint32_t attached = 0;   // the pre-pass texture last checked on `framebuffer`
};

// Volume samples passing the depth test and volume triangles, from queries in a ring, read two or
// more frames later when the GPU has them (never a stall).
class VolumeCounters {
public:
    void create();
    void destroy();
    void begin(uint64_t frame);
    void end(uint64_t frame);
    // Reports the oldest frame's counts as statistics when they are available.
    void read(shadowlab::IHost& host, uint64_t frame, glm::ivec2 size);
    void forget() { pending_.fill(false); }   // after a reallocation

private:
    std::array<GLuint, 3> samples_{}, primitives_{};
    std::array<bool, 3> pending_{};
};

} // namespace shadow_volumes
