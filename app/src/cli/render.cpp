// `shadowlab render`: one frame headless to a PNG, or every frame of a path, a comparison of two
// techniques, or the kernel view around a probed pixel (slides of the window).
#include "cli/cli.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/bench.h"
#include "bench/path_run.h"
#include "bench/report.h"
#include "bench/stress.h"
#include "groundtruth/reference_technique.h"
#include "render/render_limits.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "bench/tour_pages.h"
#include "util/log.h"
#include "util/paths.h"
#include "util/progress.h"
#include "util/scratch_dir.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"
#include "util/video_export.h"

namespace shadowlab::cli {
namespace {

// Shadow term as grey (sRGB-encoded), pixels outside the comparison dark blue: `--view reference`.
Image visibilityImage(const std::vector<glm::vec3>& visibility, const std::vector<uint8_t>& mask, int width, int height) {
    Image image{width, height, 4, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
    for (size_t i = 0; i < visibility.size(); ++i) {
        for (int c = 0; c < 3; ++c) {
            const float v = std::clamp(visibility[i][c], 0.0f, 1.0f);
            const float srgb = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
            image.pixels[i * 4 + size_t(c)] = mask[i] ? uint8_t(std::lround(srgb * 255.0f)) : uint8_t(c == 2 ? 38 : 13);
        }
    }
    return image;
}

ViewSelection parseView(const std::string& text) { return viewFromName(text); }

// The kernel view as a slide: the window's frame loop offscreen without the panel, so the
// footprint's numbers are drawn beside it, and printed.
int renderProbeSlide(App& app, const std::string& technique, const std::string& view, int frames, const std::string& out,
                     glm::ivec2 probePixel) {
    // The kernel view as a slide: the window's frame loop offscreen without the panel, so the
    // footprint's numbers are drawn beside it, and printed.
    WindowOptions w;
    w.frames = std::max(frames, 1);
    w.screenshot = out;
    w.hideUi = true;
    InteractiveOptions options;
    if (int code = windowOptionsProblem(app, w, technique, options)) return code;
    options.view = parseView(view);
    options.probe = probePixel;
    const int code = app.runInteractive(options);
    if (code) return code;
    const KernelProbe& measured = app.lastProbe();
    std::printf("probe %d,%d: %s\n", probePixel.x, probePixel.y, describeProbe(measured).c_str());
    if (measured.valid)
        std::printf("probe %d,%d: kernel=%s n=%d kernel_texels=%.4f samples=%d early_out=%d lit=%.4f search_texels=%.4f "
                    "search_samples=%d blockers=%d blocker_depth=%.5f receiver_depth=%.5f penumbra_texels=%.4f "
                    "penumbra_world=%.5f decision=%s\n",
                    probePixel.x, probePixel.y,
                    measured.kernel == FilterKernel::Box    ? "box"
                    : measured.kernel == FilterKernel::Disc ? "disc"
                                                            : "pcss",
                    measured.n, double(measured.kernelTexels), measured.samplesTaken, measured.earlyOut ? 1 : 0,
                    double(measured.lit), double(measured.searchRadiusTexels), measured.searchSamples, measured.blockers,
                    double(measured.averageBlockerDepth), double(measured.receiverDepth), double(measured.kernelTexels),
                    double(measured.penumbraWorld), measured.decision.empty() ? "-" : measured.decision.c_str());
    std::fflush(stdout);
    logInfo("wrote " + out);
    return 0;
}

// `render --path P --export FILE`: the path's frames into a scratch folder (or --out when given)
// and encoded by ffmpeg into FILE.
int renderPathExport(App& app, const std::string& technique, const std::string& path, int pathFrames, const std::string& view,
                     const std::string& out, const std::string& exportFile) {
    std::string error;
    std::filesystem::path folder = out;
    if (folder.empty()) {
        const std::filesystem::path scratch = scratchDir(error);
        if (scratch.empty()) return fail(error, kExitFailure);
        folder = scratch / "export-frames";
        std::filesystem::remove_all(folder);
    }
    if (const int code = renderPath(app, technique, path, pathFrames, view, folder, error, false)) return fail(error, code);
    if (!encodeFrames(folder, 30, exportFile, error)) return fail("--export " + error, kExitFailure);
    if (out.empty()) std::filesystem::remove_all(folder);
    logInfo("wrote " + exportFile);
    return 0;
}

// A host debug view as a slide: the window's frame loop offscreen without the panel, with the
// view's legend drawn over it.
int renderViewSlide(App& app, const std::string& technique, const std::string& view, int frames, const std::string& out) {
    WindowOptions w;
    w.frames = std::max(frames, 1);
    w.screenshot = out;
    w.hideUi = true;
    InteractiveOptions options;
    if (int code = windowOptionsProblem(app, w, technique, options)) return code;
    options.view = parseView(view);
    const int code = app.runInteractive(options);
    if (code == 0) logInfo("wrote " + out);
    return code;
}

// --out and --export, checked before the app starts: a missing encoder costs no frames.
int renderOutputsProblem(const std::string& out, const std::string& exportFile, const std::string& path) {
    if (out.empty() && exportFile.empty()) return fail("--out: required (or --path P --export FILE)", kExitBadInput);
    if (exportFile.empty()) return 0;
    if (path.empty())
        return fail("--export " + exportFile + ": exports a path (--path P); a tour step is exported by the window: "
                    "--tour T --tour-step N --frames N --export FILE",
                    kExitBadInput);
    if (const std::string problem = exportProblem("--export", exportFile); !problem.empty()) return fail(problem, kExitBadInput);
    if (std::string error; !outputProblem("--export", exportFile, false, error)) return fail(error, kExitBadInput);
    return 0;
}

// --technique and the techniques --compare names beside it ("B" or "B,C,D"), each known.
int unknownTechniqueProblem(App& app, const std::string& technique, const std::string& others) {
    std::vector<std::string> named;
    std::string error;
    if (!others.empty() && !splitList(others, "--compare", named, error)) return fail(error, kExitBadInput);
    named.insert(named.begin(), technique);
    for (const std::string& id : named) {
        if (id.empty() || app.techniques().find(id)) continue;
        std::string known;
        for (const auto& t : app.techniques().techniques()) appendListItem(known, t.id);
        return fail(std::string(others.empty() ? "--technique '" : "--compare: '") + id + "': no such technique (available: " +
                        known + ")",
                    kExitBadInput);
    }
    return 0;
}

int commandRender(const CommonOptions& common, const std::string& out, const std::string& view, int frames,
                  const std::string& reference, int samples, const WindowOptions& compare, const std::string& path,
                  int pathFrames, const std::string& probe, const std::string& exportFile) {
    if (int code = renderOutputsProblem(out, exportFile, path)) return code;
    glm::ivec2 probePixel(0);
    if (!probe.empty()) {
        // Checked before the app starts: a bad value costs no context.
        if (!parseProbe(probe, probePixel))
            return fail("--probe '" + probe + "': expected X,Y, the pixel from the top left (e.g. 640,360)", kExitBadInput);
        if (view != "kernel")
            return fail("--probe: the kernel view draws the probe (--view kernel), not --view " + view, kExitBadInput);
        if (!compare.compare.empty() || !path.empty())
            return fail("--probe: one technique, one frame (without --compare or --path)", kExitBadInput);
    }
    std::string error;
    if (!out.empty() && !outputProblem("--out", out, !path.empty(), error)) return fail(error, kExitBadInput);
    // The sets go to --technique, or to A of --compare A,B[,...] (which the app checks again).
    std::vector<std::string> compared;
    if (!compare.compare.empty() && !splitList(compare.compare, "--compare", compared, error)) return fail(error, kExitBadInput);
    if (int code = techniqueOptionsProblem(compared.size() > 1 ? compared.front() : common.technique, common.sets)) return code;
    App app;
    if (int code = startApp(app, common, false)) return code;
    if (!probe.empty()) {
        const glm::ivec2 size = app.renderer().size();
        if (probePixel.x >= size.x || probePixel.y >= size.y)
            return fail("--probe " + probe + ": outside the " + std::to_string(size.x) + "x" + std::to_string(size.y) +
                            " image (x < " + std::to_string(size.x) + ", y < " + std::to_string(size.y) + ")",
                        kExitBadInput);
        app.setProbePixel(probePixel);
    }
    std::string technique = common.technique.empty() ? app.firstTechnique() : common.technique;
    if (!path.empty()) {
        // Every frame of a camera and light path, numbered, into the folder --out (docs/stability.md).
        if (!compare.compare.empty()) return fail("--path: one technique at a time (without --compare)", kExitBadInput);
        if (view == "error" || view == "reference") return fail("--path: --view " + view + " is not drawn per frame", kExitBadInput);
        if (!app.techniques().find(technique)) return fail("--technique '" + technique + "': no such technique", kExitBadInput);
        if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
        if (const std::string problem = app.viewProblem(technique, view); !problem.empty()) return fail("--" + problem, kExitBadInput);
        if (!exportFile.empty()) return renderPathExport(app, technique, path, pathFrames, view, out, exportFile);
        const int code = renderPath(app, technique, path, pathFrames, view, out, error);
        return code ? fail(error, code) : 0;
    }
    // --compare A,B (or --compare B with --technique A): both techniques in one image, labelled;
    // A,B,C[,D]: a grid of three or four.
    std::string other, others;
    if (!compare.compare.empty()) {
        std::vector<std::string> ids;
        if (!splitList(compare.compare, "--compare", ids, error)) return fail(error, kExitBadInput);
        if (ids.size() > 1) technique = ids.front();
        for (size_t i = ids.size() > 1 ? 1 : 0; i < ids.size(); ++i) others += (others.empty() ? "" : ",") + ids[i];
        other = ids.size() > 1 ? ids[1] : ids.front();
        if (technique.empty() || other.empty() || ids.size() > size_t(kMaxGridSides))
            return fail("--compare '" + compare.compare + "': expected A,B (two technique ids, e.g. pcss,reference), "
                        "A,B,C[,D] (a grid) or one id to compare --technique with",
                        kExitBadInput);
        if (view != "lit" && view != "visibility")
            return fail("--view " + view + ": --compare shows lit or visibility", kExitBadInput);
    }
    if (int code = unknownTechniqueProblem(app, technique, others)) return code;
    if (!app.applyAssignments(common.sets, technique, error)) return fail(error, kExitBadInput);
    // The one check of a view name (tours and sessions get it too), before the first frame kept.
    if (const std::string problem = app.viewProblem(technique, view, {"reference"}); !problem.empty())
        return fail("--" + problem, kExitBadInput);
    if (!other.empty()) {
        WindowOptions w = compare;
        w.compare = others;
        w.frames = std::max(frames, 1);
        w.screenshot = out;
        w.hideUi = true;   // a slide: the view and the two labels
        InteractiveOptions options;
        if (int code = windowOptionsProblem(app, w, technique, options)) return code;
        options.view = parseView(view);
        const int code = app.runInteractive(options);
        if (code == 0) logInfo("wrote " + out);
        return code;
    }
    // The host's debug views are slides of the window's frame loop (their legends are drawn with
    // its overlays); the kernel view without --probe probes a shadow edge near the centre.
    const ViewSelection::Kind kind = parseView(view).kind;
    if (kind == ViewSelection::Kind::Kernel && probe.empty()) {
        const std::optional<glm::ivec2> edge = app.shadowEdgePixel(technique);
        if (!edge) return fail("--view kernel: no shadow edge in the frame to probe; give --probe X,Y", kExitBadInput);
        probePixel = *edge;
        app.setProbePixel(probePixel);
        logInfo("--view kernel: probing " + std::to_string(edge->x) + "," + std::to_string(edge->y) +
                ", the shadow edge nearest the centre (--probe X,Y picks another)");
    }
    if (kind == ViewSelection::Kind::Kernel) return renderProbeSlide(app, technique, view, frames, out, probePixel);
    if (kind == ViewSelection::Kind::Footprint || kind == ViewSelection::Kind::TexelGrid ||
        kind == ViewSelection::Kind::MapCoverage || kind == ViewSelection::Kind::FocusBody)
        return renderViewSlide(app, technique, view, frames, out);
    Progress progress("render: drawing " + technique, uint64_t(std::max(frames, 1)), "frames");   // a huge scene on llvmpipe
    for (int i = 0; i < std::max(frames, 1); ++i) {
        if (!app.renderFrame(technique, error)) return fail(error, kExitFailure);
        progress.step(uint64_t(i + 1));
    }
    Image image;
    if (view == "error" || view == "reference") {
        // Accuracy views: the reference traced from this frame's own G-buffer.
        std::vector<ReferenceOptions::Mode> modes;
        if (!referenceModes(reference == "auto" ? "hard" : reference, *app.techniques().find(technique), modes, error))
            return fail(error, kExitBadInput);
        ReferenceOptions options;
        options.mode = modes.front();
        options.samplesPerPixel = samples;
        options.adaptive = true;   // as eval and bench: all the rays only where a penumbra may be
        options.model = TranslucencyModel::Physical;
        Evaluation evaluation;
        if (!app.evaluate(options, evaluation, error)) return fail(error, kExitFailure);
        image = view == "error" ? evaluation.heatmap()
                                : visibilityImage(evaluation.reference, evaluation.mask, evaluation.width, evaluation.height);
    } else {
        if (!app.presentView(technique, parseView(view), ~0u, {}, error)) return fail(error, kExitBadInput);
        image = app.readDisplay();
        if (parseView(view).kind == ViewSelection::Kind::Kernel) std::printf("%s\n", describeProbe(app.lastProbe()).c_str());
    }
    if (!writePng(out, image, error)) return fail(error, kExitFailure);
    logInfo("wrote " + out);
    return 0;
}

class RenderCommand final : public Command {
public:
    CLI::App* declare(CLI::App& cli) override {
        auto* render = command_ = cli.add_subcommand("render", "render one frame headless to a PNG file");
        render->add_option("--out,-o", out_, "PNG file to write (with --path: the folder of frames)");
        render->add_option("--view", view_,
                           "lit | visibility | error (heatmap vs the reference) | reference | footprint (texel footprint m, "
                           "log2 heat map) | texel-grid | coverage (which map serves a pixel, and the light frusta) | "
                           "focus-body (the focus body B, seed 002 eq. 4.2, and the map's volume) | kernel (the filter "
                           "kernel around --probe) | a debug image (e.g. 'shadow map')");
        render->add_option("--probe", probe_,
                           "with --view kernel: X,Y, the pixel (from the top left) whose filter kernel is drawn and measured; "
                           "its numbers are printed");
        render->add_option("--frames", frames_, "frames to render before saving (default 3)")->check(CLI::Range(1, 10000));
        render->add_option("--reference", reference_, "--view error/reference: hard | soft (default hard)");
        render->add_option("--samples", samples_, "soft reference: rays per pixel, traced adaptively (default 1024)")
            ->check(CLI::Range(1, 4096));
        render->add_option("--compare", compare_.compare,
                           "A,B: both techniques in one image with their labels (B may be 'reference', the ground truth); A,B,C[,D]: a grid of three or four");
        // Options that mean something only with another are refused alone (CLI11's needs: exit 2).
        CLI::Option* compare = render->get_option("--compare");
        render->add_option("--compare-layout", compare_.compareLayout, "with --compare: side-by-side (default) | wipe | difference | grid (A,B,C[,D] give a grid)")
            ->needs(compare);
        render->add_option("--wipe", compare_.wipe, "with --compare-layout wipe: divider position, 0..1 (default 0.5)")
            ->check(CLI::Range(0.0, 1.0))
            ->needs(compare);
        render->add_option("--ui-scale", compare_.uiScale, "with --compare: size of the labels (default 1)")
            ->check(CLI::Range(0.5, 4.0))
            ->needs(compare);
        render->add_option("--path", path_,
                           "camera and light path (a JSON file, a path of the scene or built-in: orbit, dolly, sweep, walk, "
                           "static): every frame to --out FOLDER/frame_NNNNN.png (and frames.mp4 with ffmpeg)");
        render->add_option("--path-frames", pathFrames_, "with --path: frames along it (default: the path's own)")
            ->check(CLI::Range(1, 100000))
            ->needs(render->get_option("--path"));
        render->get_option("--frames")->excludes(render->get_option("--path"));   // a path draws its own frames
        render->add_option("--export", export_,
                           "with --path: the path as an animated image or video, FILE.gif, .mp4 or .webm (30 frames a "
                           "second; needs the ffmpeg program on PATH); --out then keeps the frames");
        return render;
    }
    int run(const CommonOptions& common) override {
        // Options whose meaning depends on another's value (those that need another at all are
        // declared with CLI11's needs).
        auto given = [&](const char* name) { return command_->get_option(name)->count() > 0; };
        for (const char* option : {"--reference", "--samples"})
            if (given(option) && view_ != "error" && view_ != "reference")
                return fail(std::string(option) + ": only the accuracy views trace the reference (--view error or --view reference)",
                            kExitBadInput);
        if (given("--wipe") && compare_.compareLayout != "wipe")
            return fail("--wipe: places the divider of --compare-layout wipe", kExitBadInput);
        return commandRender(common, out_, view_, frames_, reference_, samples_, compare_, path_, pathFrames_, probe_, export_);
    }
    std::vector<Unused> unusedCommonOptions() const override {
        if (view_ == "error" || view_ == "reference") return {};
        const std::string accuracy = "only the accuracy views (--view error or reference) trace the reference";
        return {{"--translucent-layers", accuracy}, {"--reference-device", accuracy}};
    }

private:
    std::string out_, view_ = "lit", probe_, reference_ = "auto", path_, export_;
    int frames_ = 3, samples_ = BenchSpec{}.referenceSamples, pathFrames_ = 0;
    WindowOptions compare_;
    CLI::App* command_ = nullptr;
};

} // namespace

std::unique_ptr<Command> renderCommand() { return std::make_unique<RenderCommand>(); }

} // namespace shadowlab::cli
