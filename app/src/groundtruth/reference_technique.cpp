// The reference as a technique (see reference_technique.h). It traces the host's camera pre-pass.
#include "groundtruth/reference_technique.h"

#include <algorithm>
#include <cstring>

#include "gl/gl.h"
#include "util/log.h"

namespace shadowlab {
namespace {

enum Param : uint32_t { kMode, kSamples, kModel, kParamCount };

const ParamDesc kParams[] = {
    {"mode", "mode", ParamType::Enum, 0, 1, 0, "",
     "hard: one shadow ray to the light's centre per pixel. soft: stratified rays over the light's area "
     "(its size in the scene), the visible fraction of the emitter.", "hard|soft"},
    {"samples", "samples per pixel", ParamType::Int, 1, 4096, 1024, "",
     "Soft mode: rays per pixel over the light's area, traced adaptively (a first batch everywhere, all "
     "of them only where a penumbra may be; docs/benchmarks.md). Fewer is faster and noisier.", nullptr},
    {"model", "translucency model", ParamType::Enum, 0, 4, 2, "",
     "What a translucent caster of alpha a and transmission t lets through, multiplied over every one a "
     "shadow ray crosses before the first opaque caster: opaque 0 (every caster blocks), coverage 1 - a "
     "(stochastic shadow maps), physical (1 - a) + a t (coloured), modified (1 - a) t (seed 001's "
     "modified translucent shadows), ignore 1 (translucent casters cast nothing).",
     "opaque|coverage|physical|modified|ignore"},
};

const TechniqueDesc kDescriptor{
    sizeof(TechniqueDesc),
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
    kTechniqueNeedsCameraPrepass,
    TranslucencyModel::Physical,
};

} // namespace

const TechniqueDesc& referenceDescriptor() { return kDescriptor; }

ReferenceOptions referenceOptions(const ParamValues& params) {
    ReferenceOptions options;
    options.mode = params.asInt(kMode) == 1 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
    options.samplesPerPixel = std::max(params.asInt(kSamples), 1);
    options.adaptive = true;
    options.model = static_cast<TranslucencyModel>(std::clamp(params.asInt(kModel), 0, int(kTranslucencyModelCount) - 1));
    return options;
}

bool ReferenceTechnique::init(IHost& host, std::string&) {
    host_ = &host;
    return true;
}

void ReferenceTechnique::renderShadows(const FrameContext& frame, const ParamValues& params) {
    // The host's camera pre-pass holds exactly the pixels the main pass shades.
    const auto* prepass = static_cast<const CameraPrepass*>(host_->extension(SHADOWLAB_EXT_CAMERA_PREPASS));
    if (!prepass) return;
    if (!visibility_ || prepass->size != size_) {
        if (visibility_) host_->destroyTexture(visibility_);
        size_ = prepass->size;
        visibility_ = host_->createTexture({.internalFormat = GL_RGBA16F, .width = size_.x, .height = size_.y,
                                            .label = "reference visibility"});
        host_->registerDebugImage("reference visibility", visibility_, DebugImageKind::Color);
        cacheKey_.clear();
    }
    // Everything the traced image depends on; unchanged means the last trace is still right.
    const CameraInfo& camera = frame.camera;
    const LightInfo& light = frame.light;
    std::vector<float> key(&camera.viewProjection[0][0], &camera.viewProjection[0][0] + 16);
    key.insert(key.end(), {light.position.x, light.position.y, light.position.z, light.direction.x, light.direction.y,
                           light.direction.z, light.size, light.spotOuterAngle, float(light.type),
                           float(params[kMode]), float(params[kSamples]), float(params[kModel]),
                           float(*sceneGeneration_), float(size_.x), float(size_.y)});
    if (key == cacheKey_) return;

    // A deliberate read-back: the reference is a CPU computation on exactly these pixels.
    const size_t pixels = size_t(size_.x) * size_t(size_.y);
    positionData_.resize(pixels);
    normalData_.resize(pixels);
    glGetTextureImage(prepass->position, 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * sizeof(glm::vec4)), positionData_.data());
    glGetTextureImage(prepass->normal, 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * sizeof(glm::vec4)), normalData_.data());
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

void ReferenceTechnique::bindMainPass(const FrameContext&, const ParamValues&) { glBindTextureUnit(4, visibility_); }

void ReferenceTechnique::shutdown() {
    if (visibility_) host_->destroyTexture(visibility_);
    visibility_ = 0;
}

} // namespace shadowlab
