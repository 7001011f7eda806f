// The GL and host side of cascaded shadow maps (the maths is kit/cascades.h): fitting every
// cascade of a frame with the casters' cull planes, telling the host which cascade serves which
// view depths, and the GPU's reduction of the camera pre-pass to the depth range the view really
// sees (sample distribution shadow maps), read back without waiting (`csm`).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include <glad/gl.h>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <shadowlab/technique.h>

#include "shadowlab/kit/cascades.h"
#include "shadowlab/kit/csm_shared.h"
#include "shadowlab/kit/focus.h"
#include "shadowlab/kit/handles.h"
#include "shadowlab/kit/shadow_map_report.h"

namespace shadowlab::kit {

// Every cascade of the frame, fitted to its slice of `ranges`, with its served view depths; and
// the planes outside which a caster reaches no cascade (directional lights; none for spot lights).
inline void fitCascades(IHost& host, const FrameContext& frame, const CascadeRanges& ranges, const CascadeFitConfig& config,
                        std::vector<Cascade>& cascades, std::vector<glm::vec4>& cullPlanes) {
    const Bounds scene = host.bounds(DrawSet::All);
    const size_t count = ranges.fitBegin.size();
    cascades.assign(count, {});
    cullPlanes.clear();
    if (frame.light.type == LightType::Directional) {
        const glm::mat4 lightView = stableLightView(frame.light);
        const Bounds casters = host.bounds(DrawSet::Casters);
        glm::vec2 lo(1e30f), hi(-1e30f);
        for (size_t i = 0; i < count; ++i) {
            cascades[i] = fitDirectionalCascade(frame.camera, lightView, ranges.fitBegin[i], ranges.splits[i + 1], config,
                                                scene, casters);
            // The rectangle in the shared light view, from the orthographic matrix.
            const glm::mat4& p = cascades[i].light.projection;
            lo = glm::min(lo, glm::vec2((-1.0f - p[3][0]) / p[0][0], (-1.0f - p[3][1]) / p[1][1]));
            hi = glm::max(hi, glm::vec2((1.0f - p[3][0]) / p[0][0], (1.0f - p[3][1]) / p[1][1]));
        }
        // Casters outside every cascade's rectangle reach no map (one set of planes for the
        // single pass; the geometry stage culls per cascade).
        LightSpace all = cascades[0].light;
        all.projection = glm::ortho(lo.x, hi.x, lo.y, hi.y, all.nearPlane, all.farPlane);
        all.viewProjection = all.projection * all.view;
        const float margin = 1e-4f * std::max(glm::length(scene.max - scene.min), 1.0f);
        cullPlanes = mapSidePlanes(all, margin);
    } else {
        const LightSpace sceneFit = host.fitLightSpace(frame.light, DrawSet::All);
        for (size_t i = 0; i < count; ++i)
            cascades[i] = fitPerspectiveCascade(frame.camera, sceneFit, ranges.fitBegin[i], ranges.splits[i + 1], config, scene);
    }
    for (size_t i = 0; i < count; ++i) {
        cascades[i].viewDistanceBegin = ranges.splits[i];
        cascades[i].viewDistanceEnd = ranges.splits[i + 1];
    }
}

// Tells the host which maps a pixel reads: in order, each serving its split range; the first
// from view depth 0 and the last to any depth, as the shader picks them.
inline void reportCascades(IHost& host, const std::vector<Cascade>& cascades, int count, int resolution) {
    static const char* kLabels[kMaxCascades] = {"cascade 0", "cascade 1", "cascade 2", "cascade 3",
                                                "cascade 4", "cascade 5", "cascade 6", "cascade 7"};
    std::array<ShadowMapInfo, kMaxCascades> maps;
    for (int i = 0; i < count; ++i) {
        ShadowMapInfo& m = maps[size_t(i)];
        m.worldToClip = cascades[size_t(i)].light.viewProjection;
        m.size = glm::ivec2(resolution);
        m.viewDistanceBegin = i == 0 ? 0.0f : cascades[size_t(i)].viewDistanceBegin;
        m.viewDistanceEnd = i == count - 1 ? 1e30f : cascades[size_t(i)].viewDistanceEnd;
        m.layer = uint32_t(i);
        m.label = kLabels[i];
    }
    reportShadowMaps(host, maps.data(), uint32_t(count));
}

// `range` narrowed to a measured one (ViewDepthBounds::latest(), a few frames old: 2% of slack
// either way, and never beyond what the view can reach); `range` itself when there is none yet.
inline DepthRange narrowToMeasured(DepthRange range, const std::optional<DepthRange>& measured) {
    if (!measured) return range;
    range.nearDistance = std::clamp(measured->nearDistance / 1.02f, range.nearDistance, range.farDistance);
    range.farDistance = std::clamp(measured->farDistance * 1.02f, range.nearDistance * 1.001f, range.farDistance);
    return range;
}

// The view depths the camera pre-pass holds, reduced on the GPU by a compute program (the
// kit's shaders/view_depth_bounds.comp: min and max as ordered bits in an SSBO at
// CSM_DEPTH_BOUNDS_BINDING), from the pre-pass's depth alone (kTechniqueNeedsCameraDepth: the
// depth-only pre-pass, not the full one with its position, normal and id targets). The 8 bytes
// are copied on the GPU's queue into one slot of a persistently mapped client buffer, a fence
// after the copy; a slot is read through the mapping only once its fence has signalled, so the
// CPU never waits for the GPU. (The first version read the SSBO back with
// glGetNamedBufferSubData after a timestamp query: the query said the GPU was past the dispatch,
// but the driver still synchronises a read of a device buffer with the whole queue, which on the
// H200 serialised CPU and GPU every frame: `range = receivers` and csm's `fit = sdsm` cost 4-5
// ms more a frame, issue 28.) With three slots a result is one to three frames old.
class ViewDepthBounds {
public:
    static constexpr int kRingSize = 3;
    static constexpr GLbitfield kMapBits = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;

