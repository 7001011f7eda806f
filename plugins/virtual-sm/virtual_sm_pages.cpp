// Virtual shadow map pages on the GPU (virtual_sm_pages.h): the frame's passes in order.
#include "virtual_sm_pages.h"

#include <algorithm>
#include <numeric>

#include <shadowlab/kit/depth_map.h>

namespace shadowlab::virtual_sm {

namespace {
constexpr GLbitfield kStorage = GL_SHADER_STORAGE_BARRIER_BIT;

kit::Buffer makeStorage(IHost& host, size_t bytes, const char* label) {
    return kit::Buffer(host, host.createBuffer(std::max<size_t>(bytes, 16), nullptr, GL_DYNAMIC_STORAGE_BIT, label));
}
// Grows `buffer` to at least `bytes`, never shrinks it (see VirtualPages::configure).
void growStorage(IHost& host, kit::Buffer& buffer, size_t& capacity, size_t bytes, const char* label) {
    if (buffer && bytes <= capacity) return;
    capacity = std::max(bytes, capacity);
    buffer = makeStorage(host, capacity, label);
}
} // namespace

bool VirtualPages::create(IHost& host, std::string& error) {
    host_ = &host;
    for (int phase = 1; phase <= 5; ++phase) {
        const std::string defines = "VSM_PHASE " + std::to_string(phase);
        if (!allocate_[size_t(phase - 1)].build(host, {.computeFile = "vsm_allocate.comp", .defines = defines.c_str()}, error))
            return false;
    }
    if (!mark_.build(host, {.computeFile = "vsm_mark.comp"}, error) ||
        !cull_.build(host, {.computeFile = "vsm_cull.comp"}, error) ||
        !clear_.build(host, {.vertexFile = "vsm_clear.vert"}, error) ||
        !depth_.build(host, {.vertexFile = "vsm_page_depth.vert"}, error))
        return false;
    framebuffer_ = kit::makeFramebuffer(host, "virtual shadow map atlas");
    state_ = makeStorage(host, VSM_STATE_WORDS * sizeof(uint32_t), "virtual-sm state");
    pairCapacity_ = kPairCapacity;
    pairs_ = makeStorage(host, pairCapacity_ * 2 * sizeof(uint32_t), "virtual-sm page instances");
    glCreateVertexArrays(1, &vao_);
    glVertexArrayVertexBuffer(vao_, 0, pairs_, 0, 2 * sizeof(uint32_t));
    glEnableVertexArrayAttrib(vao_, 0);
    glVertexArrayAttribIFormat(vao_, 0, 2, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao_, 0, 0);
    glVertexArrayBindingDivisor(vao_, 0, 1);   // one (page, object) per instance, from baseInstance
    stats_.create(host, VSM_STATS_WORDS * sizeof(uint32_t), "virtual-sm statistics");
    return true;
}

void VirtualPages::destroy() {
    if (vao_) glDeleteVertexArrays(1, &vao_);
    vao_ = 0;
    stats_.destroy();
}

void VirtualPages::configure(const PageLayout& layout) {
    if (layout == layout_ && atlas_) return;
    layout_ = layout;
    const size_t entries = size_t(layout.virtualPages());
    const size_t physical = size_t(layout.physicalPages());
    // Buffers and atlas only grow: a smaller layout uses their start (the atlas: its corner, through
    // the draws' viewport and the lookup's textureSize). Under llvmpipe every GL object's storage is
    // a malloc'd block; freeing a 16 MiB atlas each time physical_size alternated raised glibc's
    // dynamic mmap threshold to 16 MiB, after which smaller blocks of every technique came from
    // the heap and fragmented it (the soak test's RSS grew). All released with the plugin.
    growStorage(*host_, pageTable_, capacity_[0], entries * 4 * sizeof(uint32_t), "virtual-sm page table");
    growStorage(*host_, requests_, capacity_[1], entries * sizeof(uint32_t), "virtual-sm page requests");
    growStorage(*host_, free_, capacity_[2], physical * sizeof(uint32_t), "virtual-sm free list");
    growStorage(*host_, dirty_, capacity_[3], physical * 4 * sizeof(uint32_t), "virtual-sm pages to draw");
    const glm::ivec2 size = glm::ivec2(layout.atlasPages, layout.atlasRows) * VSM_PAGE_TEXELS;
    if (glm::any(glm::greaterThan(size, atlasSize_))) {
        atlasSize_ = glm::max(size, atlasSize_);
        atlas_ = kit::makeTexture(*host_, {.internalFormat = GL_DEPTH_COMPONENT32F, .width = atlasSize_.x, .height = atlasSize_.y,
                                           .label = "virtual shadow map atlas"});
        kit::attachDepthTarget(*host_, framebuffer_, atlas_, "virtual shadow map atlas");
        host_->registerDebugImage("physical atlas", atlas_, DebugImageKind::Depth);
    }
    invalidate();
}

void VirtualPages::invalidate() {
    const uint32_t zero = 0;
    glClearNamedBufferSubData(pageTable_, GL_R32UI, 0, GLsizeiptr(layout_.virtualPages()) * 16, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    std::vector<uint32_t>& all = freeList_;   // kept: invalidate() runs every frame the light moves
    all.resize(size_t(layout_.physicalPages()));
    std::iota(all.begin(), all.end(), 0u);
    std::reverse(all.begin(), all.end());   // page 0 on top: the atlas fills from its corner
    glNamedBufferSubData(free_, 0, GLsizeiptr(all.size() * sizeof(uint32_t)), all.data());
    std::array<int32_t, VSM_STATE_WORDS> state{};
    state[VSM_FREE_COUNT] = layout_.physicalPages();
    glNamedBufferSubData(state_, 0, sizeof(state), state.data());
}

// Called whenever the light moves (every frame while it does): the buffers are reallocated only
// when the casters outgrow them, so a moving light creates no GL object per frame.
void VirtualPages::setObjects(const std::vector<VsmObject>& objects) {
    objectCount_ = uint32_t(objects.size());
    if (!objects_ || objects.size() > objectCapacity_) {
        objectCapacity_ = std::max<size_t>(objects.size(), 1);
        objects_ = makeStorage(*host_, objectCapacity_ * sizeof(VsmObject), "virtual-sm casters");
        commands_ = makeStorage(*host_, objectCapacity_ * 4 * sizeof(uint32_t), "virtual-sm draw commands");
    }
    if (!objects.empty()) glNamedBufferSubData(objects_, 0, GLsizeiptr(objects.size() * sizeof(VsmObject)), objects.data());
}

void VirtualPages::render(const PageDraw& draw) {
    statsRead_ = stats_.poll() || statsRead_;
    // This frame's counters from zero (GPU-side clears: nothing waits).
    const uint32_t zero = 0;
    glClearNamedBufferSubData(requests_, GL_R32UI, 0, GLsizeiptr(layout_.virtualPages()) * 4, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glClearNamedBufferSubData(state_, GL_R32UI, VSM_DIRTY_COUNT * 4, (VSM_PAIRS - VSM_DIRTY_COUNT + 1) * 4, GL_RED_INTEGER,
                              GL_UNSIGNED_INT, &zero);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_PAGE_TABLE_BINDING, pageTable_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_REQUEST_BINDING, requests_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_STATE_BINDING, state_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_FREE_BINDING, free_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_DIRTY_BINDING, dirty_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_OBJECT_BINDING, objects_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_COMMAND_BINDING, commands_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_PAIR_BINDING, pairs_);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | kStorage);
    mark(draw);
    allocate();
    drawPages(draw);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    stats_.push(state_, 0);
}

void VirtualPages::mark(const PageDraw& draw) {
    GpuPass pass(*host_, "mark pages");
    if (!draw.prepass || !draw.prepass->depth) return;
    const glm::ivec2 size = draw.prepass->size;
    if (draw.levelImage && size != levelImageSize_) {
        levelImageSize_ = size;
        levelImage_ = kit::makeTexture(*host_, {.internalFormat = GL_RGBA8, .width = size.x, .height = size.y,
                                                .label = "page levels"});
        host_->registerDebugImage("page levels", levelImage_, DebugImageKind::Color);
    }
    glBindTextureUnit(shared::virtual_sm::kPrepassDepthUnit, draw.prepass->depth);
    glBindSampler(shared::virtual_sm::kPrepassDepthUnit, host_->sampler(SamplerKind::Nearest));
    const bool writeImage = draw.levelImage && levelImage_;
    if (writeImage)
        glBindImageTexture(shared::virtual_sm::kLevelImageUnit, levelImage_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
    glUseProgram(mark_.get());
    glUniform1i(16, writeImage ? 1 : 0);
    glUniformMatrix4fv(17, 1, GL_FALSE, &draw.inverseViewProjection[0][0]);
    glDispatchCompute(GLuint((size.x + 7) / 8), GLuint((size.y + 7) / 8), 1);
    glMemoryBarrier(kStorage | (writeImage ? GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT : 0));
}

void VirtualPages::dispatchPhase(int phase, GLuint groups) {
    glUseProgram(allocate_[size_t(phase - 1)].get());
    glDispatchCompute(groups, 1, 1);
    glMemoryBarrier(kStorage);
}

void VirtualPages::allocate() {
    GpuPass pass(*host_, "allocate pages");
    const GLuint groups = GLuint((layout_.virtualPages() + 63) / 64);
    dispatchPhase(1, groups);   // release pages the windows left, count marked, cached, needed
    dispatchPhase(5, 1);        // the shortfall
    dispatchPhase(2, groups);   // evict unmarked pages, only as many as are short
    dispatchPhase(3, groups);   // allocate, tag, list the pages to draw
    dispatchPhase(4, 1);        // statistics, the clear pass's indirect command
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT);
}

void VirtualPages::drawPages(const PageDraw& draw) {
    GpuPass pass(*host_, "draw pages");
    if (objectCount_ > 0 && draw.scene) {
        glUseProgram(cull_.get());
        glUniform1ui(16, pairCapacity_);
        glDispatchCompute(GLuint((objectCount_ + 63) / 64), 1, 1);
        glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | kStorage);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, layout_.atlasPages * VSM_PAGE_TEXELS, layout_.atlasRows * VSM_PAGE_TEXELS);
    glBindVertexArray(vao_);
    // Clear the new pages' tiles to the far depth: a quad per page, instance count from the GPU.
    glDepthFunc(GL_ALWAYS);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, state_);
    glUseProgram(clear_.get());
    glDrawArraysIndirect(GL_TRIANGLE_STRIP, reinterpret_cast<const void*>(uintptr_t(VSM_CLEAR_COMMAND * 4)));
    if (objectCount_ > 0 && draw.scene) {
        glDepthFunc(GL_LESS);
        kit::applyCull(kit::Cull(draw.cull));
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(draw.slopeBias, draw.constantBias);
        glEnable(GL_DEPTH_CLAMP);
        for (int plane = 0; plane < 4; ++plane) glEnable(GLenum(GL_CLIP_DISTANCE0 + plane));
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_VERTEX_BINDING, draw.scene->vertices);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_INDEX_BINDING, draw.scene->indices);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_TRANSFORM_BINDING, draw.scene->transforms);
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, commands_);
        glUseProgram(depth_.get());
        glMultiDrawArraysIndirect(GL_TRIANGLES, nullptr, GLsizei(objectCount_), 0);
        for (int plane = 0; plane < 4; ++plane) glDisable(GLenum(GL_CLIP_DISTANCE0 + plane));
    }
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindVertexArray(0);
    glMemoryBarrier(kStorage);
}

