// The reference as a technique (see reference_technique.h). It traces the host's camera pre-pass.
#include "groundtruth/reference_technique.h"

#include <algorithm>
#include <cstring>

#include <shadowlab/kit/params.h>

#include "gl/gl.h"
#include "util/log.h"

namespace shadowlab {
namespace {

constexpr ParamDesc kMode = kit::enumParam("mode", "mode", 0, "hard|soft",
     "hard: one shadow ray to the light's centre per pixel. soft: stratified rays over the light's area "
     "(its size in the scene), the visible fraction of the emitter.");
constexpr ParamDesc kSamples{"samples", "samples per pixel", ParamType::Int, 1, 4096, 1024, "",
     "Soft mode: rays per pixel over the light's area, traced adaptively (a first batch everywhere, all "
     "of them only where a penumbra may be; docs/benchmarks.md). Fewer is faster and noisier.", nullptr};
constexpr ParamDesc kModel = kit::enumParam("model", "translucency model", 2, "opaque|coverage|physical|modified|ignore",
     "What a translucent caster of alpha a and transmission t lets through, multiplied over every one a "
     "shadow ray crosses before the first opaque caster: opaque 0 (every caster blocks), coverage 1 - a "
     "(stochastic shadow maps), physical (1 - a) + a t (coloured), modified (1 - a) t (seed 001's "
     "modified translucent shadows), ignore 1 (translucent casters cast nothing).");

// One list, as the plugins declare theirs (kit/params.h).
#define REFERENCE_PARAMS(X)   \
    X(int, mode, kMode)       \
    X(int, samples, kSamples) \
    X(int, model, kModel)
SHADOWLAB_PARAMS(Params, REFERENCE_PARAMS);

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
    Params::table,
    Params::Id::count,
    kTechniqueNeedsCameraPrepass,
    TranslucencyModel::Physical,
};

} // namespace

const TechniqueDesc& referenceDescriptor() { return kDescriptor; }

ReferenceOptions referenceOptions(const ParamValues& params) {
    ReferenceOptions options;
    const Params p = Params::read(params);
    options.mode = p.mode == 1 ? ReferenceOptions::Mode::Soft : ReferenceOptions::Mode::Hard;
    options.samplesPerPixel = std::max(p.samples, 1);
    options.adaptive = true;
    options.model = static_cast<TranslucencyModel>(std::clamp(p.model, 0, int(kTranslucencyModelCount) - 1));
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
                           float(params[Params::Id::mode]), float(params[Params::Id::samples]), float(params[Params::Id::model]),
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
