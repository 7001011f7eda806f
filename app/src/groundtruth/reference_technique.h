// The ray-traced reference shown like any technique ("reference" in `shadowlab list`): it reads
// back the host's camera pre-pass (world positions and normals of the current view), traces it on
// the CPU (groundtruth.h) and uploads the visibility, which its shadowTerm() reads per pixel. Slow by nature (a read-back and
// a CPU trace), so it traces again only when the view, light, scene or its parameters change.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "groundtruth/groundtruth.h"
#include "plugin/params.h"
#include "shadowlab/technique.h"

namespace shadowlab {

// Traces `gbuffer` for the current scene and light; false with an error when no ground truth.
using ReferenceTracer =
    std::function<bool(const GBufferView& gbuffer, const ReferenceOptions& options, std::vector<glm::vec3>& visibility,
                       std::string& error)>;

const TechniqueDesc& referenceDescriptor();
// Reads the descriptor's parameters (mode, samples, model) into ReferenceOptions.
ReferenceOptions referenceOptions(const ParamValues& params);

class ReferenceTechnique final : public IShadowTechnique {
public:
    // `sceneGeneration` changes whenever the scene is replaced, so a new scene is traced again.
    ReferenceTechnique(ReferenceTracer tracer, const uint64_t* sceneGeneration)
        : tracer_(std::move(tracer)), sceneGeneration_(sceneGeneration) {}
    bool init(IHost& host, std::string& error) override;
    void renderShadows(const FrameContext& frame, const ParamValues& params) override;
    void bindMainPass(const FrameContext& frame, const ParamValues& params) override;
    void shutdown() override;
    const std::string& lastError() const { return error_; }

private:
    IHost* host_ = nullptr;
    ReferenceTracer tracer_;
    const uint64_t* sceneGeneration_;
    uint32_t visibility_ = 0;
    glm::ivec2 size_{0};
    std::vector<float> cacheKey_;
    std::vector<glm::vec4> positionData_, normalData_;
    std::vector<glm::vec3> visibilityData_;
    std::string error_;
};

} // namespace shadowlab
