// Render-target limits of the device (see render_limits.h).
#include "render/render_limits.h"

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
    error = renderTargetBudgetProblem(size, msaaSamples, geometryBytes);
    return error.empty();
}

} // namespace shadowlab
