// GPU timer ring (see gpu_timer.h).
#include "render/gpu_timer.h"

#include <chrono>

#include "util/log.h"

namespace shadowlab {

GpuTimer::GpuTimer() {
    for (auto& slot : slots_) glCreateQueries(GL_TIMESTAMP, GLsizei(slot.queries.size()), slot.queries.data());
}

GpuTimer::~GpuTimer() {
    for (auto& slot : slots_) glDeleteQueries(GLsizei(slot.queries.size()), slot.queries.data());
}

int GpuTimer::nextQuery() {
    FrameSlot& slot = slots_[size_t(current_)];
    if (slot.used >= int(slot.queries.size())) return -1;
    return slot.used++;
}

void GpuTimer::beginFrame() {
    current_ = (current_ + 1) % kFramesInFlight;
    FrameSlot& slot = slots_[size_t(current_)];
    // Results of the frame kFramesInFlight back. Normally ready; if the GPU is that far behind,
    // waiting here is what the driver's frame throttling would do anyway, and no frame is lost.
    // The wait is timed here, explicitly, so that no pass and no host CPU figure contains it.
    lastWaitMs_ = 0.0;
    if (slot.pending) {
        const bool wait = !ready(slot);
        const auto start = std::chrono::steady_clock::now();
        collect(slot);   // blocks in GL_QUERY_RESULT only when not ready
        if (wait) lastWaitMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    if (waitHistory_.size() < kMaxHistory) waitHistory_.push_back(lastWaitMs_);
    slot.scopes.clear();
    slot.used = 0;
    slot.pending = false;
    open_.clear();
    begin("frame");
}

void GpuTimer::endFrame() {
    while (!open_.empty()) end();
    slots_[size_t(current_)].pending = true;
}

void GpuTimer::begin(const std::string& name) {
    FrameSlot& slot = slots_[size_t(current_)];
    const int query = nextQuery();
    if (query < 0 || int(slot.scopes.size()) >= kMaxScopesPerFrame) {
        open_.push_back(-1);
        return;
    }
    glQueryCounter(slot.queries[size_t(query)], GL_TIMESTAMP);
    slot.scopes.push_back({name, query});
    open_.push_back(int(slot.scopes.size()) - 1);
}

void GpuTimer::end() {
    if (open_.empty()) return;
    const int scope = open_.back();
    open_.pop_back();
    if (scope < 0) return;
    FrameSlot& slot = slots_[size_t(current_)];
    const int query = nextQuery();
    if (query < 0) return;
    glQueryCounter(slot.queries[size_t(query)], GL_TIMESTAMP);
    slot.scopes[size_t(scope)].endQuery = query;
}

bool GpuTimer::ready(const FrameSlot& slot) const {
    if (slot.used == 0) return true;
    GLuint available = GL_FALSE;
    glGetQueryObjectuiv(slot.queries[size_t(slot.used - 1)], GL_QUERY_RESULT_AVAILABLE, &available);
    return available == GL_TRUE;
}

void GpuTimer::collect(FrameSlot& slot) {
    if (slot.scopes.empty()) return;
    std::map<std::string, double> frame;
    for (const Scope& scope : slot.scopes) {
        if (scope.endQuery < 0) continue;
        GLuint64 begin = 0, end = 0;
        glGetQueryObjectui64v(slot.queries[size_t(scope.beginQuery)], GL_QUERY_RESULT, &begin);
        glGetQueryObjectui64v(slot.queries[size_t(scope.endQuery)], GL_QUERY_RESULT, &end);
        frame[scope.name] += double(end - begin) * 1e-6;   // same name twice in a frame adds up
    }
    for (const auto& [name, ms] : frame) {
        std::vector<double>& samples = history_[name];
        if (samples.size() >= kMaxHistory) samples.erase(samples.begin(), samples.begin() + kMaxHistory / 2);
        samples.push_back(ms);
    }
    latest_ = std::move(frame);
    slot.pending = false;
}

void GpuTimer::drain() {
    for (int i = 1; i <= kFramesInFlight; ++i) {
        FrameSlot& slot = slots_[size_t((current_ + i) % kFramesInFlight)];
        if (slot.pending) collect(slot);
    }
}

} // namespace shadowlab
