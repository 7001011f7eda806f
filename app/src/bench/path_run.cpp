// Running a technique along a path (see path_run.h).
#include "bench/path_run.h"
#include "app_paths.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "render/gpu_timer.h"
#include "render/light_space.h"
#include "shadowlab/kit/focus.h"
#include "bench/bench.h"
#include "util/log.h"
#include "util/progress.h"
#include "util/stats.h"

namespace shadowlab {

bool timePath(App& app, const std::string& technique, const CameraPath& path, const SceneCamera& camera,
              const LightInfo& light, int warmupFrames, PathTiming& out, std::string& error) {
    out = {};
    setPathFrame(app, path, 0, camera, light);
    for (int i = 0; i < warmupFrames; ++i)
        if (!app.renderFrame(technique, error)) return false;
    app.timer().drain();
    app.timer().clearHistory();
    Progress progress(technique + " along path '" + path.name + "'", uint64_t(path.frames), "frames");
    bool finished = true;
    for (int frame = 0; frame < path.frames && finished; ++frame) {
        setPathFrame(app, path, frame, camera, light);
        // Ctrl-C: the frames timed so far are summarised (the caller writes them, marked).
        finished = app.renderFrame(technique, error);
        if (!finished && !interrupted()) return false;
        if (finished) out.cpuMs.push_back(app.lastCpuFrameMs());
        progress.step(out.cpuMs.size());
    }
    app.timer().drain();
    const auto& history = app.timer().history();
    if (const auto frames = history.find("frame"); frames != history.end()) out.frameMs = frames->second;
    if (out.frameMs.empty()) out.frameMs.assign(out.cpuMs.size(), 0.0);   // no timer queries: CPU only
    const TimingSummary s = summarize(out.frameMs);
    out.p5 = s.p5;
    out.p50 = s.median;
    out.p95 = s.p95;
    const auto worst = std::max_element(out.frameMs.begin(), out.frameMs.end());
    out.max = worst == out.frameMs.end() ? 0.0 : *worst;
    out.maxFrame = worst == out.frameMs.end() ? -1 : int(worst - out.frameMs.begin());
    return finished;
}

// The last frame's shadow maps and light seen from another camera: its main pass again with the
// accuracy targets, untimed, `camera` in place of the frame's, so the previous frame's shadow term
// is evaluated at the current frame's pixels exactly. Not for techniques with the camera
// pre-pass (their term is per pixel of their own view).
bool renderPreviousMapsFrom(App& app, const std::string& technique, const CameraInfo& camera, std::string& error) {
    LoadedTechnique* loaded = app.techniques().get(technique, error);
    if (!loaded) return false;
    const std::vector<double>& values = app.params().values(loaded->info());
    const ParamValues params(values.data(), uint32_t(values.size()));
    FrameContext frame = app.lastFrame();
    frame.camera = camera;
    app.renderer().setView(frame.camera, frame.light);
    return app.runMainPasses(*loaded, frame, params, FrameOutputs::Accuracy, false, error);
}

AccuracyMetrics regionMetrics(const Evaluation& e, const std::vector<uint8_t>& region, const CameraInfo& camera) {
    std::vector<uint8_t> mask = e.mask;
    for (size_t i = 0; i < mask.size() && i < region.size(); ++i) mask[i] = mask[i] && region[i];
    AccuracyMetrics m = compareVisibility(e.technique, e.reference, mask, e.width, e.height);
    if (!e.contactBand.empty()) {
        // The contact band inside the region (issue 30).
        std::vector<uint8_t> band = e.contactBand;
        for (size_t i = 0; i < band.size(); ++i) band[i] = mask[i] ? band[i] : 0;
        const ContactBandMetrics contact = contactBandMetrics(band, e.technique, e.reference);
        m.contactFalseLightRate = contact.falseLightRate;
        m.contactBandPixels = contact.bandPixels;
    }
    // Thirds of the visible depth range: with a far plane of 10 000 every visible pixel of a
    // scene would fall into the first third of [near, far].
    float nearest = camera.farPlane, farthest = camera.nearPlane;
    for (size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i]) continue;
        const float depth = -(camera.view * glm::vec4(glm::vec3(e.positions[i]), 1.0f)).z;
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }
    if (farthest > nearest)
        addViewDepthThirds(m, e.technique, e.reference, mask, e.positions.data(), e.width, e.height, camera.view, nearest,
                           farthest);
    return m;
}