void VirtualPages::bindMainPass() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VSM_PAGE_TABLE_BINDING, pageTable_);
    glBindTextureUnit(shared::virtual_sm::kAtlasUnit, atlas_);
    glBindSampler(shared::virtual_sm::kAtlasUnit, host_->sampler(SamplerKind::CompareLinear));
}

void VirtualPages::reportStatistics(IHost& host) const {
    host.reportStatistic("physical pages", layout_.physicalPages());
    // The layout's atlas and its page buffers: what a physical_size^2 map's memory is compared with.
    host.reportStatistic("physical MiB", double(layout_.atlasBytes() + layout_.bufferBytes()) / (1024.0 * 1024.0));
    if (!statsRead_) return;
    const std::vector<uint32_t>& s = stats_.latest();
    host.reportStatistic("pages marked", s[VSM_MARKED]);
    host.reportStatistic("pages allocated", s[VSM_RESIDENT]);
    host.reportStatistic("pages drawn", s[VSM_DIRTY_COUNT]);
    host.reportStatistic("pages cached", s[VSM_CACHED]);
    host.reportStatistic("pages failed", s[VSM_FAILED]);
    host.reportStatistic("pages drawn total", s[VSM_DRAWN_TOTAL]);
    host.reportStatistic("page caster instances", s[VSM_PAIRS]);
}

} // namespace shadowlab::virtual_sm
