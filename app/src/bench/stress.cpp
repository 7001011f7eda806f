// The failure suite (see stress.h).
#include "bench/stress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>

#include <glm/gtc/constants.hpp>
#include <nlohmann/json.hpp>

#include "app.h"
#include "bench/bench.h"
#include "bench/bench_spec.h"
#include "bench/path_run.h"
#include "render/light_space.h"
#include "shadowlab/kit/focus.h"
#include "util/log.h"
#include "util/progress.h"
#include "util/paths.h"
#include "util/stats.h"
#include "util/strings.h"
#include "util/text_file.h"

namespace shadowlab {

namespace {

using nlohmann::json;

constexpr double kDegrees = glm::pi<double>() / 180.0;

std::filesystem::path sharedAssetPath(const std::string& name) {
    constexpr std::string_view assets = "@assets/";
    if (!name.starts_with(assets)) return name;
    const char* dir = std::getenv("SHADOWLAB_ASSETS_DIR");
    const std::filesystem::path root = dir && *dir ? std::filesystem::path(dir)
                                                   : std::filesystem::path(SHADOWLAB_SOURCE_DIR) / ".." / "shared" / "assets";
    return (root / name.substr(assets.size())).lexically_normal();
}

std::string sceneArgument(const StressSuite& suite, const StressCase& c) {
    if (!c.scene.ends_with(".json")) return c.scene;
    return (std::filesystem::path(suite.file).parent_path() / c.scene).lexically_normal().string();
}

bool isTemporal(StressMetric m) { return m == StressMetric::Flicker || m == StressMetric::Popping || m == StressMetric::Noise; }


// The temporal error image of one frame: grey where the technique changed as the truth did,
// magenta where it darkened more (or brightened less), green the other way (errorHeatmap's colours).
Image temporalImage(const TemporalChanges& changes, const std::vector<uint8_t>& region, int width, int height) {
    std::vector<glm::vec3> technique(changes.valid.size()), reference(changes.valid.size());
    std::vector<uint8_t> mask(changes.valid.size());
    for (size_t i = 0; i < changes.valid.size(); ++i) {
        technique[i] = glm::vec3(0.5f + changes.deltaTechnique[i]);
        reference[i] = glm::vec3(0.5f + changes.deltaReference[i]);
        mask[i] = changes.valid[i] && region[i];
    }
    const auto rgb = errorHeatmap(technique, reference, mask, width, height);
    Image image{width, height, 4, std::vector<uint8_t>(size_t(width) * size_t(height) * 4, 255)};
    for (size_t i = 0; i < size_t(width) * size_t(height); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i * 4 + size_t(c)] = rgb[i * 3 + size_t(c)];
    return image;
}

// Applies `text` (key=value) to `technique` when it declares the key; a key naming another
// technique ("pcf.kernel=3") applies only to that one.
bool applyWhereDeclared(App& app, const TechniqueInfo& info, const std::string& text, std::string& error) {
    const auto assignment = parseAssignment(text, error);
    if (!assignment) return false;
    if (assignment->technique == hostParams().id) {
        // host.* (contact shadows, the eye-space blur, ...): for every technique alike.
        if (!app.params().set(hostParams(), assignment->param, assignment->value, error)) {
            error = "--set " + text + ": " + error;
            return false;
        }
        return true;
    }
    if (!assignment->technique.empty() && assignment->technique != info.id) return true;
    if (!info.findParam(assignment->param)) return true;
    if (!app.params().set(info, assignment->param, assignment->value, error)) {
        error = "--set " + text + ": " + error;
        return false;
    }
    return true;
}

std::string settingsOf(App& app, const TechniqueInfo& info) {
    std::string text;
    const auto& values = app.params().values(info);
    for (size_t i = 0; i < info.params.size(); ++i) {
        const ParamSpec& p = info.params[i];
        if (values[i] == p.defaultValue) continue;
        if (!text.empty()) text += " ";
        text += p.id + "=" + formatParamValue(p, values[i]);
    }
    return text;
}

// The technique's settings that differ from its defaults, then the host's (host.contact_shadows=...).
std::string cellSettings(App& app, const TechniqueInfo& info) {
    std::string text = settingsOf(app, info);
    std::istringstream host(settingsOf(app, hostParams()));
    std::string item;
    while (host >> item) text += (text.empty() ? "host." : " host.") + item;
    return text;
}

// The texel footprint m over the pixels of `region` the measure served: its median, and the median
// over the nearest third of the visible depth range (nearest to farthest compared pixel of the
// region, as regionMetrics' thirds), so it describes the same pixels as mae_near_third.
struct FootprintSummary {
    double median = 0.0, nearThird = 0.0;
    size_t pixels = 0;
};
FootprintSummary footprintOver(const Evaluation& e, const std::vector<uint8_t>& region, const CameraInfo& camera) {
    FootprintSummary out;
    if (e.footprint.m.size() != e.mask.size()) return out;
    std::vector<double> depths(e.mask.size(), -1.0);
    double nearest = camera.farPlane, farthest = camera.nearPlane;
    for (size_t i = 0; i < e.mask.size(); ++i) {
        if (!e.mask[i] || (i < region.size() && !region[i])) continue;
        depths[i] = -(camera.view * glm::vec4(glm::vec3(e.positions[i]), 1.0f)).z;
        nearest = std::min(nearest, depths[i]);
        farthest = std::max(farthest, depths[i]);
    }
    std::vector<double> all, nearThird;
    const double nearEnd = nearest + (farthest - nearest) / 3.0;
    for (size_t i = 0; i < depths.size(); ++i) {
        if (depths[i] < 0.0 || !(e.footprint.m[i] > 0.0f)) continue;
        all.push_back(e.footprint.m[i]);
        if (depths[i] < nearEnd) nearThird.push_back(e.footprint.m[i]);
    }
    out.pixels = all.size();
    if (!all.empty()) out.median = percentile(all, 0.5);
    if (!nearThird.empty()) out.nearThird = percentile(nearThird, 0.5);
    return out;
}

} // namespace

std::filesystem::path defaultStressCases() { return dataRoot() / "assets" / "stress" / "cases.json"; }

// The pixels a case counts (its region: an object's bounds or a sphere), or none for all of them.
static bool caseRegion(const StressSuite& suite, const StressCase& c, const Scene& loaded,
                       std::function<std::vector<uint8_t>(const Evaluation&)>& region, std::string& error) {
    if (!c.regionObject.empty() || c.regionCentre) {
        Bounds object{};
        if (!c.regionObject.empty()) {
            bool found = false;
            for (size_t i = 0; i < loaded.objects.size(); ++i)
                if (loaded.objects[i].name == c.regionObject) {
                    object = found ? Bounds{glm::min(object.min, loaded.objectInfo[i].bounds.min), glm::max(object.max, loaded.objectInfo[i].bounds.max)}
                                   : loaded.objectInfo[i].bounds;
                    found = true;
                }
            if (!found) {
                error = suite.file + ": case " + c.id + ": region.object: scene '" + loaded.name + "' has no object '" + c.regionObject + "'";
                return false;
            }
            object.min.y += 0.02f * (object.max.y - object.min.y);
        }
        region = [&c, object](const Evaluation& e) {
            std::vector<uint8_t> inside(e.mask.size(), 0);
            for (size_t i = 0; i < inside.size(); ++i) {
                const glm::vec3 p(e.positions[i]);
                if (e.positions[i].w < 0.5f) continue;
                inside[i] = c.regionCentre ? glm::length(p - *c.regionCentre) <= c.regionRadius
                                           : glm::all(glm::greaterThanEqual(p, object.min)) && glm::all(glm::lessThanEqual(p, object.max));
            }
            return inside;
        };
    }
    return true;
}

// The cell's figures from a measured path: spatial ones from its worst frame, temporal ones from
// its summary, and the case's metric among them.
static void foldPathResult(const StressCase& c, const PathAccuracy& result, StressCell& cell) {
    for (const PathFrameResult& frame : result.frames) {
        cell.mae = std::max(cell.mae, frame.metrics.mae);
        cell.falseShadow = std::max(cell.falseShadow, frame.metrics.falseShadowRate);
        cell.falseLight = std::max(cell.falseLight, frame.metrics.falseLightRate);
        cell.maeNear = std::max(cell.maeNear, frame.metrics.maeByViewDepth[0]);
        cell.maeFar = std::max(cell.maeFar, frame.metrics.maeByViewDepth[2]);
        cell.contactFalseLight = std::max(cell.contactFalseLight, frame.metrics.contactFalseLightRate);
        cell.contactBandPixels = std::max(cell.contactBandPixels, frame.metrics.contactBandPixels);
        cell.pixels = std::max(cell.pixels, frame.metrics.comparedPixels);
    }
    cell.flicker = result.temporal.meanFlicker;
    cell.popping = result.temporal.popping;
    cell.noise = result.temporal.meanNoise;
    switch (c.metric) {
    case StressMetric::FalseShadow: cell.value = cell.falseShadow; break;
    case StressMetric::FalseLight: cell.value = cell.falseLight; break;
    case StressMetric::Mae: cell.value = cell.mae; break;
    case StressMetric::MaeNearThird: cell.value = cell.maeNear; break;
    case StressMetric::MaeFarThird: cell.value = cell.maeFar; break;
    case StressMetric::Flicker: cell.value = cell.flicker; break;
    case StressMetric::Popping:
        cell.value = cell.popping;
        if (result.temporal.poppingFrame >= 0) cell.worstFrame = result.temporal.poppingFrame;
        break;
    case StressMetric::Noise: cell.value = cell.noise; break;
    case StressMetric::ContactFalseLight: cell.value = cell.contactFalseLight; break;
    }
}

static bool runStressCellWithHost(App& app, const StressSuite& suite, const StressCase& c, const std::string& technique,
                                  const StressOptions& options, StressCell& cell, std::string& error);

bool runStressCell(App& app, const StressSuite& suite, const StressCase& c, const std::string& technique,
                   const StressOptions& options, StressCell& cell, std::string& error) {
    // A case's host.* settings (contact shadows, ...) hold for its cells only.
    const std::vector<double> savedHost = app.hostValues();
    const bool ran = runStressCellWithHost(app, suite, c, technique, options, cell, error);
    app.params().values(hostParams()) = savedHost;
    return ran;
}

static bool runStressCellWithHost(App& app, const StressSuite& suite, const StressCase& c, const std::string& technique,
                                  const StressOptions& options, StressCell& cell, std::string& error) {
    cell = {};
    cell.technique = technique;
    cell.caseId = c.id;
    cell.expectedFail = std::find(c.expectedToFail.begin(), c.expectedToFail.end(), technique) != c.expectedToFail.end();
    cell.expectedPass = std::find(c.expectedToPass.begin(), c.expectedToPass.end(), technique) != c.expectedToPass.end();
    if (c.requires_ && !std::filesystem::exists(sharedAssetPath(*c.requires_))) {
        cell.skipped = true;
        cell.skipReason = sharedAssetPath(*c.requires_).string() + " is not there";
        return true;
    }
    const TechniqueInfo* info = app.techniques().find(technique);
    if (!info) {
        error = "--techniques: no technique '" + technique + "'";
        return false;
    }
    // The scene, loaded only when it changes (the reference's BVH is built once per scene).
    const std::string scene = sceneArgument(suite, c);
    const std::string source = scene.ends_with(".json") ? scene : "builtin:" + scene;
    if (app.scene().source != source && !app.loadScene(scene, {}, error)) {
        error = suite.file + ": case " + c.id + ": " + error;
        return false;
    }
    const glm::ivec2 size = options.size.value_or(suite.size);
    if (app.renderer().size() != size && !app.setRenderSize(size, error)) return false;

    SceneCamera camera = app.scene().camera;
    if (c.cameraPosition) camera.position = *c.cameraPosition;
    if (c.cameraTarget) camera.target = *c.cameraTarget;
    if (c.cameraNear) camera.nearPlane = *c.cameraNear;
    if (c.cameraFar) camera.farPlane = *c.cameraFar;
    LightInfo light = app.scene().light;
    if (c.lightAngles) {
        const double e = c.lightAngles->x * kDegrees, a = c.lightAngles->y * kDegrees;
        light.direction = -glm::vec3(float(std::cos(e) * std::cos(a)), float(std::sin(e)), float(std::cos(e) * std::sin(a)));
    }
    if (c.lightSize) light.size = float(*c.lightSize * kDegrees);

    app.params().resetToDefaults(*info);
    for (const std::string& text : c.sets)
        if (!applyWhereDeclared(app, *info, text, error)) return false;
    for (const std::string& text : options.sets)
        if (!applyWhereDeclared(app, *info, text, error)) return false;
    if (info->category == "reference" && info->paramIndex("mode") >= 0 && info->paramIndex("samples") >= 0) {
        // The ray-traced reference shows the trace the case compares with (area-reference, also
        // in the category, is a technique of its own and keeps its parameters).
        if (!app.params().set(*info, "mode", c.reference == ReferenceOptions::Mode::Hard ? "0" : "1", error) ||
            !app.params().set(*info, "samples", std::to_string(c.referenceSamples), error))
            return false;
    }
    cell.settings = cellSettings(app, *info);

    // The path; the dolly moves by a fraction of this technique's own map texel (its fit, crop and
    // resolution at the first frame; 2048 texels over the scene fit without a map).
    CameraPath path;
    BuiltinPathOptions pathOptions;
    pathOptions.frames = c.frames;
    pathOptions.texelsPerFrame = c.texelsPerFrame;
    pathOptions.texelWorldSize = techniqueTexelWorldSize(app, *info, camera, light, size);
    pathOptions.camera = camera;   // the built-in paths start from the case's view and light
    pathOptions.light = light;
    if (!builtinPath(c.path.empty() ? "static" : c.path, app.scene(), pathOptions, path, error)) return false;
    if (c.path.empty()) path.frames = 1;

    PathAccuracyOptions accuracy;
    accuracy.reference.mode = c.reference;
    accuracy.reference.samplesPerPixel = c.referenceSamples;
    accuracy.reference.adaptive = true;
    accuracy.reference.model = TranslucencyModel::Physical;
    if (!caseRegion(suite, c, app.scene(), accuracy.region, error)) return false;
    Image worst;
    double worstValue = -1.0;
    auto spatialValue = [&](const AccuracyMetrics& m) {
        switch (c.metric) {
        case StressMetric::FalseShadow: return m.falseShadowRate;
        case StressMetric::FalseLight: return m.falseLightRate;
        case StressMetric::MaeNearThird: return m.maeByViewDepth[0];
        case StressMetric::MaeFarThird: return m.maeByViewDepth[2];
        case StressMetric::ContactFalseLight: return m.contactFalseLightRate;
        default: return m.mae;
        }
    };
    const bool wantImage = !options.outDir.empty();
    accuracy.onFrame = [&](const PathFrameResult& frame, const Evaluation& e, const TemporalChanges* changes) {
        // The footprint of the worst frame for m (the largest median): a still case has one frame.
        const FootprintSummary footprint =
            footprintOver(e, accuracy.region ? accuracy.region(e) : std::vector<uint8_t>(e.mask.size(), 1), app.lastFrame().camera);
        if (footprint.pixels > 0 && footprint.median > cell.footprintMedian) {
            cell.footprintMedian = footprint.median;
            cell.footprintNear = footprint.nearThird;
            cell.footprintPixels = footprint.pixels;
        }
        const double value = isTemporal(c.metric) ? (changes ? frame.temporal.flicker : -1.0) : spatialValue(frame.metrics);
        if (value > worstValue) {
            worstValue = value;
            cell.worstFrame = frame.frame;
            if (wantImage) {
                const std::vector<uint8_t> region = accuracy.region ? accuracy.region(e) : std::vector<uint8_t>(e.mask.size(), 1);
                if (changes) {
                    worst = temporalImage(*changes, region, e.width, e.height);
                } else {
                    Evaluation masked = e;
                    for (size_t i = 0; i < masked.mask.size(); ++i) masked.mask[i] = masked.mask[i] && region[i];
                    worst = masked.heatmap();
                }
            }
        }
    };
    PathAccuracy result;
    if (!measurePath(app, technique, path, camera, light, accuracy, result, error)) return false;

    foldPathResult(c, result, cell);
    cell.pass = cell.value <= c.threshold;
    if (wantImage && !worst.pixels.empty()) {
        cell.image = "images/" + technique + "-" + c.id + ".png";
        if (!writePng(options.outDir / cell.image, worst, error)) return false;
    }
    return true;
}

// The suite's Markdown page: the table of verdicts against the literature's claims, the cases and
// the worst frames.
static std::string stressPage(App& app, const StressSuite& suite, const StressOptions& options,
                              const std::vector<const StressCase*>& cases, const std::vector<std::string>& techniques,
                              const std::vector<StressCell>& cells, bool chart) {
    const json environment = benchEnvironment(app);
    std::ostringstream page;
    page << "# shadowlab stress: where shadow techniques fail\n\n"
         << "- renderer: " << environment.value("gpu", "") << " (" << environment.value("backend", "") << ")\n"
         << "- commit: " << environment.value("commit", "") << ", date: " << environment.value("date", "") << "\n"
         << "- cases: " << suite.file << ", " << size_t(options.size.value_or(suite.size).x) << "x"
         << size_t(options.size.value_or(suite.size).y) << "\n\n"
         << "Each cell is the case's metric for the technique with its defaults plus the case's settings, and the "
            "verdict against the case's threshold (pass: at most the threshold). A mark after the verdict says "
            "whether the measurement agrees with the literature's claim for that technique (the claims are below): "
            "`(as claimed)` when the technique does what the claim says (a technique it names as failing fails, one it "
            "names as doing better passes, or the reference passes), `(claim: fails)` when a technique named as failing "
            "passes, `(claim: passes)` when one named as doing better fails; no mark where the claim names no verdict. Spatial metrics are the worst frame of the case; temporal ones the mean over "
            "its path (docs/stability.md).\n\n";
    if (chart) page << "![verdicts](stress.png)\n\n";
    // A case with "footprint" gets a column of the texel footprint m beside it (median / nearest third).
    page << "| technique |";
    size_t columns = 0;
    for (const StressCase* c : cases) {
        page << " " << c->id << " |";
        if (c->footprint) page << " " << c->id << ": m median / near third |";
        columns += c->footprint ? 2 : 1;
    }
    page << "\n|---|";
    for (size_t i = 0; i < columns; ++i) page << "---:|";
    page << "\n";
    for (const std::string& technique : techniques) {
        page << "| " << technique << " |";
        for (const StressCase* c : cases) {
            const auto cell = std::find_if(cells.begin(), cells.end(),
                                           [&](const StressCell& s) { return s.technique == technique && s.caseId == c->id; });
            if (cell->skipped) {
                page << (c->footprint ? " skipped | - |" : " skipped |");
                continue;
            }
            std::string mark;
            const bool reference = app.techniques().find(technique)->category == "reference";
            if (cell->expectedFail) mark = cell->pass ? " (claim: fails)" : " (as claimed)";
            else if (cell->expectedPass) mark = cell->pass ? " (as claimed)" : " (claim: passes)";
            else if (reference && cell->pass) mark = " (as claimed)";
            page << " " << (cell->image.empty() ? fixed(cell->value, 4) : "[" + fixed(cell->value, 4) + "](" + cell->image + ")")
                 << " " << (cell->pass ? "pass" : "**fail**") << mark << " |";
            if (c->footprint)
                page << " " << (cell->footprintPixels ? fixed(cell->footprintMedian, 2) + " / " + fixed(cell->footprintNear, 2) : "-") << " |";
        }
        page << "\n";
    }
    page << "\n## The cases\n\n| case | what | metric | threshold | the literature's claim | source |\n|---|---|---|---:|---|---|\n";
    for (const StressCase* c : cases) {
        page << "| " << c->id << " | " << c->title << " (`" << c->scene << "`" << (c->path.empty() ? "" : ", path `" + c->path + "`, " + std::to_string(c->frames) + " frames")
             << ") | " << stressMetricName(c->metric) << " | " << c->threshold << " | " << c->claim << " | " << c->source << " |\n";
    }
    page << "\n## Worst frames\n\nThe error image of each cell's worst frame (spatial: magenta false shadow, green false light; "
            "temporal: the change of the technique against the change of the reference, same colours).\n\n";
    for (const StressCell& cell : cells)
        if (!cell.image.empty()) page << "![" << cell.technique << " " << cell.caseId << "](" << cell.image << ")\n";
    return page.str();
}

int checkStressRequest(const std::vector<TechniqueInfo>& found, const StressSuite& suite, const StressOptions& options,
                       std::vector<std::string>& techniques, std::vector<const StressCase*>& cases, std::string& error) {
    const auto find = [&found](const std::string& id) -> const TechniqueInfo* {
        const auto it = std::find_if(found.begin(), found.end(), [&id](const TechniqueInfo& info) { return info.id == id; });
        return it == found.end() ? nullptr : &*it;
    };
    techniques = options.techniques;
    if (techniques.empty())
        for (const auto& info : found) techniques.push_back(info.id);
    std::string available;
    for (const auto& info : found) appendListItem(available, info.id);
    for (const std::string& id : techniques) {
        if (find(id)) continue;
        error = "--techniques: no technique '" + id + "' (available: " + available + ")";
        return 2;
    }
    cases.clear();
    for (const StressCase& c : suite.cases)
        if (options.cases.empty() || std::find(options.cases.begin(), options.cases.end(), c.id) != options.cases.end()) cases.push_back(&c);
    for (const std::string& id : options.cases) {
        if (std::none_of(suite.cases.begin(), suite.cases.end(), [&](const StressCase& c) { return c.id == id; })) {
            std::string list;
            for (const StressCase& c : suite.cases) appendListItem(list, c.id);
            error = "--cases: no case '" + id + "' in " + suite.file + " (cases: " + list + ")";
            return 2;
        }
    }
    // Each case's scene, and its camera as the case composes it with the scene's (a position
    // alone may land on the scene's target): the check scenes, tours and paths make.
    for (const StressCase* c : cases) {
        if (c->requires_ && !std::filesystem::exists(sharedAssetPath(*c->requires_))) continue;   // skipped at run time
        SceneCheck scene;
        try {
            scene = checkScene(sceneArgument(suite, *c));
        } catch (const SceneError& e) {
            error = suite.file + ": case " + c->id + ": scene: " + e.what();
            return 2;
        }
        const glm::dvec3 position(c->cameraPosition.value_or(scene.camera.position));
        const glm::dvec3 target(c->cameraTarget.value_or(scene.camera.target));
        if (const std::string problem = cameraProblem(position, target, glm::dvec3(scene.camera.up)); !problem.empty()) {
            error = suite.file + ": case " + c->id + ": camera (with the " + (c->cameraPosition ? "target" : "position") +
                    " of scene '" + scene.name + "'): " + problem;
            return 2;
        }
    }
    // Checked on values of their own; each cell applies them (applyWhereDeclared).
    ParamStore values;
    for (const std::string& text : options.sets) {
        const auto assignment = parseAssignment(text, error);
        if (!assignment) return 2;
        if (assignment->technique == hostParams().id) {
            if (!values.set(hostParams(), assignment->param, assignment->value, error)) {
                error = "--set " + text + ": " + error;
                return 2;
            }
            continue;
        }
        // A key naming its technique goes to it; a bare key to each technique that declares it
        // (applyWhereDeclared), so at least one must.
        bool declared = false;
        for (const std::string& id : assignment->technique.empty() ? techniques : std::vector<std::string>{assignment->technique}) {
            const TechniqueInfo* info = find(id);
            if (!info) {
                error = "--set " + text + ": no technique '" + id + "' (available: " + available + ")";
                return 2;
            }
            if (assignment->technique.empty() && !info->findParam(assignment->param)) continue;
            declared = true;
            if (!values.set(*info, assignment->param, assignment->value, error)) {
                error = "--set " + text + ": " + id + ": " + error;
                return 2;
            }
        }
        if (!declared) {
            std::string measured;
            for (const std::string& id : techniques) appendListItem(measured, id);
            error = "--set " + text + ": '" + assignment->param + "' is no parameter of the techniques measured (" + measured + ")";
            return 2;
        }
    }
    return 0;
}

// A cell as a row of results.json / results.csv.
static json stressRow(const StressCase& c, const std::string& technique, const StressCell& cell) {
    json row = {{"case", c.id}, {"technique", technique}, {"scene", c.scene}, {"metric", stressMetricName(c.metric)},
                {"threshold", c.threshold}, {"skipped", cell.skipped}, {"settings", cell.settings},
                {"expected_to_fail", cell.expectedFail}, {"expected_to_pass", cell.expectedPass}};
    if (cell.skipped) {
        row["skip_reason"] = cell.skipReason;
        return row;
    }
    row.update({{"value", cell.value}, {"pass", cell.pass}, {"worst_frame", cell.worstFrame}, {"image", cell.image},
                {"mae", cell.mae}, {"false_shadow", cell.falseShadow}, {"false_light", cell.falseLight},
                {"mae_near_third", cell.maeNear}, {"mae_far_third", cell.maeFar}, {"flicker", cell.flicker},
                {"popping", cell.popping}, {"noise", cell.noise}, {"pixels", cell.pixels},
                {"contact_false_light", cell.contactFalseLight}, {"contact_band_pixels", cell.contactBandPixels},
                {"frames", c.path.empty() ? 1 : c.frames}});
    // Whether the verdict agrees with the claim: only where the claim names the technique.
    if (cell.expectedFail || cell.expectedPass) row["agrees_with_literature"] = cell.expectedFail != cell.pass;
    // m only where the technique reported its maps (none, planar and the references have none).
    if (cell.footprintPixels > 0)
        row.update({{"footprint_median", cell.footprintMedian}, {"footprint_near_third", cell.footprintNear},
                    {"footprint_pixels", cell.footprintPixels}});
    return row;
}

int runStress(App& app, const StressSuite& suite, const StressOptions& options, std::vector<StressCell>& cells,
              std::string& error) {
    std::vector<std::string> techniques;
    std::vector<const StressCase*> cases;
    if (const int code = checkStressRequest(app.techniques().techniques(), suite, options, techniques, cases, error)) return code;
    if (!options.outDir.empty()) {
        std::error_code ec;
        std::filesystem::create_directories(options.outDir / "images", ec);
        if (ec) {
            error = options.outDir.string() + ": cannot create the folder (" + ec.message() + ")";
            return 1;
        }
    }
    const auto start = std::chrono::steady_clock::now();
    const size_t total = cases.size() * techniques.size();
    cells.clear();
    std::vector<json> rows;
    for (const StressCase* c : cases) {
        for (const std::string& technique : techniques) {
            StressCell cell;
            if (!runStressCell(app, suite, *c, technique, options, cell, error)) {
                if (!interrupted()) return 2;
                // Ctrl-C: the cells done are the results (no chart or page for a partial table).
                if (!options.outDir.empty() && (!writeBenchResults(options.outDir / "results.json", rows, error) ||
                                                !writeBenchResults(options.outDir / "results.csv", rows, error)))
                    return 1;
                error = "interrupted (Ctrl-C): " + std::to_string(cells.size()) + " of " + std::to_string(total) + " cells" +
                        (options.outDir.empty() ? std::string() : " written to " + (options.outDir / "results.json").string());
                return kExitInterrupted;
            }
            cells.push_back(cell);
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            const double left = elapsed / double(cells.size()) * double(total - cells.size());
            if (!options.quiet)
                std::fprintf(stderr, "stress: %zu of %zu  %-22s %-20s %s  (%s elapsed, about %s left)\n", cells.size(), total,
                             c->id.c_str(), technique.c_str(),
                             cell.skipped ? ("skipped: " + cell.skipReason).c_str()
                                          : (std::string(stressMetricName(c->metric)) + " " + fixed(cell.value, 4) + " " +
                                             (cell.pass ? "pass" : "FAIL")).c_str(),
                             durationText(elapsed).c_str(), durationText(left).c_str());
            rows.push_back(stressRow(*c, technique, cell));
        }
    }
    if (options.outDir.empty()) return 0;

    const std::filesystem::path dir = options.outDir;
    if (!writeBenchResults(dir / "results.json", rows, error) || !writeBenchResults(dir / "results.csv", rows, error)) return 1;
    // The chart: tools/stress_chart.py (matplotlib, with the system interpreter).
    const auto script = dataRoot() / "tools" / "stress_chart.py";
    const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    const std::string command = python + " " + shellQuote(script.string()) + " " + shellQuote((dir / "results.json").string()) +
                                " --out " + shellQuote(dir.string()) + " > /dev/null";
    const bool chart = std::system(command.c_str()) == 0;
    if (!chart) logWarning("stress chart: " + command + " failed (is python3-matplotlib installed?)");

    const std::string page = stressPage(app, suite, options, cases, techniques, cells, chart);
    if (!writeWholeFile(dir / "README.md", page, error)) return 1;
    std::printf("stress: %zu cells (%zu cases x %zu techniques) in %.0f s, written to %s\n", cells.size(), cases.size(),
                techniques.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                dir.string().c_str());
    return 0;
}

} // namespace shadowlab