bool measurePath(App& app, const std::string& technique, const CameraPath& path, const SceneCamera& camera,
                 const LightInfo& light, const PathAccuracyOptions& options, PathAccuracy& out, std::string& error) {
    out = {};
    setPathFrame(app, path, 0, camera, light);
    for (int i = 0; i < options.warmupFrames; ++i)
        if (!app.renderFrame(technique, error)) return false;
    TemporalFrame previous, current;
    std::vector<TemporalFrameMetrics> temporal;
    TemporalChanges changes;
    const TechniqueInfo* techniqueInfo = app.techniques().find(technique);
    // Exact: the previous frame's maps and light at the current pixels. Techniques with the camera
    // pre-pass (full or depth only) hold a per-pixel term of their own view, so they are
    // reprojected as images instead.
    const bool samePoints = techniqueInfo && !(techniqueInfo->flagsFor(app.params().values(*techniqueInfo)) &
                                               (kTechniqueNeedsCameraPrepass | kTechniqueNeedsCameraDepth));
    std::vector<glm::vec3> previousTechnique, previousReference;
    Progress progress(technique + " along path '" + path.name + "' against the reference", uint64_t(path.frames), "frames");
    for (int frame = 0; frame < path.frames; ++frame) {
        progress.step(uint64_t(frame));   // Ctrl-C stops the next renderFrame
        if (frame > 0 && samePoints) {
            // Frame t's camera, frame t-1's maps and light (the app's light is still t-1's).
            SceneCamera c = camera;
            LightInfo unusedLight = light;
            applyPathState(samplePath(path, path.frameTime(frame)), c, unusedLight);
            app.camera().reset(c);
            if (!renderPreviousMapsFrom(app, technique, app.camera().info(app.renderer().size()), error)) return false;
            const auto positions = app.renderer().readTarget(MainTarget::Position);
            const auto normals = app.renderer().readTarget(MainTarget::Normal);
            const auto visibility = app.renderer().readTarget(MainTarget::Visibility);
            previousTechnique.resize(visibility.size());
            for (size_t i = 0; i < visibility.size(); ++i) previousTechnique[i] = glm::clamp(glm::vec3(visibility[i]), 0.0f, 1.0f);
            const GBufferView gbuffer{app.renderer().size().x, app.renderer().size().y, positions.data(), normals.data()};
            if (!app.traceReference(gbuffer, options.reference, previousReference, error)) return false;
        }
        setPathFrame(app, path, frame, camera, light);
        if (!app.renderFrame(technique, error)) return false;
        Evaluation e;
        if (!app.evaluate(options.reference, e, error)) return false;
        const CameraInfo info = app.lastFrame().camera;
        const std::vector<uint8_t> region = options.region ? options.region(e) : std::vector<uint8_t>(e.mask.size(), 1);
        PathFrameResult result;
        result.frame = frame;
        result.metrics = regionMetrics(e, region, info);
        current.width = e.width;
        current.height = e.height;
        current.positions = e.positions;
        current.technique = e.technique;
        current.reference = e.reference;
        current.mask = e.mask;
        current.viewProjection = info.viewProjection;
        current.eye = info.position;
        if (frame > 0) {
            result.temporal = samePoints ? compareAtSamePoints(previousTechnique, previousReference, current, &changes, &region)
                                         : compareConsecutiveFrames(previous, current, &changes, &region);
            temporal.push_back(result.temporal);
        }
        if (options.onFrame) options.onFrame(result, e, frame > 0 ? &changes : nullptr);
        out.frames.push_back(result);
        std::swap(previous, current);
    }
    out.temporal = summarizeTemporal(temporal);
    return true;
}

