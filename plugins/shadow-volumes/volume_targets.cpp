// shadow-volumes: screen targets and stencil-pass counters (volume_targets.h).
#include "volume_targets.h"

namespace shadow_volumes {

using namespace shadowlab;

bool VolumeTargets::allocate(IHost& host, glm::ivec2 newSize) {
    size = newSize;
    attached = 0;
    mask = kit::Texture(host, host.createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                  .label = "volume mask"}));
    overdraw = kit::Texture(host, host.createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                      .label = "volume overdraw"}));
    edgeImage = kit::Texture(host, host.createTexture({.internalFormat = GL_R8, .width = size.x, .height = size.y,
                                                       .label = "silhouette edges"}));
    framebuffer = kit::Framebuffer(host, host.createFramebuffer("shadow volumes"));
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, mask, 0);
    debugFramebuffer = kit::Framebuffer(host, host.createFramebuffer("shadow volume debug images"));
    glNamedFramebufferTexture(debugFramebuffer, GL_COLOR_ATTACHMENT0, overdraw, 0);
    host.registerDebugImage("volume mask", mask, DebugImageKind::Mask);
    host.registerDebugImage("volume overdraw", overdraw, DebugImageKind::Mask);
    host.registerDebugImage("silhouette edges", edgeImage, DebugImageKind::Mask);
    return host.checkFramebuffer(framebuffer, "shadow volumes") &&
           host.checkFramebuffer(debugFramebuffer, "shadow volume debug images");
}

bool VolumeTargets::attachPrepass(IHost& host, const CameraPrepass& prepass) {
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, prepass.depth, 0);
    if (prepass.depth == attached) return true;
    attached = prepass.depth;
    return host.checkFramebuffer(framebuffer, "shadow volumes");
}

void VolumeCounters::create() {
    glCreateQueries(GL_SAMPLES_PASSED, GLsizei(samples_.size()), samples_.data());
    glCreateQueries(GL_PRIMITIVES_GENERATED, GLsizei(primitives_.size()), primitives_.data());
}

void VolumeCounters::destroy() {
    glDeleteQueries(GLsizei(samples_.size()), samples_.data());
    glDeleteQueries(GLsizei(primitives_.size()), primitives_.data());
}

void VolumeCounters::begin(uint64_t frame) {
    const size_t slot = frame % samples_.size();
    glBeginQuery(GL_SAMPLES_PASSED, samples_[slot]);
    glBeginQuery(GL_PRIMITIVES_GENERATED, primitives_[slot]);
}

void VolumeCounters::end(uint64_t frame) {
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_SAMPLES_PASSED);
    pending_[frame % samples_.size()] = true;
}

void VolumeCounters::read(IHost& host, uint64_t frame, glm::ivec2 size) {
    const size_t slot = (frame + 1) % samples_.size();
    if (!pending_[slot]) return;
    GLuint available = 0;
    glGetQueryObjectuiv(samples_[slot], GL_QUERY_RESULT_AVAILABLE, &available);
    if (!available) return;
    GLuint64 samples = 0, primitives = 0;
    glGetQueryObjectui64v(samples_[slot], GL_QUERY_RESULT, &samples);
    glGetQueryObjectui64v(primitives_[slot], GL_QUERY_RESULT, &primitives);
    pending_[slot] = false;
    host.reportStatistic("volume samples passing depth per pixel", double(samples) / double(size.x * size.y));
    host.reportStatistic("volume triangles", double(primitives));
}

} // namespace shadow_volumes
