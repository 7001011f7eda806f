// The window's measurement on a worker thread (see async_measurement.h).
#include "ui/async_measurement.h"

#include <algorithm>

#include "ui/classroom.h"

namespace shadowlab {

struct AsyncMeasurement::Job {
    struct SideJob {
        Side request;
        SideMeasurement result;   // label, memory and key from the click; figures from the worker
        EvaluationInput input;    // filled by the worker from the mapped buffer
        Image lit;
    };
    std::vector<SideJob> sides;
    TraceControl control;
    std::atomic<int> tracesPlanned{0};
    std::atomic<bool> delivered{false};   // the worker copied the pixels: the buffer may be unmapped
    std::atomic<bool> finished{false};    // results and error are written
    bool workerStarted = false;           // GL thread only
    std::string error;
};

AsyncMeasurement::AsyncMeasurement(App& app) : app_(app) {}

AsyncMeasurement::~AsyncMeasurement() { cancel(); }

bool AsyncMeasurement::start(const std::vector<Side>& sides, std::string& error) {
    cancel();
    if (app_.referenceDevice() != ReferenceDevice::Cpu) {
        error = "the GPU reference traces with GL, on the frame loop's thread only (measureSide)";
        return false;
    }
    job_ = std::make_unique<Job>();
    job_->sides.reserve(sides.size());
    // Every side is drawn at the renderer's size: room for each side's targets, layers and lit view.
    const glm::ivec2 size = app_.renderer().size();
    const size_t litBytes = size_t(size.x) * size_t(size.y) * 4;
    // Layers are peeled only in a scene with translucent surfaces (App::captureTranslucentLayers).
    const auto& materials = app_.scene().materials;
    const bool translucent = std::any_of(materials.begin(), materials.end(), [](const Material& m) { return m.translucent(); });
    const int layers = translucent ? app_.translucentLayers() : 0;
    const size_t reads = 3 * size_t(1 + layers) + 1;   // each padded to 16 bytes
    readback_.begin(sides.size() * (EvaluationInput::bytesFor(size, layers) + litBytes + 16 * reads));
    for (const Side& side : sides)
        if (!captureSide(side, *job_, error)) {
            error = side.technique + ": " + error;
            cancel();
            return false;
        }
    readback_.end();
    return true;
}

// One side's frame, drawn and queued for reading (GL thread).
bool AsyncMeasurement::captureSide(const Side& request, Job& job, std::string& error) {
    Job::SideJob& side = job.sides.emplace_back();
    side.request = request;
    // This side's own frame: the frame before may have been the other side's technique.
    if (!app_.renderFrame(request.technique, error, FrameOutputs::Accuracy)) return false;
    if (!app_.captureEvaluation(side.input, readback_, error)) return false;
    if (!app_.presentView(request.technique, {}, ~0u, {}, error)) return false;
    const glm::ivec2 size = app_.renderer().size();
    side.lit = Image{size.x, size.y, 4, std::vector<uint8_t>(size_t(size.x) * size_t(size.y) * 4)};
    readback_.read(app_.renderer().displayTexture(), GL_RGBA, GL_UNSIGNED_BYTE, side.lit.pixels.size(), side.lit.pixels.data());
    if (!describeSide(app_, request.technique, side.result, error)) return false;
    side.result.gpuMs = request.gpuMs;
    return true;
}

AsyncMeasurement::Status AsyncMeasurement::poll() {
    if (!job_) return Status::Idle;
    if (!job_->workerStarted) {
        if (!readback_.ready()) return Status::Running;
        job_->workerStarted = true;
        if (!readback_.map()) {
            job_->error = "the read-back buffer could not be mapped";
            job_->finished = true;
            return Status::Failed;
        }
        worker_ = std::thread([this, job = job_.get()] { work(*job); });
        return Status::Running;
    }
    if (job_->delivered && readback_.mapped()) readback_.reset();   // the worker has its copy
    if (!job_->finished) return Status::Running;
    if (worker_.joinable()) worker_.join();
    readback_.reset();
    return job_->error.empty() ? Status::Done : Status::Failed;
}

// The worker: no GL here. The buffer stays mapped until `delivered` is set.
void AsyncMeasurement::work(Job& job) {
    readback_.deliver();
    job.delivered = true;
    int planned = 0;
    for (const Job::SideJob& side : job.sides) planned += int(App::plannedTraces(side.input));
    job.tracesPlanned = planned;
    for (Job::SideJob& side : job.sides) {
        ReferenceOptions options = side.request.options;
        options.control = &job.control;
        Evaluation evaluation;
        std::string error;
        if (job.control.cancelled()) error = "cancelled";
        else if (!app_.evaluateCapture(side.input, options, evaluation, error)) error = side.request.technique + ": " + error;
        if (!error.empty()) {
            job.error = error;
            break;
        }
        fillSideFigures(evaluation, side.lit, side.result);
        side.input = {};   // the G-buffer copies are no longer needed
    }
    job.finished = true;
}

std::vector<SideMeasurement> AsyncMeasurement::take(std::string& error) {
    std::vector<SideMeasurement> results;
    if (!job_ || !job_->finished) return results;
    if (worker_.joinable()) worker_.join();
    error = job_->error;
    if (error.empty())
        for (Job::SideJob& side : job_->sides) results.push_back(std::move(side.result));
    job_.reset();
    readback_.reset();
    return results;
}

void AsyncMeasurement::cancel() {
    if (!job_) return;
    job_->control.cancel = true;
    if (worker_.joinable()) worker_.join();
    readback_.reset();
    job_.reset();
}

float AsyncMeasurement::progress() const {
    if (!job_ || !job_->delivered) return 0.0f;
    const TraceControl& control = job_->control;
    const uint64_t total = control.rowsTotal.load();
    const double current = total ? double(control.rowsDone.load()) / double(total) : 0.0;
    const int planned = std::max(1, job_->tracesPlanned.load());
    return float(std::clamp((double(control.tracesDone.load()) + current) / double(planned), 0.0, 1.0));
}

std::string AsyncMeasurement::stage() const {
    if (!job_) return "";
    if (!job_->delivered) return "reading back the frame";
    const int planned = std::max(1, job_->tracesPlanned.load());
    const int done = std::min(job_->control.tracesDone.load(), planned - 1);
    return "tracing the reference, image " + std::to_string(done + 1) + " of " + std::to_string(planned);
}

std::vector<std::string> AsyncMeasurement::techniques() const {
    std::vector<std::string> ids;
    if (job_)
        for (const Job::SideJob& side : job_->sides) ids.push_back(side.request.technique);
    return ids;
}

} // namespace shadowlab
