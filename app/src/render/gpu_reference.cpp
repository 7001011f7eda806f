// The GPU reference: see gpu_reference.h.
#include "render/gpu_reference.h"

#include <algorithm>
#include <cmath>

namespace shadowlab {

GpuReference::~GpuReference() {
    if (program_) shaders_.release(program_);
}

bool GpuReference::trace(Renderer& renderer, const GBufferView& gbuffer, const LightInfo& light,
                         const ReferenceOptions& options, std::vector<glm::vec3>& visibility, ReferenceStats* stats,
                         std::string& error) {
    if (!program_) {
        ShaderRequest request;
        request.computeFile = "reference_trace.comp";
        request.searchPaths = hostShaderPaths();
        request.label = "gpu reference";
        program_ = shaders_.build(request, error);
        if (!program_) return false;
    }
    const int width = gbuffer.width, height = gbuffer.height;
    const size_t pixels = size_t(std::max(width, 0)) * size_t(std::max(height, 0));
    visibility.assign(pixels, glm::vec3(0.0f));
    ReferenceStats local;
    ReferenceStats& out = stats ? *stats : local;
    out = ReferenceStats{};
    for (size_t i = 0; i < pixels; ++i) out.tracedPixels += facesLight(gbuffer.positions[i], gbuffer.normals[i], light);
    const bool soft = options.mode == ReferenceOptions::Mode::Soft && light.size > 0.0f && options.samplesPerPixel > 1;
    const int count = soft ? std::clamp(options.samplesPerPixel, 1, 4096) : 1;
    out.samplesPerPixel = count;
    out.refinedPixels = out.tracedPixels;
    out.shadowRays = uint64_t(out.tracedPixels) * uint64_t(count);
    if (pixels == 0) return true;

    if (glm::ivec2(width, height) != size_ || !positions_) {
        size_ = {width, height};
        auto make = [&](GlTexture& texture) {
            GLuint name = 0;
            glCreateTextures(GL_TEXTURE_2D, 1, &name);
            glTextureStorage2D(name, 1, GL_RGBA32F, width, height);
            texture.reset(name);
        };
        make(positions_);
        make(normals_);
        make(result_);
    }
    glTextureSubImage2D(positions_.get(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, gbuffer.positions);
    glTextureSubImage2D(normals_.get(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, gbuffer.normals);

    const RayTracingScene& scene = renderer.rayTracing();
    const GLuint buffers[] = {scene.nodes, scene.triangles, scene.uvs, scene.materials, scene.texels};
    for (GLuint i = 0; i < 5; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3 + i, buffers[i]);
    glBindTextureUnit(4, positions_.get());
    glBindTextureUnit(5, normals_.get());
    glBindSampler(4, 0);
    glBindSampler(5, 0);
    glBindImageTexture(7, result_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    const GLuint program = shaders_.program(program_);
    glUseProgram(program);
    glProgramUniform4f(program, 0, light.position.x, light.position.y, light.position.z, float(light.type));
    glProgramUniform4f(program, 1, light.direction.x, light.direction.y, light.direction.z, light.size);
    glProgramUniform4f(program, 2, scene.rayOffset, std::cos(light.spotOuterAngle), 0.0f, 0.0f);
    glProgramUniform4ui(program, 3, uint32_t(count), options.seed, uint32_t(options.model), 0u);
    glDispatchCompute(GLuint((width + 7) / 8), GLuint((height + 7) / 8), 1);
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> result(pixels);
    glGetTextureImage(result_.get(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels * sizeof(glm::vec4)), result.data());
    glUseProgram(0);
    if (soft) out.sampleError.assign(pixels, 0.0f);
    for (size_t i = 0; i < pixels; ++i) {
        visibility[i] = glm::clamp(glm::vec3(result[i]), 0.0f, 1.0f);
        if (soft) out.sampleError[i] = result[i].w;
    }
    return true;
}

} // namespace shadowlab
