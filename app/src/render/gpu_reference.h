// The ray-traced reference on the GPU (issue 27, `--reference-device gpu`): the Embree module's
// shadow rays (groundtruth.h ReferenceOptions: hard, or N jittered stratified rays over the
// emitter; every translucency model) traced through the host's BVH (Renderer::rayTracing(),
// shaders/ray_trace.glsl) by shaders/reference_trace.comp, from the same read-back G-buffer.
// What differs from Embree: the soft samples' random numbers (a 32-bit hash, not SplitMix64: the
// same estimator, another draw), soft is always uniform (ReferenceOptions::adaptive ignored), and
// shadowRays counts N per traced pixel (rays below a surface's horizon included). The per-pixel
// sampling error is the reference's own collapsed-strata estimate. Embree stays the default
// ground truth; tests/test_raytraced.cpp checks this one against it on every built-in scene.
#pragma once

#include <string>
#include <vector>

#include "gl/gl.h"
#include "groundtruth/groundtruth.h"
#include "render/renderer.h"
#include "render/shader_library.h"

namespace shadowlab {

enum class ReferenceDevice { Cpu, Gpu };
// "cpu" or "gpu" (also the names written to results).
inline const char* referenceDeviceName(ReferenceDevice device) { return device == ReferenceDevice::Gpu ? "gpu" : "cpu"; }

class GpuReference {
public:
    explicit GpuReference(ShaderLibrary& shaders) : shaders_(shaders) {}
    ~GpuReference();
    GpuReference(const GpuReference&) = delete;
    GpuReference& operator=(const GpuReference&) = delete;

    // As IGroundTruth::trace, on the renderer's scene (its GL context current). Leaves the
    // technique texture units 4-5, image unit 7 and storage bindings 3-7 changed.
    bool trace(Renderer& renderer, const GBufferView& gbuffer, const LightInfo& light, const ReferenceOptions& options,
               std::vector<glm::vec3>& visibility, ReferenceStats* stats, std::string& error);

private:
    ShaderLibrary& shaders_;
    ProgramId program_ = 0;
    GlTexture positions_, normals_, result_;
    glm::ivec2 size_{0};
};

} // namespace shadowlab
