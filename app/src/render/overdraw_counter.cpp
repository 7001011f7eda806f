// Samples-passed ring (see overdraw_counter.h).
#include "render/overdraw_counter.h"

namespace shadowlab {

OverdrawCounter::~OverdrawCounter() { release(); }

void OverdrawCounter::create() {
    if (slots_[0].query) return;
    std::array<GLuint, kSlots> names{};
    glCreateQueries(GL_SAMPLES_PASSED, kSlots, names.data());
    for (int i = 0; i < kSlots; ++i) slots_[size_t(i)] = {names[size_t(i)], 0, false};
    next_ = oldest_ = 0;
}

void OverdrawCounter::release() {
    for (const Slot& slot : slots_)
        if (slot.query) glDeleteQueries(1, &slot.query);
    slots_ = {};
    open_ = false;
}

bool OverdrawCounter::begin(uint64_t samples) {
    Slot& slot = slots_[size_t(next_)];
    if (!slot.query || slot.pending || open_ || samples == 0) return false;
    glBeginQuery(GL_SAMPLES_PASSED, slot.query);
    slot.samples = samples;
    slot.discarded = false;
    open_ = true;
    return true;
}

void OverdrawCounter::end() {
    if (!open_) return;
    glEndQuery(GL_SAMPLES_PASSED);
    slots_[size_t(next_)].pending = true;
    next_ = (next_ + 1) % kSlots;
    open_ = false;
}

void OverdrawCounter::discardPending() {
    for (Slot& slot : slots_) slot.discarded = slot.pending;
}

std::optional<double> OverdrawCounter::poll() {
    std::optional<double> newest;
    // In issue order: a later query cannot finish before an earlier one.
    for (int n = 0; n < kSlots; ++n) {
        Slot& slot = slots_[size_t(oldest_)];
        if (!slot.pending) break;
        GLuint available = GL_FALSE;
        glGetQueryObjectuiv(slot.query, GL_QUERY_RESULT_AVAILABLE, &available);
        if (available != GL_TRUE) break;
        GLuint64 passed = 0;
        glGetQueryObjectui64v(slot.query, GL_QUERY_RESULT, &passed);
        if (!slot.discarded) newest = double(passed) / double(slot.samples);
        slot.pending = false;
        oldest_ = (oldest_ + 1) % kSlots;
    }
    return newest;
}

} // namespace shadowlab
