// The depth complexity of the main pass, measured without stalling (issue 32): a
// GL_SAMPLES_PASSED query around the opaque draws of the pass that depth-tests them with LESS,
// in a ring of kSlots queries created once, read only when GL_QUERY_RESULT_AVAILABLE says so.
// The GPU timer keeps the CPU at most GpuTimer::kFramesInFlight frames ahead, so a result is
// available kFramesInFlight frames after its query at the latest; a slot whose result is still
// pending is skipped for that frame rather than waited for.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "gl/gl.h"

namespace shadowlab {

class OverdrawCounter {
public:
    static constexpr int kSlots = 6;

    OverdrawCounter() = default;
    ~OverdrawCounter();
    OverdrawCounter(const OverdrawCounter&) = delete;
    OverdrawCounter& operator=(const OverdrawCounter&) = delete;

    void create();    // the queries (a GL context is current)
    void release();
    // Around the counted draws; `samples` is the target's sample count (pixels x MSAA samples).
    // begin() returns false (and end() then does nothing) when the next slot is still in flight.
    bool begin(uint64_t samples);
    void end();
    // The newest finished count as fragments per sample, oldest first; none when no query
    // finished since the last call. Never waits.
    std::optional<double> poll();
    // The queries in flight measure something no longer wanted (a new scene): poll() drops them.
    void discardPending();

private:
    struct Slot {
        GLuint query = 0;
        uint64_t samples = 0;
        bool pending = false;
        bool discarded = false;
    };
    std::array<Slot, kSlots> slots_{};
    int next_ = 0;      // the slot the next begin() uses
    int oldest_ = 0;    // the oldest slot that may be pending
    bool open_ = false;
};

} // namespace shadowlab
