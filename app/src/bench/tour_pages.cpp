// The headless tour pages (see tour_pages.h).
#include "bench/tour_pages.h"
#include "util/strings.h"

#include <algorithm>
#include <cstdio>
#include <memory>
#include <sstream>

#include "bench/accuracy_columns.h"
#include "bench/path_run.h"
#include "ui/session.h"
#include "ui/tour_player.h"
#include "util/log.h"
#include "util/text_file.h"

namespace shadowlab {
namespace {

struct TechniqueFigures {
    std::string technique;
    std::string displayName;
    std::string reference;        // "hard", "soft", or "" (the reference itself: no error)
    double frameMs = 0.0;         // median GPU ms of a timed frame
    double gpuMiB = 0.0;
    AccuracyMetrics metrics;
    AccuracyMetrics translucent;  // the translucent receivers (comparedPixels 0: none in view)
    // A step with a path: the temporal error (flicker, docs/stability.md) over its first frames.
    int temporalFrames = 0;
    TemporalSummary temporal;
    TexelFootprint footprint;     // medians and undersampled rate only (the per-pixel vectors dropped)
};

struct StepPage {
    std::string image;            // file name in the output folder (a path step: its first frame)
    std::vector<std::pair<std::string, int>> strip;   // a path step: (image, path frame) of its first, middle and last frame
    int pathFrames = 0;
    std::vector<TechniqueFigures> figures;
    std::vector<TourExpectResult> expectations;   // the step's "expect", checked after measuring
};

std::string stepImageName(size_t index, const char* suffix) {
    char name[48];
    std::snprintf(name, sizeof(name), "step-%02zu-%s.png", index + 1, suffix);
    return name;
}

std::string stepImageName(size_t index) {
    char name[32];
    std::snprintf(name, sizeof(name), "step-%02zu.png", index + 1);
    return name;
}

bool measureTechnique(App& app, const std::string& id, const TourPageOptions& options, TechniqueFigures& out,
                      std::string& error) {
    const TechniqueInfo* info = app.techniques().find(id);
    if (!info) {
        error = "no technique '" + id + "'";
        return false;
    }
    out.technique = id;
    out.displayName = info->displayName;
    if (!app.setRenderSize(options.size, error)) return false;
    Measurement m;
    if (!app.measure(id, options.warmupFrames, options.benchFrames, m, error)) return false;
    const auto frame = m.gpuMs.find("frame");
    out.frameMs = frame == m.gpuMs.end() ? 0.0 : frame->second.median;
    out.gpuMiB = double(m.gpuBytes) / (1024.0 * 1024.0);
    if (id == "reference") return true;   // the ground truth itself: nothing to compare
    ReferenceOptions reference;
    reference.mode = ownReferenceMode(*info);
    const bool hard = reference.mode == ReferenceOptions::Mode::Hard;
    reference.samplesPerPixel = options.referenceSamples;
    reference.adaptive = true;
    reference.model = TranslucencyModel::Physical;
    Evaluation evaluation;
    if (!app.evaluate(reference, evaluation, error)) return false;
    out.reference = hard ? "hard" : "soft";
    out.metrics = evaluation.metrics;
    out.translucent = evaluation.translucentMetrics;
    out.footprint = evaluation.footprint;
    out.footprint.m.clear();
    out.footprint.projection.clear();
    out.footprint.depthError.clear();
    return true;
}

// The figures an expectation can name (ui/tour_expect.h), per side; what was not measured is left out.
TourStepFigures expectFigures(const StepPage& page) {
    TourStepFigures out;
    for (size_t s = 0; s < page.figures.size() && s < 2; ++s) {
        const TechniqueFigures& f = page.figures[s];
        auto& m = out.side[s];
        m["frame_ms"] = f.frameMs;
        m["gpu_mib"] = f.gpuMiB;
        if (f.reference.empty()) continue;   // the reference itself: no error
        const AccuracyMetrics& a = f.metrics;
        m["mae"] = a.mae;
        m["false_shadow"] = a.falseShadowRate;
        m["false_light"] = a.falseLightRate;
        m["mae_penumbra"] = a.maePenumbra;
        m["penumbra"] = a.techniquePenumbraFraction;
        m["noise"] = a.noiseEnergy;
        if (a.edgeBandPixels > 0) m["edge_band_mae"] = a.maeEdgeBand;   // hard reference only (groundtruth/edge_band.h)
        const char* thirds[] = {"mae_near", "mae_mid", "mae_far"};
        for (int t = 0; t < 3; ++t)
            if (a.pixelsByViewDepth[size_t(t)] > 0) m[thirds[t]] = a.maeByViewDepth[size_t(t)];
        if (f.translucent.comparedPixels > 0) m["translucent_mae"] = f.translucent.mae;
        if (f.temporalFrames >= 2) m["flicker"] = f.temporal.meanFlicker;
        if (f.footprint.measuredPixels > 0) {
            m["footprint_near"] = f.footprint.medianByViewDepth[0];
            m["footprint_far"] = f.footprint.medianByViewDepth[2];
            m["undersampled"] = f.footprint.undersampledFraction;
        }
    }
    return out;
}

// The temporal error of `id` along the first `frames` frames of the step's path (the path's own
// spacing kept, so the dolly still moves a fraction of a texel a frame), against the reference of
// measureTechnique's kind: measurePath (bench/path_run.h), each frame traced twice.
bool measurePathTemporal(App& app, const std::string& id, const CameraPath& path, const SceneCamera& camera,
                         const LightInfo& light, const TourPageOptions& options, TechniqueFigures& out, std::string& error) {
    if (id == "reference" || options.pathMeasureFrames < 2) return true;
    const TechniqueInfo* info = app.techniques().find(id);
    if (!info) {
        error = "no technique '" + id + "'";
        return false;
    }
    CameraPath first = path;
    first.frames = std::min(path.frames, options.pathMeasureFrames);
    first.endTime = path.frameTime(first.frames - 1);
    PathAccuracyOptions accuracy;
    accuracy.reference.mode = ownReferenceMode(*info);
    accuracy.reference.samplesPerPixel = options.referenceSamples;
    accuracy.reference.adaptive = true;
    accuracy.reference.model = TranslucencyModel::Physical;
    PathAccuracy result;
    if (!app.setRenderSize(options.size, error)) return false;
    if (!measurePath(app, id, first, camera, light, accuracy, result, error)) return false;
    out.temporalFrames = first.frames;
    out.temporal = result.temporal;
    return true;
}

std::string temporalLine(const StepPage& page, const TourStep& step) {
    std::string line = "Path " + step.path + ", " + std::to_string(page.pathFrames) + " frames (above: frames";
    for (const auto& [image, frame] : page.strip) line += " " + std::to_string(frame + 1);
    line += ").";
    for (const TechniqueFigures& f : page.figures) {
        if (f.temporalFrames < 2) continue;
        line += " " + f.technique + ": temporal error (flicker) " + fixed(f.temporal.meanFlicker, 5) + " mean, " +
                fixed(f.temporal.maxFlicker, 5) + " max over its first " + std::to_string(f.temporalFrames) + " frames;";
    }
    if (line.back() == ';') line.back() = '.';
    return line;
}

// What each column means: said once, on both pages.
const char* const kColumns[][2] = {
    {"technique", "the technique measured (A, then B when the step compares two)"},
    {"reference", "what it is compared with: the hard (one ray to the light's centre) or soft (rays over the light's "
                  "area) ray-traced reference; hard for hard techniques, soft for filtered and soft ones"},
    {"MAE", "mean absolute error of the shadow term against the reference, over the compared (lit-side) pixels: every "
            "shade of difference counts, as on the error heatmap (magenta: darker than the reference, green: lighter)"},
    {"false shadow", "the share of compared pixels the reference lights (>= 0.5) that the technique darkens below 0.5: "
                     "acne, over-darkening. A surface darkened by less than half (a wide filter's grey) raises the MAE and "
                     "is magenta on the heatmap, but is not counted here"},
    {"false light", "the share of compared pixels the reference shadows (< 0.5) that the technique lights above 0.5: leaks, "
                    "peter panning, light bleeding; a shadow only lightened is, likewise, in the MAE alone"},
    {"translucent MAE", "the same on the translucent surfaces themselves (peeled from the camera, seed 001 sec. 5.3.3); "
                        "- where the step shows none facing the light"},
    {"frame ms", "median GPU time of a whole frame over the short benchmark (" "warm-up, then timed frames)"},
    {"GPU MiB", "the technique's own GPU memory (shadow maps, blurred copies)"},
};

std::string figureCell(const TechniqueFigures& f, int column) {
    const bool measured = !f.reference.empty();
    switch (column) {
    case 0: return f.displayName + " (" + f.technique + ")";
    case 1: return measured ? f.reference : "(is the reference)";
    case 2: return measured ? fixed(f.metrics.mae, 4) : "-";
    case 3: return measured ? fixed(100.0 * f.metrics.falseShadowRate, 2) + "%" : "-";
    case 4: return measured ? fixed(100.0 * f.metrics.falseLightRate, 2) + "%" : "-";
    case 5: return measured && f.translucent.comparedPixels > 0 ? fixed(f.translucent.mae, 4) : "-";
    case 6: return fixed(f.frameMs, 3);
    case 7: return fixed(f.gpuMiB, 2);
    }
    return "";
}

constexpr int kColumnCount = int(sizeof(kColumns) / sizeof(kColumns[0]));

const char* const kExpectNote =
    "Under a caption, what it claims as data (the step's \"expect\", docs/classroom.md), each checked against the "
    "figures of its table: passed, or FAILED in red with the figure measured.";

// The step's expectations under its caption, a failed one marked in red and in words.
std::string expectHtml(const StepPage& page) {
    if (page.expectations.empty()) return "";
    std::string out = "<ul class=\"expect\">\n";
    for (const TourExpectResult& r : page.expectations)
        out += std::string("<li class=\"") + (r.passed ? "passed\">passed: " : "failed\">FAILED: ") +
               htmlEscape(tourExpectLine(r)) + "</li>\n";
    return out + "</ul>\n";
}

std::string htmlPage(const Tour& tour, const std::vector<StepPage>& pages, const TourPageOptions& options) {
    std::ostringstream html;
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << htmlEscape(tour.title)
         // Never wider than the window (a 1280-pixel projector included): the tables take the
         // page's width and wrap their cells rather than scroll sideways.
         << "</title>\n<style>\nbody{font-family:sans-serif;max-width:" << options.size.x + 40
         << "px;margin:2em auto;padding:0 1em;box-sizing:border-box;line-height:1.45;color:#222;overflow-wrap:anywhere}\n"
            "table{width:100%;table-layout:fixed}\nfigure{margin:0 0 1em}\nimg{max-width:100%;height:auto;"
            "border:1px solid #ccc}\nfigcaption{margin-top:.5em}\ntable{border-collapse:collapse;margin:.5em 0 2em}\n"
            "td,th{border:1px solid #ccc;padding:.2em .5em;text-align:right}\ntd:first-child,th:first-child{text-align:left}\n"
            "dt{font-weight:bold}\nul.expect{margin:.3em 0;padding-left:1.2em;font-size:90%}\nli.passed{color:#2a6a2a}\n"
            "li.failed{color:#b00000;font-weight:bold}\n</style>\n</head>\n<body>\n<h1>"
         << htmlEscape(tour.title) << "</h1>\n";
    if (!tour.description.empty()) html << "<p>" << htmlEscape(tour.description) << "</p>\n";
    html << "<p>" << tour.steps.size() << " steps, drawn at " << options.size.x << "x" << options.size.y
         << ". Columns of the tables:</p>\n<dl>\n";
    for (const auto& column : kColumns) html << "<dt>" << column[0] << "</dt><dd>" << htmlEscape(column[1]) << "</dd>\n";
    html << "</dl>\n<p>" << htmlEscape(kExpectNote) << "</p>\n";
    for (size_t i = 0; i < tour.steps.size(); ++i) {
        const TourStep& step = tour.steps[i];
        html << "<section id=\"step-" << i + 1 << "\">\n<h2>" << i + 1 << ". " << htmlEscape(step.title) << "</h2>\n"
             << "<figure>\n<img src=\"" << pages[i].image << "\" width=\"" << options.size.x << "\" height=\""
             << options.size.y << "\" alt=\"" << htmlEscape(step.title) << "\">\n";
        // A path step: its middle and last frames beside the first, at a third of the width.
        for (size_t k = 1; k < pages[i].strip.size(); ++k)
            html << "<img src=\"" << pages[i].strip[k].first << "\" width=\"" << options.size.x / 2 << "\" height=\""
                 << options.size.y / 2 << "\" alt=\"" << htmlEscape(step.title) << ", path frame " << pages[i].strip[k].second + 1
                 << "\">\n";
        html << "<figcaption>" << htmlEscape(step.caption) << "</figcaption>\n" << expectHtml(pages[i]) << "</figure>\n";
        if (!step.path.empty()) html << "<p class=\"path\">" << htmlEscape(temporalLine(pages[i], step)) << "</p>\n";
        html << "<table>\n<tr>";
        for (const auto& column : kColumns) html << "<th>" << column[0] << "</th>";
        html << "</tr>\n";
        for (const TechniqueFigures& f : pages[i].figures) {
            html << "<tr>";
            for (int c = 0; c < kColumnCount; ++c) html << "<td>" << htmlEscape(figureCell(f, c)) << "</td>";
            html << "</tr>\n";
        }
        html << "</table>\n</section>\n";
    }
    html << "</body>\n</html>\n";
    return html.str();
}

std::string markdownPage(const Tour& tour, const std::vector<StepPage>& pages, const TourPageOptions& options) {
    std::ostringstream md;
    md << "# " << tour.title << "\n\n";
    if (!tour.description.empty()) md << tour.description << "\n\n";
    md << tour.steps.size() << " steps, drawn at " << options.size.x << "x" << options.size.y
       << " (`shadowlab tour`). Columns of the tables:\n\n";
    for (const auto& column : kColumns) md << "- **" << column[0] << "**: " << column[1] << "\n";
    md << "\n" << kExpectNote << "\n\n";
    for (size_t i = 0; i < tour.steps.size(); ++i) {
        const TourStep& step = tour.steps[i];
        md << "## " << i + 1 << ". " << step.title << "\n\n![" << step.title << "](" << pages[i].image << ")";
        for (size_t k = 1; k < pages[i].strip.size(); ++k)
            md << " ![" << step.title << ", path frame " << pages[i].strip[k].second + 1 << "](" << pages[i].strip[k].first << ")";
        md << "\n\n" << step.caption << "\n\n";
        for (const TourExpectResult& r : pages[i].expectations)
            md << "- " << (r.passed ? "passed: " : "**FAILED**: ") << tourExpectLine(r) << "\n";
        if (!pages[i].expectations.empty()) md << "\n";
        if (!step.path.empty()) md << temporalLine(pages[i], step) << "\n\n";
        md << "|";
        for (const auto& column : kColumns) md << " " << column[0] << " |";
        md << "\n|---|";
        for (int c = 1; c < kColumnCount; ++c) md << "---:|";
        md << "\n";
        for (const TechniqueFigures& f : pages[i].figures) {
            md << "|";
            for (int c = 0; c < kColumnCount; ++c) md << " " << figureCell(f, c) << " |";
            md << "\n";
        }
        md << "\n";
    }
    return md.str();
}

// Every step's expectations against its figures (and the previous step's); the failures, one line
// each naming tour, step, expectation and figure, into `failures`.
int checkStepExpectations(const Tour& tour, std::vector<StepPage>& pages, std::string& failures) {
    int failed = 0;
    for (size_t i = 0; i < tour.steps.size(); ++i) {
        const TourStepFigures now = expectFigures(pages[i]);
        const TourStepFigures before = i > 0 ? expectFigures(pages[i - 1]) : TourStepFigures{};
        pages[i].expectations = evaluateTourExpectations(tour.steps[i].expect, now, i > 0 ? &before : nullptr);
        for (const TourExpectResult& r : pages[i].expectations) {
            if (r.passed) continue;
            ++failed;
            failures += "\n  " + tour.source + ": steps[" + std::to_string(i) + "] (\"" + tour.steps[i].title +
                        "\"): expect " + tourExpectLine(r);
        }
    }
    return failed;
}

} // namespace

std::string htmlEscape(const std::string& text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

int writeTourPages(App& app, const Tour& tour, const TourPageOptions& options, std::string& error) {
    std::error_code ec;
    std::filesystem::create_directories(options.outDir, ec);
    if (ec) {
        error = options.outDir.string() + ": cannot create the folder (" + ec.message() + ")";
        return 1;
    }
    if (!checkTourDebugViews(app, tour, error)) return 2;
    std::vector<StepPage> pages(tour.steps.size());
    for (size_t i = 0; i < tour.steps.size(); ++i) {
        const TourStep& step = tour.steps[i];
        // The slide: the window's own frame loop with the step applied by its UiCommand, panel hidden.
        InteractiveOptions slide;
        slide.technique = step.technique;
        // The step alone (its views were checked above; the window checks a tour's views again).
        auto alone = std::make_shared<Tour>(Tour{tour.source, tour.title, tour.description, {step}});
        slide.tour = alone;
        slide.tourStep = 0;
        slide.showUi = false;
        slide.frames = std::max(options.frames, step.view == "error" ? 3 : 1);   // error: measured after frame 1
        pages[i].image = stepImageName(i);
        slide.screenshot = (options.outDir / pages[i].image).string();
        // A path step: window frame k shows path frame k; its first, middle and last frame are saved.
        CameraPath path;
        SceneCamera pathCamera;
        LightInfo pathLight;
        if (!step.path.empty()) {
            UiState probe;
            if (!applyTourStep(app, step, probe, error) || !probe.path) {
                error = tour.source + ": steps[" + std::to_string(i) + "] (\"" + step.title + "\"): path '" + step.path + "': " + error;
                return 2;
            }
            path = *probe.path;
            pathCamera = probe.pathCamera;
            pathLight = probe.pathLight;
            pages[i].pathFrames = path.frames;
            const int middle = path.frames / 2, lastFrame = path.frames - 1;
            pages[i].strip = {{pages[i].image, 0}, {stepImageName(i, "middle"), middle}, {stepImageName(i, "last"), lastFrame}};
            slide.frames = path.frames;
            slide.screenshotsAt = {{0, slide.screenshot}, {middle, (options.outDir / pages[i].strip[1].first).string()}};
            slide.screenshot = (options.outDir / pages[i].strip[2].first).string();   // after the last frame
        }
        if (const int code = app.runInteractive(slide); code != 0) {
            error = tour.source + ": steps[" + std::to_string(i) + "]: the slide was not written";
            return code;
        }
        // A path step is measured at its first frame (the slide left the camera at its last).
        if (!step.path.empty()) setPathFrame(app, path, 0, pathCamera, pathLight);
        for (const std::string& id : {step.technique, step.compare}) {
            if (id.empty()) continue;
            TechniqueFigures figures;
            if (!measureTechnique(app, id, options, figures, error) ||
                (!step.path.empty() && !measurePathTemporal(app, id, path, pathCamera, pathLight, options, figures, error))) {
                error = tour.source + ": steps[" + std::to_string(i) + "]: " + id + ": " + error;
                return 1;
            }
            pages[i].figures.push_back(figures);
        }
        std::printf("step %zu/%zu  %-40s", i + 1, tour.steps.size(), step.title.substr(0, 40).c_str());
        for (const TechniqueFigures& f : pages[i].figures)
            std::printf("  %s: %.3f ms%s", f.technique.c_str(), f.frameMs,
                        f.reference.empty() ? "" : (", MAE " + fixed(f.metrics.mae, 4) +
                                                    (f.translucent.comparedPixels ? ", translucent " + fixed(f.translucent.mae, 4) : ""))
                                                       .c_str());
        std::printf("\n");
        std::fflush(stdout);
    }
    std::string failures;
    const int failed = checkStepExpectations(tour, pages, failures);
    if (!writeWholeFile(options.outDir / "index.html", htmlPage(tour, pages, options), error)) return 1;
    if (!writeWholeFile(options.outDir / "README.md", markdownPage(tour, pages, options), error)) return 1;
    size_t images = 0;
    for (const StepPage& page : pages) images += std::max<size_t>(1, page.strip.size());
    logInfo("tour: " + std::to_string(tour.steps.size()) + " steps, " + std::to_string(images) + " images, index.html and "
            "README.md in " + options.outDir.string());
    if (failed > 0) {
        size_t total = 0;
        for (const TourStep& step : tour.steps) total += step.expect.size();
        error = tour.source + ": " + std::to_string(failed) + " of " + std::to_string(total) +
                " expectations failed (marked FAILED on the pages in " + options.outDir.string() + "):" + failures;
        return kExitTourExpectation;
    }
    return 0;
}

} // namespace shadowlab
