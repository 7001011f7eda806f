// Render-target limits of the device (see gl_limits.h).
#include "util/gl_limits.h"

#include <algorithm>
#include <cstdio>

#include "gl/gl.h"
#include "scene/scene.h"

namespace shadowlab {
namespace {

int integer(GLenum name) {
    GLint value = 0;
    glGetIntegerv(name, &value);
    return value;
}

std::string gibibytes(uint64_t bytes) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f GiB", double(bytes) / double(uint64_t(1) << 30));
    return text;
}

} // namespace

RenderLimits queryRenderLimits() {
    RenderLimits limits;
    limits.maxSamples = std::min({integer(GL_MAX_SAMPLES), integer(GL_MAX_COLOR_TEXTURE_SAMPLES),
                                  integer(GL_MAX_DEPTH_TEXTURE_SAMPLES)});
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    limits.maxSize = std::min({integer(GL_MAX_TEXTURE_SIZE), integer(GL_MAX_FRAMEBUFFER_WIDTH),
                               integer(GL_MAX_FRAMEBUFFER_HEIGHT), int(viewport[0]), int(viewport[1])});
    return limits;
}

std::string describeRenderLimits() {
    const RenderLimits limits = queryRenderLimits();
    return "this device renders up to " + std::to_string(limits.maxSize) + "x" + std::to_string(limits.maxSize) +
           " with MSAA up to " + std::to_string(limits.maxSamples) + " samples";
}

uint64_t mainTargetBytes(glm::ivec2 size, int msaaSamples) {
    // RGBA16F colour, visibility and normal, RGBA32F position, depth24-stencil8: 44 bytes a sample;
    // the RGBA8 display texture: 4.
    const uint64_t pixels = uint64_t(std::max(size.x, 1)) * uint64_t(std::max(size.y, 1));
    return pixels * (44 + 4 + 44 * uint64_t(std::max(msaaSamples, 0)));
}

bool checkRenderTargets(glm::ivec2 size, int msaaSamples, uint64_t geometryBytes, std::string& error) {
    const RenderLimits limits = queryRenderLimits();
    if (msaaSamples > limits.maxSamples) {
        error = "--msaa " + std::to_string(msaaSamples) + ": this device supports MSAA up to " +
                std::to_string(limits.maxSamples) + " samples (" + glRendererString() + ")";
        return false;
    }
    if (size.x > limits.maxSize || size.y > limits.maxSize) {
        error = "--size " + std::to_string(size.x) + "x" + std::to_string(size.y) + ": this device renders up to " +
                std::to_string(limits.maxSize) + "x" + std::to_string(limits.maxSize) + " (" + glRendererString() + ")";
        return false;
    }
    const uint64_t targets = mainTargetBytes(size, msaaSamples);
    const uint64_t budget = sceneBudget().gpuBytes;
    if (targets + geometryBytes > budget) {
        error = "--size " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                (msaaSamples > 0 ? " with --msaa " + std::to_string(msaaSamples) : std::string()) + ": the render targets (" +
                gibibytes(targets) + ") and the scene's geometry (" + gibibytes(geometryBytes) +
                ") would need more than the GPU memory budget of " + gibibytes(budget) +
                "; raise it with --budget gpu-mib=N (docs/scene-format.md, \"Limits\")";
        return false;
    }
    return true;
}

} // namespace shadowlab
