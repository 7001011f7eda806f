// shadow-volumes, extract = compute: record buffers, extraction and indirect draws (volume_records.h).
#include "volume_records.h"

#include <algorithm>
#include <string>

#include "shadow_volumes_shared.h"

namespace shadow_volumes {

using namespace shadowlab;
using namespace shadowlab::shared::shadow_volumes;

namespace {
// The records volume_extract.comp writes (shadow_volumes_shared.h).
constexpr uint64_t kSideBytes = 6 * sizeof(float);
constexpr uint64_t kCapBytes = 9 * sizeof(float);
} // namespace

bool VolumeRecords::create(IHost& host, std::string& error) {
    host_ = &host;
    if (!extract_.build(host, {.computeFile = "volume_extract.comp"}, error) ||
        !indirect_.build(host, {.vertexFile = "volume_indirect.vert", .fragmentFile = "volume_count.frag"}, error))
        return false;
    glCreateVertexArrays(1, &emptyVao_);   // the indirect draws fetch no attributes
    GLint maxBlock = 0;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
    maxBlockBytes_ = uint64_t(std::max(maxBlock, 0));
    return true;
}

void VolumeRecords::destroy() {
    glDeleteVertexArrays(1, &emptyVao_);
    emptyVao_ = 0;
}

const AdjacencyScene* VolumeRecords::prepare() {
    const auto* access = static_cast<const Adjacency*>(host_->extension(SHADOWLAB_EXT_ADJACENCY));
    const AdjacencyScene* scene = access ? access->scene(access->context) : nullptr;
    if (!scene) {
        if (!warned_) host_->log(LogLevel::Warning, "extract = compute: the host has no adjacency extension; using the geometry stage");
        warned_ = true;
        return nullptr;
    }
    // The worst case: a side per edge of a closed mesh (3 per 2 triangles), three sides a
    // triangle of any other mesh, a cap a triangle (volume.geom's rules).
    const uint64_t sides = std::max<uint64_t>(1, (scene->closedTriangles * 3 + 1) / 2 + (scene->triangles - scene->closedTriangles) * 3);
    const uint64_t caps = std::max<uint64_t>(1, scene->triangles);
    if (sides == sideCapacity_ && caps == capCapacity_ && commands_) return scene;
    sides_ = {};
    caps_ = {};
    sideCapacity_ = capCapacity_ = 0;
    const uint64_t bytes = std::max(sides * kSideBytes, caps * kCapBytes);
    if (bytes > maxBlockBytes_ || sides > UINT32_MAX / 6 || caps > UINT32_MAX / 3) {
        if (!warned_)
            host_->log(LogLevel::Warning, ("extract = compute: the worst case of " + std::to_string(scene->triangles) +
                                           " caster triangles needs a storage block of " + std::to_string(bytes >> 20) +
                                           " MiB, over the device's " + std::to_string(maxBlockBytes_ >> 20) +
                                           " MiB; using the geometry stage").c_str());
        warned_ = true;
        return nullptr;
    }
    sides_ = kit::Buffer(*host_, host_->createBuffer(size_t(sides * kSideBytes), nullptr, 0, "volume sides"));
    caps_ = kit::Buffer(*host_, host_->createBuffer(size_t(caps * kCapBytes), nullptr, 0, "volume caps"));
    if (!commands_) {   // {count, instances 1, first 0, base instance 0} x 3; the counts cleared every frame
        const uint32_t commands[12] = {0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0};
        commands_ = kit::Buffer(*host_, host_->createBuffer(sizeof(commands), commands, 0, "volume indirect draws"));
    }
    sideCapacity_ = uint32_t(sides);
    capCapacity_ = uint32_t(caps);
    warned_ = false;
    return scene;
}

void VolumeRecords::release() {
    sides_ = {};
    caps_ = {};
    commands_ = {};
    sideCapacity_ = capCapacity_ = 0;
}

// One dispatch per batch of objects sharing a mesh, chunked so no index overflows.
void VolumeRecords::extract(const AdjacencyScene& scene, float push) {
    GpuPass pass(*host_, "volume extract");
    const GLuint zero = 0;
    for (uint32_t command : {kSideCommand, kNearCapCommand, kFarCapCommand})
        glClearNamedBufferSubData(commands_, GL_R32UI, command * sizeof(uint32_t), sizeof(uint32_t), GL_RED_INTEGER,
                                  GL_UNSIGNED_INT, &zero);
    glUseProgram(extract_.get());
    glUniform1f(kPushLocation, push);
    glUniform2ui(kCapacityLocation, sideCapacity_, capCapacity_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, scene.transforms);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kVerticesBinding, scene.vertices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kAdjacencyBinding, scene.indices);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSidesBinding, sides_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCapsBinding, caps_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCommandsBinding, commands_);
    constexpr uint64_t kMaxGroupsX = 65535, kMaxInvocations = uint64_t(1) << 31;
    for (uint32_t b = 0; b < scene.batchCount; ++b) {
        const AdjacencyBatch& batch = scene.batches[b];
        if (batch.triangleCount == 0) continue;
        glUniform2i(kMeshLocation, batch.baseVertex, GLint(batch.closed));
        const uint32_t perDispatch = uint32_t(std::clamp<uint64_t>(kMaxInvocations / batch.triangleCount, 1, batch.objectCount));
        for (uint32_t first = 0; first < batch.objectCount; first += perDispatch) {
            const uint32_t objects = std::min(perDispatch, batch.objectCount - first);
            const uint64_t groups = (uint64_t(objects) * batch.triangleCount + kExtractGroupSize - 1) / kExtractGroupSize;
            const uint64_t x = std::min(groups, kMaxGroupsX);
            glUniform4ui(kBatchLocation, batch.firstObject + first, objects, batch.firstTriangle, batch.triangleCount);
            glDispatchCompute(GLuint(x), GLuint((groups + x - 1) / x), 1);
        }
    }
    // The draws read the commands and the records; next frame's clear follows the atomics.
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void VolumeRecords::draw(float push, float increment, bool edges) {
    glUseProgram(indirect_.get());
    glUniform1f(kPushLocation, push);
    glUniform1f(kIncrementLocation, increment);
    glUniform2ui(kCapacityLocation, sideCapacity_, capCapacity_);
    glBindVertexArray(emptyVao_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kSidesBinding, sides_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCapsBinding, caps_);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_);
    auto draw = [](GLenum mode, int what, uint32_t command) {
        glUniform1i(kDrawLocation, what);
        glDrawArraysIndirect(mode, reinterpret_cast<const void*>(uintptr_t(command) * sizeof(uint32_t)));
    };
    if (edges) {
        draw(GL_LINES, kDrawEdges, kSideCommand);
    } else {
        draw(GL_TRIANGLES, kDrawSides, kSideCommand);
        draw(GL_TRIANGLES, kDrawNearCaps, kNearCapCommand);
        draw(GL_TRIANGLES, kDrawFarCaps, kFarCapCommand);   // count 0 under a directional light
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
}

} // namespace shadow_volumes
