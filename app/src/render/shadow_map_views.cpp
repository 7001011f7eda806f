// Debug views of the reported shadow maps (see shadow_map_views.h).
#include "render/shadow_map_views.h"

#include <algorithm>

#include "util/paths.h"

namespace shadowlab {

namespace {

// shaders/shadow_map_view.glsl's block, std140.
struct ReportedMapBlock {
    glm::mat4 worldToClip;
    glm::vec4 sizeAndRange;
};
struct ReportedMapsBlock {
    ReportedMapBlock maps[ShadowMapViews::kMaxMaps];
    glm::mat4 cameraView;
    glm::mat4 cameraViewProjection;
    glm::mat4 cameraInverseViewProjection;
    glm::ivec4 mapCountViewport;
};

} // namespace

bool ShadowMapViews::init(ShaderLibrary& shaders, std::string& error) {
    shaders_ = &shaders;
    ShaderRequest view;
    view.vertexFile = "fullscreen.vert";
    view.fragmentFile = "shadow_map_view.frag";
    view.searchPaths = hostShaderPaths();
    view.label = "host shadow-map views";
    viewProgram_ = shaders.build(view, error);
    if (!viewProgram_) return false;
    ShaderRequest frustum;
    frustum.vertexFile = "shadow_map_frustum.vert";
    frustum.fragmentFile = "shadow_map_frustum.frag";
    frustum.searchPaths = hostShaderPaths();
    frustum.label = "host shadow-map frusta";
    frustumProgram_ = shaders.build(frustum, error);
    if (!frustumProgram_) return false;
    GLuint name = 0;
    glCreateBuffers(1, &name);
    uniforms_.reset(name);
    glNamedBufferStorage(name, sizeof(ReportedMapsBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &name);
    emptyVao_.reset(name);
    return true;
}

void ShadowMapViews::release() {
    if (shaders_) {
        if (viewProgram_) shaders_->release(viewProgram_);
        if (frustumProgram_) shaders_->release(frustumProgram_);
    }
    viewProgram_ = frustumProgram_ = 0;
    uniforms_.reset();
    emptyVao_.reset();
}

void ShadowMapViews::draw(Renderer& renderer, ShadowMapView view, const std::vector<ShadowMapInfo>& maps,
                          GLuint framebuffer, glm::ivec2 size) {
    const CameraInfo& camera = renderer.camera();
    ReportedMapsBlock block{};
    const size_t count = std::min(maps.size(), kMaxMaps);
    for (size_t i = 0; i < count; ++i)
        block.maps[i] = {maps[i].worldToClip, {float(maps[i].size.x), float(maps[i].size.y), maps[i].viewDistanceBegin,
                                               maps[i].viewDistanceEnd}};
    block.cameraView = camera.view;
    block.cameraViewProjection = camera.viewProjection;
    block.cameraInverseViewProjection = camera.inverseViewProjection;
    block.mapCountViewport = {int(count), renderer.size().x, renderer.size().y, 0};
    glNamedBufferSubData(uniforms_.get(), 0, sizeof(block), &block);

    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, size.x, size.y);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, uniforms_.get());
    glUseProgram(shaders_->program(viewProgram_));
    glUniform1i(0, int(view));
    const GLuint nearest = renderer.sampler(SamplerKind::Nearest);
    const GLuint textures[] = {renderer.target(MainTarget::Position), renderer.target(MainTarget::Normal),
                               renderer.target(MainTarget::Color)};
    for (GLuint unit = 0; unit < 3; ++unit) {
        glBindTextureUnit(unit, textures[unit]);
        glBindSampler(unit, nearest);
    }
    renderer.drawFullscreenTriangle();
    if (view == ShadowMapView::Coverage && count > 0) {
        // The light frusta over it, not depth tested: a volume behind a wall still shows.
        glUseProgram(shaders_->program(frustumProgram_));
        glBindVertexArray(emptyVao_.get());
        glLineWidth(1.0f);
        glDrawArraysInstanced(GL_LINES, 0, 24, GLsizei(count));
    }
    for (GLuint unit = 0; unit < 3; ++unit) glBindSampler(unit, 0);
}

} // namespace shadowlab