int benchPath(App& app, const PathBenchOptions& options, std::vector<nlohmann::json>& rows,
              const std::function<void(const nlohmann::json&)>& onRow, std::string& error) {
    std::vector<std::string> techniques = options.techniques;
    if (techniques.empty())
        for (const auto& info : app.techniques().techniques())
            if (info.category != "reference") techniques.push_back(info.id);
    const std::vector<std::string> scenes = options.scenes.empty() ? std::vector<std::string>{app.scene().name} : options.scenes;
    for (const std::string& id : techniques)
        if (!app.techniques().find(id)) {
            error = "--techniques: no technique '" + id + "'";
            return 2;
        }
    BuiltinPathOptions pathOptions;
    pathOptions.frames = options.frames;
    for (const std::string& scene : scenes) {
        if (scene != app.scene().name && !app.loadScene(scene, {}, error)) return 2;
        CameraPath path;
        if (!resolvePath(options.path, app.scene(), pathOptions, path, error)) return 2;
        const SceneCamera camera = app.scene().camera;
        const LightInfo light = app.light();
        for (const std::string& technique : techniques) {
            const TechniqueInfo& info = *app.techniques().find(technique);
            app.params().resetToDefaults(info);
            if (!app.applyAssignments(options.sets, technique, error)) return 2;
            PathTiming timing;
            const bool timed = timePath(app, technique, path, camera, light, options.warmupFrames, timing, error);
            if (!timed && (!interrupted() || timing.cpuMs.empty())) return 1;
            nlohmann::json row = benchEnvironment(app);
            row.update({{"scene", app.scene().name}, {"technique", technique}, {"path", path.name}, {"frames", path.frames},
                        {"width", app.renderer().size().x}, {"height", app.renderer().size().y},
                        {"frame_ms_p5", timing.p5}, {"frame_ms_p50", timing.p50}, {"frame_ms_p95", timing.p95},
                        {"frame_ms_max", timing.max}, {"frame_ms_max_frame", timing.maxFrame},
                        {"frame_ms_per_frame", timing.frameMs}, {"cpu_ms_per_frame", timing.cpuMs}});
            if (!timed) {
                // Stopped by Ctrl-C: the frames timed so far, said so in the row itself.
                row.update({{"frames", timing.cpuMs.size()}, {"path_frames", path.frames}, {"interrupted", true}});
                rows.push_back(row);
                if (onRow) onRow(row);
                return 1;
            }
            if (options.accuracy) {
                PathAccuracyOptions accuracy;
                accuracy.reference.mode = options.reference;
                accuracy.reference.samplesPerPixel = 64;
                accuracy.reference.adaptive = true;
                accuracy.reference.model = TranslucencyModel::Physical;
                PathAccuracy measured;
                if (!measurePath(app, technique, path, camera, light, accuracy, measured, error)) return 1;
                std::vector<double> flicker{0.0}, mae;
                for (const PathFrameResult& frame : measured.frames) {
                    if (frame.frame > 0) flicker.push_back(frame.temporal.flicker);
                    mae.push_back(frame.metrics.mae);
                }
                row.update({{"flicker_mean", measured.temporal.meanFlicker}, {"flicker_max", measured.temporal.maxFlicker},
                            {"flicker_worst_frame", measured.temporal.worstFrame}, {"popping", measured.temporal.popping},
                            {"popping_frame", measured.temporal.poppingFrame}, {"temporal_noise", measured.temporal.meanNoise},
                            {"flicker_per_frame", flicker}, {"mae_per_frame", mae}});
            }
            rows.push_back(row);
            if (onRow) onRow(row);
        }
    }
    return 0;
}

int renderPath(App& app, const std::string& technique, const std::string& pathText, int frames, const std::string& view,
               const std::filesystem::path& outDir, std::string& error, bool video) {
    CameraPath path;
    BuiltinPathOptions pathOptions;
    pathOptions.frames = frames;
    if (!resolvePath(pathText, app.scene(), pathOptions, path, error)) return 2;
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec || !std::filesystem::is_directory(outDir)) {
        error = "--out " + outDir.string() + ": cannot create the folder of frames" + (ec ? " (" + ec.message() + ")" : "");
        return 1;
    }
    const SceneCamera camera = app.scene().camera;
    const LightInfo light = app.light();
    const ViewSelection selection = viewFromName(view);   // checked by the caller (App::viewProblem)
    Progress progress("render --path '" + path.name + "'", uint64_t(path.frames), "frames");
    for (int frame = 0; frame < path.frames; ++frame) {
        progress.step(uint64_t(frame));
        setPathFrame(app, path, frame, camera, light);
        if (!app.renderFrame(technique, error)) {
            // Ctrl-C: the frames written so far are the result.
            if (interrupted())
                error = "interrupted (Ctrl-C): " +
                        (frame == 0 ? std::string("no frame") : "frames 0 to " + std::to_string(frame - 1)) + " of path '" +
                        path.name + "' written to " + outDir.string() + " (" + std::to_string(frame) + " of " +
                        std::to_string(path.frames) + ")";
            return 1;
        }
        if (!app.presentView(technique, selection, ~0u, {}, error)) return 2;
        char name[32];
        std::snprintf(name, sizeof(name), "frame_%05d.png", frame);
        if (!writePng(outDir / name, app.readDisplay(), error)) return 1;
    }
    logInfo("wrote " + std::to_string(path.frames) + " frames of path '" + path.name + "' to " + outDir.string());
    // A video for slides when ffmpeg is installed (it is not a dependency).
    if (video && std::system("command -v ffmpeg > /dev/null 2>&1") == 0) {
        const std::string command = "ffmpeg -loglevel error -y -framerate 60 -i '" + (outDir / "frame_%05d.png").string() +
                                    "' -pix_fmt yuv420p -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '" + (outDir / "frames.mp4").string() + "'";
        if (std::system(command.c_str()) == 0) logInfo("wrote " + (outDir / "frames.mp4").string());
        else logWarning("ffmpeg could not write " + (outDir / "frames.mp4").string());
    }
    return 0;
}

} // namespace shadowlab
