// What the device can render into, asked before the host allocates its main render targets, so
// that `--msaa 8` on a 4-sample device or a size the driver cannot allocate gets a message saying
// what the device supports instead of "framebuffer is incomplete". GL must be current.
#pragma once

#include <cstdint>
#include <string>

#include <glm/glm.hpp>

namespace shadowlab {

struct RenderLimits {
    int maxSamples = 0;          // min of GL_MAX_SAMPLES, _COLOR_TEXTURE_SAMPLES, _DEPTH_TEXTURE_SAMPLES
    int maxSize = 0;             // min of GL_MAX_TEXTURE_SIZE, GL_MAX_FRAMEBUFFER_WIDTH/HEIGHT, GL_MAX_VIEWPORT_DIMS
};
RenderLimits queryRenderLimits();
// "this device renders up to 16384x16384 with MSAA up to 4 samples"
std::string describeRenderLimits();

// False, with a message naming the option and what the device supports, when `size` and
// `msaaSamples` exceed the device's limits, or when the targets plus `geometryBytes` exceed the
// GPU memory budget (renderTargetBudgetProblem in scene.h).
bool checkRenderTargets(glm::ivec2 size, int msaaSamples, uint64_t geometryBytes, std::string& error);

} // namespace shadowlab
