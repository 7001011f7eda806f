// GPU time per pass with GL_TIMESTAMP queries, ring-buffered over frames so results are read a
// few frames late and the frame loop never waits for the GPU. Scopes may nest.
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

    void beginFrame();     // also collects the oldest frame's results when they are ready
    void endFrame();
    void begin(const std::string& name);
    void end();
    // Blocks until every issued query has its result; for the end of a measurement only.
    void drain();

    // Milliseconds of the most recent completed frame, per pass ("frame" is the whole frame).
    const std::map<std::string, double>& latest() const { return latest_; }
    // Every completed frame's milliseconds per pass since clearHistory().
    const std::map<std::string, std::vector<double>>& history() const { return history_; }
    void clearHistory() { history_.clear(); }

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
    int nextQuery();

    std::array<FrameSlot, kFramesInFlight> slots_;
    int current_ = 0;
    std::vector<int> open_;
    std::map<std::string, double> latest_;
    std::map<std::string, std::vector<double>> history_;
};

} // namespace shadowlab
