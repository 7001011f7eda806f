// The reference as a technique (see reference_technique.h).
#include "reference/reference_technique.h"

#include <cstring>

#include "gl/gl.h"
#include "util/log.h"

namespace shadowlab {
namespace {

enum Param : uint32_t { kMode, kSamples, kTransmission, kParamCount };

const ParamDesc kParams[] = {
    {"mode", "mode", ParamType::Enum, 0, 1, 0, "",
     "hard: one shadow ray to the light's centre per pixel. soft: stratified rays over the light's area "
     "(its size in the scene), the visible fraction of the emitter.", "hard|soft"},
    {"samples", "samples per pixel", ParamType::Int, 1, 1024, 64, "",
     "Soft mode: rays per pixel over the light's area. Fewer is faster and noisier.", nullptr},
    {"transmission", "coloured transmission", ParamType::Bool, 0, 1, 0, "",
     "Multiply the transmission of every translucent surface a shadow ray crosses (coloured shadows); "
     "off, every caster blocks.", nullptr},
};

const TechniqueDesc kDescriptor{
    "reference",
    "Ray-traced reference",
    "reference",
    "Embree ray tracing on the CPU from the exact pixels the rasteriser drew: the ground truth every "
    "technique is measured against. Hard mode traces one ray to the light's centre; soft mode "
    "integrates the light's area with stratified samples. Slow by design: it is traced again only "
    "when the view, the light or its parameters change.",
    "reference_visibility.glsl",
    kParams,
    kParamCount,
};

} // namespace

const TechniqueDesc& referenceDescriptor() { return kDescriptor; }

ReferenceOptions referenceOptions(const ParamValues& params) {
    ReferenceOptions options;
    options.mode = params.asInt(kMode) == 1 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
    options.samplesPerPixel = std::max(params.asInt(kSamples), 1);
    options.transmission = params.asBool(kTransmission);
    return options;
}

bool ReferenceTechnique::init(IHost& host, std::string& error) {
    host_ = &host;
    gbufferProgram_ = host.buildProgram({"reference_gbuffer.vert", "reference_gbuffer.frag", nullptr}, error);
    if (!gbufferProgram_) return false;
    framebuffer_ = host.createFramebuffer("reference G-buffer");
    return true;
}

void ReferenceTechnique::ensureTargets(glm::ivec2 size) {
    if (visibility_ && size == size_) return;
    for (uint32_t* texture : {&positions_, &normals_, &depth_, &visibility_})
        if (*texture) host_->destroyTexture(*texture);
    size_ = size;
    positions_ = host_->createTexture({GL_TEXTURE_2D, GL_RGBA32F, size.x, size.y, 1, 1, "reference positions"});
    normals_ = host_->createTexture({GL_TEXTURE_2D, GL_RGBA32F, size.x, size.y, 1, 1, "reference normals"});
    depth_ = host_->createTexture({GL_TEXTURE_2D, GL_DEPTH_COMPONENT32F, size.x, size.y, 1, 1, "reference depth"});
    visibility_ = host_->createTexture({GL_TEXTURE_2D, GL_RGBA16F, size.x, size.y, 1, 1, "reference visibility"});
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT0, positions_, 0);
    glNamedFramebufferTexture(framebuffer_, GL_COLOR_ATTACHMENT1, normals_, 0);
    glNamedFramebufferTexture(framebuffer_, GL_DEPTH_ATTACHMENT, depth_, 0);
    const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(framebuffer_, 2, buffers);
    host_->checkFramebuffer(framebuffer_, "reference G-buffer");
    host_->registerDebugImage("reference visibility", visibility_, DebugImageKind::Color);
    cacheKey_.clear();
}

void ReferenceTechnique::renderShadows(const ParamValues& params) {
    const CameraInfo& camera = host_->camera();
    ensureTargets(camera.viewport);
    // Everything the traced image depends on; unchanged means the last trace is still right.
    const LightInfo& light = host_->light();
    std::vector<float> key(&camera.viewProjection[0][0], &camera.viewProjection[0][0] + 16);
    key.insert(key.end(), {light.position.x, light.position.y, light.position.z, light.direction.x, light.direction.y,
                           light.direction.z, light.size, light.spotOuterAngle, float(light.type),
                           float(params[kMode]), float(params[kSamples]), float(params[kTransmission]),
                           float(*sceneGeneration_), float(size_.x), float(size_.y)});
    if (key == cacheKey_) return;

    {
        GpuPass pass(*host_, "reference G-buffer");
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        glViewport(0, 0, size_.x, size_.y);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        const float zero[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(framebuffer_, GL_COLOR, 1, zero);
        const float one = 1.0f;
        glClearNamedFramebufferfv(framebuffer_, GL_DEPTH, 0, &one);
        host_->drawScene(DrawSet::All, host_->glProgram(gbufferProgram_));
    }
    // A deliberate read-back: the reference is a CPU computation on exactly these pixels.
    const size_t pixels = size_t(size_.x) * size_t(size_.y);
    positionData_.resize(pixels);
    normalData_.resize(pixels);
    glGetTextureImage(positions_, 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * sizeof(glm::vec4)), positionData_.data());
    glGetTextureImage(normals_, 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * sizeof(glm::vec4)), normalData_.data());
    const GBufferView gbuffer{size_.x, size_.y, positionData_.data(), normalData_.data()};
    if (!tracer_(gbuffer, referenceOptions(params), visibilityData_, error_)) {
        host_->log(LogLevel::Error, error_.c_str());
        visibilityData_.assign(pixels, glm::vec3(1.0f));
    } else {
        error_.clear();
    }
    glTextureSubImage2D(visibility_, 0, 0, 0, size_.x, size_.y, GL_RGB, GL_FLOAT, visibilityData_.data());
    cacheKey_ = std::move(key);
}

void ReferenceTechnique::bindMainPass(uint32_t, const ParamValues&) { glBindTextureUnit(4, visibility_); }

void ReferenceTechnique::shutdown() {
    for (uint32_t* texture : {&positions_, &normals_, &depth_, &visibility_})
        if (*texture) host_->destroyTexture(*texture);
    if (framebuffer_) host_->destroyFramebuffer(framebuffer_);
    positions_ = normals_ = depth_ = visibility_ = framebuffer_ = 0;
}

} // namespace shadowlab
