// Debug views of the reported shadow maps (see shadow_map_views.h).
#include "render/shadow_map_views.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

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
    viewProgram_ = shaders.build(hostShaderRequest("fullscreen.vert", "shadow_map_view.frag", "host shadow-map views"), error);
    if (!viewProgram_) return false;
    frustumProgram_ = shaders.build(
        hostShaderRequest("shadow_map_frustum.vert", "shadow_map_frustum.frag", "host shadow-map frusta"), error);
    if (!frustumProgram_) return false;
    overlayProgram_ = shaders.build(hostShaderRequest("shadow_map_overlay.vert", "shadow_map_frustum.frag",
                                                      "host debug-view overlays (focus body, kernel footprint)"),
                                    error);
    if (!overlayProgram_) return false;
    GLuint name = 0;
    glCreateBuffers(1, &name);
    uniforms_.reset(name);
    glNamedBufferStorage(name, sizeof(ReportedMapsBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &name);
    emptyVao_.reset(name);
    // The overlays' vertices: one buffer of fixed size, updated when drawn.
    glCreateBuffers(1, &name);
    overlayVertices_.reset(name);
    glNamedBufferStorage(name, GLsizeiptr(kMaxOverlayVertices * sizeof(OverlayVertex)), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glCreateVertexArrays(1, &name);
    overlayVao_.reset(name);
    glVertexArrayVertexBuffer(name, 0, overlayVertices_.get(), 0, sizeof(OverlayVertex));
    glEnableVertexArrayAttrib(name, 0);
    glEnableVertexArrayAttrib(name, 1);
    glVertexArrayAttribFormat(name, 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(OverlayVertex, position)));
    glVertexArrayAttribFormat(name, 1, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(OverlayVertex, colour)));
    glVertexArrayAttribBinding(name, 0, 0);
    glVertexArrayAttribBinding(name, 1, 0);
    return true;
}

void ShadowMapViews::release() {
    if (shaders_) {
        if (viewProgram_) shaders_->release(viewProgram_);
        if (frustumProgram_) shaders_->release(frustumProgram_);
        if (overlayProgram_) shaders_->release(overlayProgram_);
    }
    viewProgram_ = frustumProgram_ = overlayProgram_ = 0;
    uniforms_.reset();
    overlayVertices_.reset();
    emptyVao_.reset();
    overlayVao_.reset();
}

void ShadowMapViews::drawOverlay(const std::vector<OverlayVertex>& vertices, GLenum mode) {
    const size_t count = std::min(vertices.size(), kMaxOverlayVertices);
    if (count == 0) return;
    glNamedBufferSubData(overlayVertices_.get(), 0, GLsizeiptr(count * sizeof(OverlayVertex)), vertices.data());
    glUseProgram(shaders_->program(overlayProgram_));
    glBindVertexArray(overlayVao_.get());
    glDrawArrays(mode, 0, GLsizei(count));
}

void ShadowMapViews::kernelOverlay(const ShadowMapInfo& map, const KernelProbe& probe, std::vector<OverlayVertex>& lines,
                                   std::vector<OverlayVertex>& points) {
    using namespace overlay_colour;
    auto line = [&](glm::vec2 a, glm::vec2 b, glm::vec3 colour) {
        lines.push_back({onReceiverPlane(map, probe, a), colour});
        lines.push_back({onReceiverPlane(map, probe, b), colour});
    };
    auto circle = [&](glm::vec2 centre, float radiusTexels, glm::vec3 colour) {
        constexpr int kSegments = 64;
        const float r = radiusTexels / probe.resolution;
        for (int i = 0; i < kSegments; ++i) {
            const float a0 = 6.2831853f * float(i) / kSegments, a1 = 6.2831853f * float(i + 1) / kSegments;
            line(centre + r * glm::vec2(std::cos(a0), std::sin(a0)), centre + r * glm::vec2(std::cos(a1), std::sin(a1)), colour);
        }
    };
    const glm::vec2 centre(probe.coord);
    if (probe.kernel == FilterKernel::Box) {
        const glm::vec2 a = probe.boxMin, b = probe.boxMax;
        line(a, {b.x, a.y}, kBox);
        line({b.x, a.y}, b, kBox);
        line(b, {a.x, b.y}, kBox);
        line({a.x, b.y}, a, kBox);
    } else {
        if (probe.kernel == FilterKernel::Pcss) circle(centre, probe.searchRadiusTexels, kSearchDisc);
        if (probe.filterRadiusTexels > 0.0f) circle(centre, probe.filterRadiusTexels, kFilterDisc);
    }
    for (const KernelTap& tap : probe.taps) {
        const glm::vec3 colour = tap.stage == KernelTap::Stage::Search ? (tap.lit > 0.5f ? kNoBlocker : kBlocker)
                                 : !tap.taken                          ? kSkippedTap
                                 : tap.lit >= 0.5f                     ? kLitTap
                                                                       : kShadowedTap;
        points.push_back({onReceiverPlane(map, probe, tap.uv), colour});
    }
    // A cross of half a texel... at least a small fixed size in the map: the probed point.
    const float arm = 0.75f / probe.resolution;
    line(centre - glm::vec2(arm, 0.0f), centre + glm::vec2(arm, 0.0f), kProbe);
    line(centre - glm::vec2(0.0f, arm), centre + glm::vec2(0.0f, arm), kProbe);
}

void ShadowMapViews::draw(Renderer& renderer, ShadowMapView view, const std::vector<ShadowMapInfo>& maps,
                          GLuint framebuffer, glm::ivec2 size, const std::vector<std::vector<glm::vec3>>* bodies,
                          const KernelProbe* probe) {
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
    if ((view == ShadowMapView::Coverage || view == ShadowMapView::FocusBody) && count > 0) {
        // The light frusta over it, not depth tested: a volume behind a wall still shows.
        glUseProgram(shaders_->program(frustumProgram_));
        glBindVertexArray(emptyVao_.get());
        glLineWidth(1.0f);
        glDrawArraysInstanced(GL_LINES, 0, 24, GLsizei(count));
    }
    if (view == ShadowMapView::FocusBody && bodies) {
        // B's edges last, white over everything (behind surfaces too: B is a volume).
        std::vector<OverlayVertex> lines;
        for (size_t i = 0; i < std::min(bodies->size(), count); ++i)
            for (const glm::vec3& p : (*bodies)[i]) lines.push_back({p, overlay_colour::kFocusBody});
        drawOverlay(lines, GL_LINES);
    }
    if (view == ShadowMapView::Kernel && probe && probe->valid && count > 0) {
        std::vector<OverlayVertex> lines, points;
        kernelOverlay(maps[0], *probe, lines, points);
        // The taps first, the outlines over them (a small box stays visible among its taps).
        glPointSize(4.0f);
        drawOverlay(points, GL_POINTS);
        glPointSize(1.0f);
        glLineWidth(1.0f);
        drawOverlay(lines, GL_LINES);
    }
    glBindVertexArray(0);
    for (GLuint unit = 0; unit < 3; ++unit) glBindSampler(unit, 0);
}

} // namespace shadowlab
