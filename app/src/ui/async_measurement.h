// "Measure accuracy" without stopping the window (issue 32). The GL work happens on the frame
// loop's thread, the rest on one worker thread:
//   start()  (GL thread, in the frame of the click) each side's frame drawn with the accuracy
//            targets, its translucent layers peeled and its lit view presented, as a synchronous
//            measurement does, and all of them queued into one pixel-pack buffer with a fence
//            after them (render/texture_readback.h): nothing waits for the GPU.
//   poll()   (GL thread, once a frame) once the fence has signalled the buffer is mapped and the
//            worker starts: it copies the pixels out (then the buffer is unmapped on the next
//            poll), traces each side's reference with Embree (App::evaluateCapture, which touches
//            no GL) and computes the metrics and the heatmap over the lit view. When it is done,
//            take() hands the sides over; the caller uploads the heatmaps (GL thread).
//   progress() traces finished and rows of the current one (TraceControl), for the panel.
//   cancel() sets the trace's cancel flag (the module takes no new row), joins the worker and
//            drops the readback: the window calls it when the scene or the technique changes,
//            a tour step or session is applied, a new measurement starts, and at exit (the
//            destructor), so the worker never outlives what it reads.
// The reference is traced with one thread fewer than the machine has, leaving one to the frame
// loop (the thread count changes no sample: the figures are those of `eval`).
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "app.h"
#include "render/texture_readback.h"
#include "ui/session.h"

namespace shadowlab {

class AsyncMeasurement {
public:
    struct Side {
        std::string technique;
        ReferenceOptions options;   // mode, rays and translucency model of this side
        double gpuMs = 0.0;         // the side's GPU frame time, shown beside its figures
    };
    enum class Status { Idle, Running, Done, Failed };

    explicit AsyncMeasurement(App& app);
    ~AsyncMeasurement();   // cancel()
    AsyncMeasurement(const AsyncMeasurement&) = delete;
    AsyncMeasurement& operator=(const AsyncMeasurement&) = delete;

    // GL thread. A running measurement is cancelled first. False with `error` when a side's frame
    // cannot be drawn or captured (nothing is left running then).
    bool start(const std::vector<Side>& sides, std::string& error);
    // GL thread, once a frame (see above). Done or Failed until take().
    Status poll();
    // After Done: the sides measured; after Failed: none, with `error`. Idle afterwards.
    std::vector<SideMeasurement> take(std::string& error);
    // GL thread. Idle afterwards; nothing runs and the buffer is unmapped.
    void cancel();
    bool running() const { return job_ != nullptr; }
    // 0..1 over the traces planned (0 until the pixels are copied).
    float progress() const;
    // "reading back the G-buffer", "tracing 2 of 3": what the worker is doing.
    std::string stage() const;
    // The techniques measured (A, then B), to cancel when the view's change.
    std::vector<std::string> techniques() const;

private:
    struct Job;
    void work(Job& job);
    bool captureSide(const Side& request, Job& job, std::string& error);

    App& app_;
    PixelBufferReadback readback_;
    std::unique_ptr<Job> job_;
    std::thread worker_;
};

} // namespace shadowlab