    void create(IHost& host) {
        host_ = &host;
        reduced_ = Buffer(host, host.createBuffer(2 * sizeof(uint32_t), nullptr, 0, "view depth bounds"));
        readback_ = Buffer(host, host.createBuffer(kRingSize * 2 * sizeof(uint32_t), nullptr,
                                                   kMapBits | GL_CLIENT_STORAGE_BIT, "view depth bounds readback"));
        mapped_ = static_cast<const uint32_t*>(
            glMapNamedBufferRange(readback_, 0, kRingSize * 2 * sizeof(uint32_t), kMapBits));
    }
    void destroy() {
        for (GLsync& fence : fences_) {
            if (fence) glDeleteSync(fence);
            fence = nullptr;
        }
        if (mapped_) glUnmapNamedBuffer(readback_);
        mapped_ = nullptr;
    }

    // The newest bounds the GPU has finished, if any.
    const std::optional<DepthRange>& latest() const { return latest_; }

    // First collects the newest result the GPU has finished (never waiting), then reduces this
    // frame's pre-pass into the next slot of the ring.
    void reduce(const Program& program) {
        collect();
        const auto* prepass = static_cast<const CameraPrepass*>(host_->extension(SHADOWLAB_EXT_CAMERA_PREPASS));
        if (!prepass || !prepass->depth || !mapped_) return;
        GpuPass pass(*host_, "depth bounds");
        const uint32_t ones = 0xFFFFFFFFu;
        glClearNamedBufferData(reduced_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &ones);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, CSM_DEPTH_BOUNDS_BINDING, reduced_);
        glBindTextureUnit(shared::csm::kPrepassDepthUnit, prepass->depth);
        glBindSampler(shared::csm::kPrepassDepthUnit, host_->sampler(SamplerKind::Nearest));
        glUseProgram(program.get());
        glDispatchCompute(GLuint((prepass->size.x + 15) / 16), GLuint((prepass->size.y + 15) / 16), 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);   // the copy reads what the atomics wrote
        const GLintptr offset = GLintptr(next_) * 2 * GLintptr(sizeof(uint32_t));
        glCopyNamedBufferSubData(reduced_, readback_, 0, offset, 2 * sizeof(uint32_t));
        GLsync& fence = fences_[size_t(next_)];
        if (fence) glDeleteSync(fence);   // never read: a newer result replaces it
        fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        serials_[size_t(next_)] = ++serial_;
        next_ = (next_ + 1) % kRingSize;
    }

private:
    // The newest slot whose fence has signalled (polled with timeout 0), read through the mapping;
    // it and every older slot are then done.
    void collect() {
        int newest = -1;
        for (int i = 0; i < kRingSize; ++i) {
            GLsync fence = fences_[size_t(i)];
            if (!fence || (newest >= 0 && serials_[size_t(i)] < serials_[size_t(newest)])) continue;
            const GLenum status = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);   // poll, no wait
            if (status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED) newest = i;
        }
        if (newest < 0) return;
        for (int i = 0; i < kRingSize; ++i)
            if (fences_[size_t(i)] && serials_[size_t(i)] <= serials_[size_t(newest)]) {
                glDeleteSync(fences_[size_t(i)]);
                fences_[size_t(i)] = nullptr;
            }
        const uint32_t minBits = mapped_[2 * newest], maxBits = ~mapped_[2 * newest + 1];
        float nearest = 0.0f, farthest = 0.0f;
        std::memcpy(&nearest, &minBits, sizeof(float));
        std::memcpy(&farthest, &maxBits, sizeof(float));
        // Nothing drawn (cleared values) or nonsense: keep the previous bounds.
        if (minBits != 0xFFFFFFFFu && std::isfinite(nearest) && std::isfinite(farthest) && farthest >= nearest &&
            nearest > 0.0f)
            latest_ = DepthRange{nearest, farthest};
    }

    IHost* host_ = nullptr;
    Buffer reduced_, readback_;
    const uint32_t* mapped_ = nullptr;
    std::array<GLsync, kRingSize> fences_{};
    std::array<uint64_t, kRingSize> serials_{};
    int next_ = 0;
    uint64_t serial_ = 0;
    std::optional<DepthRange> latest_;
};

} // namespace shadowlab::kit
