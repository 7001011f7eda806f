// GPU time per pass with GL_TIMESTAMP queries, ring-buffered over frames so results are read a
// few frames late. The frame loop waits for the GPU only when it is kFramesInFlight frames
// behind; that wait is explicit and measured (lastWaitMs, waitHistory), never hidden in a pass.
// Scopes may nest.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "gl/gl.h"

namespace shadowlab {

class GpuTimer {
public:
    static constexpr int kFramesInFlight = 4;
    static constexpr int kMaxScopesPerFrame = 32;

    GpuTimer();
    ~GpuTimer();
    GpuTimer(const GpuTimer&) = delete;
    GpuTimer& operator=(const GpuTimer&) = delete;

    // Also collects the results of the frame kFramesInFlight back: at once when the GPU has
    // finished it, otherwise after waiting for it (the CPU is that far ahead: the wait a driver's
    // frame throttling would impose). The wait is timed into lastWaitMs() and waitHistory().
    void beginFrame();
    void endFrame();
    void begin(const std::string& name);
    void end();
    // Blocks until every issued query has its result; for the end of a measurement only.
    void drain();

    // Milliseconds of the most recent completed frame, per pass ("frame" is the whole frame).
    const std::map<std::string, double>& latest() const { return latest_; }
    // Every completed frame's milliseconds per pass since clearHistory().
    // At most kMaxHistory samples per pass are kept (the window runs for hours): the newest.
    const std::map<std::string, std::vector<double>>& history() const { return history_; }
    // CPU milliseconds beginFrame() spent waiting for the GPU, per frame since clearHistory()
    // (0 where the results were ready).
    const std::vector<double>& waitHistory() const { return waitHistory_; }
    double lastWaitMs() const { return lastWaitMs_; }
    void clearHistory() {
        history_.clear();
        waitHistory_.clear();
    }
    static constexpr size_t kMaxHistory = 100000;

private:
    struct Scope {
        std::string name;
        int beginQuery;
        int endQuery = -1;
    };
    struct FrameSlot {
        std::array<GLuint, 2 * kMaxScopesPerFrame + 2> queries{};
        std::vector<Scope> scopes;
        int used = 0;
        bool pending = false;
    };
    void collect(FrameSlot& slot);   // reads the slot's results (waits if the GPU has not finished them)
    bool ready(const FrameSlot& slot) const;   // its last query has a result (no wait)
    int nextQuery();

    std::array<FrameSlot, kFramesInFlight> slots_;
    int current_ = 0;
    std::vector<int> open_;
    std::map<std::string, double> latest_;
    std::map<std::string, std::vector<double>> history_;
    std::vector<double> waitHistory_;
    double lastWaitMs_ = 0.0;
};

} // namespace shadowlab
