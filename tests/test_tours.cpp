// Guided tours and saved sessions (issue 14): the built-in tours are valid against the real
// plugins; a bad tour is refused whole with the file, the step and the problem named; a step
// applied through the window's own path (App::runInteractive, the tour player's UiCommand) puts
// its scene, parameters and view on screen; a saved session is a tour step and restores the
// same frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>

#include <unistd.h>

#include "bench/accuracy_columns.h"
#include "app_paths.h"
#include "groundtruth/reference_technique.h"
#include "plugin/plugin_library.h"
#include "test_support.h"
#include "ui/session.h"
#include "ui/tour.h"
#include "ui/tour_player.h"
#include "ui/ui.h"
#include "util/paths.h"

using namespace shadowlab;
using nlohmann::json;

namespace {

std::vector<TechniqueInfo> realTechniques() {
    std::vector<TechniqueInfo> techniques = scanPlugins(pluginDir()).techniques;
    techniques.push_back(copyDescriptor(referenceDescriptor(), {}));
    return techniques;
}

json validTour() {
    return json::parse(R"({
      "title": "t",
      "steps": [
        {"title": "one", "scene": "cube", "technique": "shadowmap", "caption": "First."},
        {"title": "two", "scene": "hover", "sceneParameters": {"height": 1.2}, "technique": "pcf",
         "compare": "shadowmap", "layout": "wipe", "wipe": 0.3,
         "parameters": {"kernel": 7, "cone_bias": false, "shadowmap.depth_format": "16"},
         "camera": {"position": [0, 3, 4], "target": [0, 0.3, 0], "fov": 50},
         "light": {"direction": [0.3, -1, 0.2], "size": 2.5}, "view": "visibility", "caption": "Second."}
      ]})");
}

// The error of the tour with steps[1] patched by `patch` (merge_patch: null removes a field).
std::string errorOf(const json& patch) {
    json tour = validTour();
    tour["steps"][1].merge_patch(patch);
    Tour parsed;
    std::string error;
    if (parseTour(tour, "t.json", {}, parsed, error) && checkTour(parsed, realTechniques(), error)) return "";
    return error;
}

int countMagenta(const Texture& image) {
    int count = 0;
    for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
        count += image.rgba[i] > 150 && image.rgba[i + 1] < 110 && image.rgba[i + 2] > 150;
    return count;
}

} // namespace

TEST(Tours, EveryBuiltInTourIsValidAgainstThePluginsAndCitesItsSeeds) {
    const auto names = builtinTourNames();
    for (const char* expected : {"shadow-mapping", "soft-shadows", "large-scenes", "coloured-shadows"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << "missing tour " << expected;
    const auto techniques = realTechniques();
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        Tour tour;
        std::string error;
        ASSERT_TRUE(loadTour(name, techniques, tour, error)) << error;
        EXPECT_GE(tour.steps.size(), 5u);
        for (const TourStep& step : tour.steps) {
            // Every caption says where its formula or figure comes from.
            EXPECT_NE(step.caption.find("seed 00"), std::string::npos) << step.title << ": the caption cites no seed";
            EXPECT_GE(step.caption.size(), 150u) << step.title << ": a caption of a few sentences";
        }
    }
}

TEST(Tours, AValidTourParsesToItsFieldsAndRoundTrips) {
    Tour tour;
    std::string error;
    ASSERT_TRUE(parseTour(validTour(), "t.json", {}, tour, error)) << error;
    ASSERT_TRUE(checkTour(tour, realTechniques(), error)) << error;
    const TourStep& step = tour.steps[1];
    EXPECT_EQ(step.compare, "shadowmap");
    EXPECT_EQ(step.layout, CompareLayout::Wipe);
    EXPECT_FLOAT_EQ(step.wipe, 0.3f);
    ASSERT_EQ(step.parameters.size(), 3u);
    EXPECT_EQ(step.parameters[0], (std::pair<std::string, std::string>{"cone_bias", "false"}));
    ASSERT_TRUE(step.camera);
    EXPECT_FLOAT_EQ(step.camera->fovDegrees, 50.0f);
    EXPECT_DOUBLE_EQ(*step.light.size, 2.5);
    EXPECT_EQ(step.view, "visibility");
    // The JSON a session is saved as reads back as the same step.
    TourStep again;
    ASSERT_TRUE(parseTourStep(tourStepJson(step), "again", {}, again, error)) << error;
    EXPECT_EQ(tourStepJson(again), tourStepJson(step));
}

TEST(Tours, ABadStepIsNamedWithItsFileStepAndProblem) {
    const std::pair<json, std::string> cases[] = {
        {{{"technique", "nosuch"}}, "technique 'nosuch': no such technique"},
        {{{"compare", "nosuch"}}, "compare 'nosuch': no such technique"},
        {{{"parameters", {{"radius", 3}}}}, "pcf has no parameter 'radius'"},
        {{{"parameters", {{"kernel", 99}}}}, "out of range"},
        {{{"parameters", {{"kernel", 2.5}}}}, "not an integer"},
        {{{"parameters", {{"shadowmap.depth_format", "12"}}}}, "is not one of"},
        {{{"parameters", {{"vsm.min_variance", 0.1}}}}, "'vsm' is not this step's technique"},
        {{{"parameters", {{"kernel", {1, 2}}}}}, "expected a number, true/false or an enum label"},
        {{{"scene", "no-such-scene"}}, "scene: no-such-scene"},
        {{{"sceneParameters", {{"height", "high"}}}}, "sceneParameters.height: expected a finite number"},
        {{{"sceneParameters", {{"heigth", 1}}}}, "heigth"},
        {{{"light", {{"size", 90}}}}, "light.size"},
        {{{"light", {{"direction", {0, 0, 0}}}}}, "light.direction: zero-length direction"},
        {{{"camera", {{"position", {0, 1, 0}}, {"target", {0, 1, 0}}}}}, "camera: the target is at the camera position"},
        {{{"camera", {{"position", {0, 1, 0}}, {"target", {0, 0, 0}}, {"fov", 0}}}}, "camera.fov"},
        {{{"camera", {{"position", {0, 1e30, 0}}, {"target", {0, 0, 0}}}}}, "camera.position"},
        {{{"layout", "diagonal"}}, "layout: 'diagonal'"},
        {{{"wipe", 2}}, "wipe: expected a number from 0 to 1"},
        {{{"caption", ""}}, "caption: must not be empty"},
        {{{"caption", nullptr}}, "missing 'caption'"},
        {{{"techinque", "pcf"}}, "unknown field 'techinque'"},
    };
    for (const auto& [patch, expected] : cases) {
        SCOPED_TRACE(patch.dump());
        const std::string error = errorOf(patch);
        EXPECT_NE(error.find("t.json: steps[1]"), std::string::npos) << error;
        EXPECT_NE(error.find(expected), std::string::npos) << error;
    }
    EXPECT_EQ(errorOf(json::object()), "") << "the unpatched tour is valid";
}

TEST(Tours, BadFilesAreNamed) {
    const auto techniques = realTechniques();
    char folder[] = "/tmp/shadowlab-tours-XXXXXX";
    ASSERT_TRUE(mkdtemp(folder));
    const std::filesystem::path dir = folder;
    auto write = [&](const std::string& name, const std::string& text) {
        std::ofstream(dir / name) << text;
        return (dir / name).string();
    };
    Tour tour;
    std::string error;
    EXPECT_FALSE(loadTour(write("broken.json", "{\"title\": \"x\", \"steps\": ["), techniques, tour, error));
    EXPECT_NE(error.find("broken.json"), std::string::npos) << error;
    EXPECT_FALSE(loadTour(write("empty.json", "{\"title\": \"x\", \"steps\": []}"), techniques, tour, error));
    EXPECT_NE(error.find("empty.json: 'steps' must be a non-empty array"), std::string::npos) << error;
    EXPECT_FALSE(loadTour(write("list.json", "[1, 2]"), techniques, tour, error));
    EXPECT_NE(error.find("list.json: expected an object"), std::string::npos) << error;
    EXPECT_FALSE(loadTour("no-such-tour", techniques, tour, error));
    EXPECT_NE(error.find("no-such-tour: no such tour file"), std::string::npos) << error;
    EXPECT_NE(error.find("shadow-mapping"), std::string::npos) << "the built-in tours are listed: " << error;
    TourStep step;
    EXPECT_FALSE(loadSession(write("session.json", "{\"title\": \"s\"}"), techniques, step, error));
    EXPECT_NE(error.find("session.json: missing 'scene'"), std::string::npos) << error;
    std::filesystem::remove_all(dir);
}

// The tour player's path: runInteractive with a tour applies the step by its UiCommand before
// the first frame, and the heatmap of a step whose view is "error" shows its acne.
TEST(TourPlayer, AStepThroughTheWindowPathSetsSceneParametersAndView) {
    auto app = test::makeHeadlessApp("contact", {320, 180});
    ASSERT_TRUE(app);
    auto tour = std::make_shared<Tour>();
    std::string error;
    ASSERT_TRUE(loadTour("shadow-mapping", realTechniques(), *tour, error)) << error;
    auto stepIndex = [&](const std::string& prefix) {
        for (size_t i = 0; i < tour->steps.size(); ++i)
            if (tour->steps[i].title.rfind(prefix, 0) == 0) return int(i);
        ADD_FAILURE() << "no step " << prefix;
        return 0;
    };
    const std::string shot = "/tmp/shadowlab-tour-step-" + std::to_string(getpid()) + ".png";
    auto slide = [&](int step) {
        InteractiveOptions options;
        options.technique = "none";
        options.tour = tour;
        options.tourStep = step;
        options.frames = 3;
        options.showUi = false;
        options.screenshot = shot;
        EXPECT_EQ(app->runInteractive(options), 0);
        const Texture image = loadPngTexture(shot, 1.0f, uint64_t(64) << 20);
        std::filesystem::remove(shot);
        return image;
    };
    const Texture acne = slide(stepIndex("Shadow acne"));
    EXPECT_EQ(app->scene().name, "cube");
    const TechniqueInfo* shadowmap = app->techniques().find("shadowmap");
    ASSERT_TRUE(shadowmap);
    const auto& values = app->params().values(*shadowmap);
    EXPECT_EQ(values[size_t(shadowmap->paramIndex("constant_bias"))], 0.0);
    EXPECT_EQ(values[size_t(shadowmap->paramIndex("slope_bias"))], 0.0);
    EXPECT_EQ(values[size_t(shadowmap->paramIndex("cull"))], 0.0) << "cull none";
    EXPECT_EQ(acne.width, 320);
    const Texture biased = slide(stepIndex("Bias removes"));
    EXPECT_EQ(values[size_t(shadowmap->paramIndex("constant_bias"))], 2.0);
    // The heatmap (the step's view "error") marks acne's false shadow magenta; bias removes most.
    const int acnePixels = countMagenta(acne), biasedPixels = countMagenta(biased);
    EXPECT_GT(acnePixels, 500) << "no false shadow shown for acne";
    EXPECT_LT(biasedPixels * 4, acnePixels) << "bias should remove most of the acne";
}

TEST(TourPlayer, StepParametersStayEditableAndRestartRestoresThem) {
    auto app = test::makeHeadlessApp("cube", {160, 96});
    ASSERT_TRUE(app);
    Tour tour;
    std::string error;
    ASSERT_TRUE(parseTour(validTour(), "t.json", {}, tour, error)) << error;
    UiState state;
    ASSERT_TRUE(applyTourStep(*app, tour.steps[1], state, error)) << error;
    EXPECT_EQ(state.technique, "pcf");
    EXPECT_EQ(state.compareTechnique, "shadowmap");
    EXPECT_EQ(app->scene().name, "hover");
    EXPECT_NEAR(app->scene().parameters.at("height"), 1.2, 1e-12);
    const TechniqueInfo* pcf = app->techniques().find("pcf");
    auto kernel = [&] { return app->params().values(*pcf)[size_t(pcf->paramIndex("kernel"))]; };
    EXPECT_EQ(kernel(), 7.0);
    ASSERT_TRUE(app->params().set(*pcf, "kernel", "11", error)) << error;   // as the panel's slider does
    EXPECT_EQ(kernel(), 11.0);
    app->camera().zoom(3.0f);
    ASSERT_TRUE(applyTourStep(*app, tour.steps[1], state, error)) << error;   // "Restart step"
    EXPECT_EQ(kernel(), 7.0);
    EXPECT_NEAR(glm::distance(app->camera().pose().position, glm::vec3(0, 3, 4)), 0.0f, 1e-4f);
    EXPECT_NEAR(glm::degrees(app->light().size), 2.5f, 1e-4f);
}

// A saved session is a valid tour step, and loading it elsewhere gives the same frame.
TEST(Sessions, ASavedSessionIsATourStepAndRestoresTheSameFrame) {
    const auto techniques = realTechniques();
    auto app = test::makeHeadlessApp("contact", {160, 96});
    ASSERT_TRUE(app);
    std::string error;
    UiState state;
    state.technique = "pcf";
    state.view = {ViewSelection::Kind::Visibility, ""};
    ASSERT_TRUE(app->applyAssignments({"kernel=9", "offset_scale=1.37", "cone_bias=false"}, "pcf", error)) << error;
    app->camera().look({40.0f, -25.0f});
    app->camera().pan({15.0f, 5.0f});
    app->light().direction = glm::normalize(glm::vec3(0.4f, -1.0f, 0.25f));
    app->light().size = glm::radians(1.7f);
    const auto before = test::renderVisibility(*app, "pcf", {});

    const json saved = tourStepJson(captureSession(*app, state));
    TourStep step;
    ASSERT_TRUE(parseTourStep(json::parse(saved.dump()), "session.json", {}, step, error)) << error;
    ASSERT_TRUE(checkTourStep(step, "session.json", techniques, error)) << error;
    Tour tour;   // pasted into a tour as it is
    ASSERT_TRUE(parseTour(json{{"title", "from a session"}, {"steps", {saved}}}, "t.json", {}, tour, error)) << error;
    ASSERT_TRUE(checkTour(tour, techniques, error)) << error;

    auto other = test::makeHeadlessApp("cube", {160, 96});   // another scene, defaults everywhere
    ASSERT_TRUE(other);
    UiState restored;
    ASSERT_TRUE(applyTourStep(*other, step, restored, error)) << error;
    EXPECT_EQ(restored.technique, "pcf");
    EXPECT_EQ(restored.view.kind, ViewSelection::Kind::Visibility);
    EXPECT_EQ(other->scene().name, "contact");
    const TechniqueInfo* pcf = other->techniques().find("pcf");
    EXPECT_EQ(other->params().values(*pcf), app->params().values(*app->techniques().find("pcf")));
    EXPECT_LT(glm::distance(other->camera().pose().position, app->camera().pose().position), 1e-4f);
    EXPECT_LT(glm::distance(other->light().direction, app->light().direction), 1e-6f);
    EXPECT_NEAR(other->light().size, app->light().size, 1e-6f);
    const auto after = test::renderVisibility(*other, "pcf", {});
    ASSERT_EQ(before.size(), after.size());
    float largest = 0.0f;
    for (size_t i = 0; i < before.size(); ++i) largest = std::max(largest, glm::length(before[i] - after[i]));
    EXPECT_LT(largest, 1e-3f) << "the restored session draws a different frame";
    // Saved again, it is the same session.
    json again = tourStepJson(captureSession(*other, restored));
    for (const char* key : {"scene", "sceneParameters", "technique", "parameters", "view"})
        EXPECT_EQ(again.value(key, json()), saved.value(key, json())) << key;
    EXPECT_EQ(saved.value("scene", ""), "contact");
    EXPECT_EQ(saved["parameters"].value("kernel", 0), 9);
    EXPECT_EQ(saved["parameters"].value("offset_scale", 0.0), 1.37) << "written in full precision";
}

// --- A step that plays a camera or light path (issue 12's paths, issue 14) -------------------

namespace {

struct TempDir {
    std::filesystem::path path;
    TempDir() {
        char folder[] = "/tmp/shadowlab-tour-path-XXXXXX";
        if (mkdtemp(folder)) path = folder;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::string write(const std::string& name, const std::string& text) const {
        std::filesystem::create_directories((path / name).parent_path());
        std::ofstream(path / name) << text;
        return (path / name).string();
    }
};

// The mean absolute difference of two images, in 8-bit levels over the RGB channels.
double meanLevels(const Texture& a, const Texture& b) {
    if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return 1e9;
    double sum = 0.0;
    size_t count = 0;
    for (size_t i = 0; i < a.rgba.size(); i += 4)
        for (size_t c = 0; c < 3; ++c, ++count) sum += std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c]));
    return sum / double(count);
}

} // namespace

TEST(Tours, APathStepIsReadRelativeToItsTourCheckedAndRoundTrips) {
    TempDir dir;
    ASSERT_FALSE(dir.path.empty());
    dir.write("paths/slide.json", R"({"frames": 6, "keyframes": [
        {"time": 0, "camera": {"position": [3, 2, 4], "target": [0, 0.5, 0]}},
        {"time": 1, "camera": {"position": [1, 2, 4], "target": [-2, 0.5, 0]}}]})");
    const std::string file = dir.write("lesson.json", R"({"title": "t", "steps": [
        {"title": "dolly", "scene": "cube", "technique": "shadowmap", "parameters": {"fit": "frustum"},
         "path": "dolly", "pathFrames": 12, "caption": "c"},
        {"title": "file", "scene": "cube", "technique": "pcf", "path": "paths/slide.json", "caption": "c"}]})");
    Tour tour;
    std::string error;
    ASSERT_TRUE(loadTour(file, realTechniques(), tour, error)) << error;
    EXPECT_EQ(tour.steps[0].path, "dolly");
    EXPECT_EQ(tour.steps[0].pathFrames, 12);
    EXPECT_EQ(tour.steps[1].path, (dir.path / "paths" / "slide.json").lexically_normal().string())
        << "a path file is relative to the tour file";
    EXPECT_EQ(tour.steps[1].pathFrames, 0);
    for (const TourStep& step : tour.steps) {
        TourStep again;
        ASSERT_TRUE(parseTourStep(tourStepJson(step), "again", {}, again, error)) << error;
        EXPECT_EQ(again.path, step.path);
        EXPECT_EQ(again.pathFrames, step.pathFrames);
    }
}

TEST(Tours, ABadPathIsNamedWithItsFileStepAndPath) {
    TempDir dir;
    ASSERT_FALSE(dir.path.empty());
    const std::string lamp = dir.write("lamp.json", R"({"keyframes": [{"time": 0, "light": {"position": [0, 5, 0]}},
                                                                      {"time": 1, "light": {"position": [1, 5, 0]}}]})");
    const std::string typo = dir.write("typo.json", R"({"keyframes": [{"time": 0, "camra": {}}]})");
    const std::pair<json, std::string> cases[] = {
        {{{"path", "dolyy"}}, "path 'dolyy': not a built-in path (orbit, dolly, sweep, walk, static) nor a path file"},
        {{{"path", dir.path.string() + "/missing.json"}}, "path '" + dir.path.string() + "/missing.json': "},
        {{{"path", lamp}}, "path '" + lamp + "': moves the light by position, but scene 'hover' has a directional light"},
        {{{"path", typo}}, "camra"},
        {{{"path", "orbit"}, {"view", "error"}}, "path 'orbit': the error view"},
        {{{"path", 3}}, "path: expected a string"},
        {{{"path", ""}}, "path: must not be empty"},
        {{{"pathFrames", 12}}, "pathFrames: needs 'path'"},
        {{{"path", "dolly"}, {"pathFrames", 1}}, "pathFrames: expected a whole number from 2 to 10000"},
    };
    for (const auto& [patch, expected] : cases) {
        SCOPED_TRACE(patch.dump());
        const std::string error = errorOf(patch);
        EXPECT_NE(error.find("t.json: steps[1]"), std::string::npos) << error;
        EXPECT_NE(error.find(expected), std::string::npos) << error;
    }
    EXPECT_EQ(errorOf({{"path", "sweep"}, {"pathFrames", 8}}), "") << "a built-in path is valid";
}

// In the window, the step plays its path one path frame per frame from the step's camera: frame k
// of the step is the frame a still step with the path's camera at frame k draws; applying the
// step again (Restart step) starts the path again.
TEST(TourPlayer, APathStepPlaysItsPathFrameByFrameAndRestarts) {
    auto app = test::makeHeadlessApp("cube", {192, 108});
    ASSERT_TRUE(app);
    TempDir dir;
    ASSERT_FALSE(dir.path.empty());
    // Five frames from (3, 2, 4) to (0.6, 2, 4), eye and target together: the scene slides right.
    dir.write("slide.json", R"({"frames": 5, "keyframes": [
        {"time": 0, "camera": {"position": [3, 2, 4], "target": [0, 0.4, 0]}},
        {"time": 1, "camera": {"position": [0.6, 2, 4], "target": [-2.4, 0.4, 0]}}]})");
    const std::string file = dir.write("t.json", R"({"title": "t", "steps": [
        {"title": "moving", "scene": "cube", "technique": "shadowmap", "path": "slide.json", "caption": "c",
         "camera": {"position": [3, 2, 4], "target": [0, 0.4, 0], "fov": 45}},
        {"title": "end", "scene": "cube", "technique": "shadowmap", "caption": "c",
         "camera": {"position": [0.6, 2, 4], "target": [-2.4, 0.4, 0], "fov": 45}},
        {"title": "middle", "scene": "cube", "technique": "shadowmap", "caption": "c",
         "camera": {"position": [1.8, 2, 4], "target": [-1.2, 0.4, 0], "fov": 45}},
        {"title": "start", "scene": "cube", "technique": "shadowmap", "caption": "c",
         "camera": {"position": [3, 2, 4], "target": [0, 0.4, 0], "fov": 45}}]})");
    auto tour = std::make_shared<Tour>();
    std::string error;
    ASSERT_TRUE(loadTour(file, realTechniques(), *tour, error)) << error;
    auto shot = [&](const std::string& name) { return (dir.path / name).string(); };
    auto run = [&](int step, int frames, const std::vector<std::pair<int, std::string>>& at, const std::string& last) {
        InteractiveOptions options;
        options.technique = "shadowmap";
        options.tour = tour;
        options.tourStep = step;
        options.frames = frames;
        options.showUi = false;
        options.screenshot = shot(last);
        for (const auto& [frame, name] : at) options.screenshotsAt.emplace_back(frame, shot(name));
        EXPECT_EQ(app->runInteractive(options), 0);
    };
    auto image = [&](const std::string& name) { return loadPngTexture(shot(name), 1.0f, uint64_t(64) << 20); };
    run(0, 5, {{0, "path-0.png"}, {2, "path-2.png"}}, "path-4.png");
    EXPECT_LT(glm::distance(app->camera().pose().position, glm::vec3(0.6f, 2.0f, 4.0f)), 1e-4f)
        << "after the last frame the camera is the path's last keyframe";
    run(1, 1, {}, "end.png");
    run(2, 1, {}, "middle.png");
    run(3, 1, {}, "start.png");
    const Texture first = image("path-0.png"), middle = image("path-2.png"), last = image("path-4.png");
    ASSERT_EQ(first.width, 192);
    // The step's frames follow the path: each equals the still frame from the path's camera there...
    EXPECT_LT(meanLevels(first, image("start.png")), 0.5);
    EXPECT_LT(meanLevels(middle, image("middle.png")), 0.5);
    EXPECT_LT(meanLevels(last, image("end.png")), 0.5);
    // ...and the path really moves the view: the first and last frames differ, the middle between.
    const double travelled = meanLevels(first, last);
    EXPECT_GT(travelled, 5.0);
    EXPECT_GT(meanLevels(first, middle), 1.0);
    EXPECT_GT(meanLevels(middle, last), 1.0);

    // Restart: the step applied again starts its path from frame 0 and the step's camera.
    UiState state;
    ASSERT_TRUE(applyTourStep(*app, tour->steps[0], state, error)) << error;
    ASSERT_TRUE(state.path);
    EXPECT_EQ(state.path->frames, 5);
    state.pathFrame = 3;
    app->camera().zoom(2.0f);
    ASSERT_TRUE(applyTourStep(*app, tour->steps[0], state, error)) << error;
    EXPECT_EQ(state.pathFrame, 0);
    EXPECT_LT(glm::distance(state.pathCamera.position, glm::vec3(3.0f, 2.0f, 4.0f)), 1e-4f);
    ASSERT_TRUE(applyTourStep(*app, tour->steps[1], state, error)) << error;
    EXPECT_FALSE(state.path) << "a step without a path stops the last one";
}

// The built-in dolly moves by a fraction of the step technique's own texel (as the stress suite's
// shimmer case): twice the resolution, half the step; the steps are equal along the path.
TEST(TourPlayer, TheDollyOfAStepMovesByAQuarterOfItsMapsTexel) {
    auto app = test::makeHeadlessApp("cube", {160, 90});
    ASSERT_TRUE(app);
    auto stepOf = [&](int resolution) {
        Tour tour;
        std::string error;
        json object = json::parse(R"({"title": "t", "steps": [
            {"title": "dolly", "scene": "cube", "technique": "shadowmap", "parameters": {"fit": "frustum", "snap": false},
             "camera": {"position": [2.4, 1.6, 2.2], "target": [0.6, 0.0, -0.6]}, "path": "dolly", "pathFrames": 12,
             "caption": "c"}]})");
        object["steps"][0]["parameters"]["resolution"] = resolution;
        EXPECT_TRUE(parseTour(object, "t.json", {}, tour, error)) << error;
        EXPECT_TRUE(checkTour(tour, realTechniques(), error)) << error;
        UiState state;
        EXPECT_TRUE(applyTourStep(*app, tour.steps[0], state, error)) << error;
        if (!state.path) return 0.0f;
        EXPECT_EQ(state.path->frames, 12);
        const PathState start = samplePath(*state.path, state.path->frameTime(0));
        const PathState next = samplePath(*state.path, state.path->frameTime(1));
        const PathState end = samplePath(*state.path, state.path->frameTime(11));
        if (!start.cameraPosition || !next.cameraPosition || !end.cameraPosition) return 0.0f;
        const float step = glm::distance(*start.cameraPosition, *next.cameraPosition);
        EXPECT_NEAR(glm::distance(*start.cameraPosition, *end.cameraPosition), 11.0f * step, 1e-4f);
        return step;
    };
    const float coarse = stepOf(256), fine = stepOf(512);
    EXPECT_GT(coarse, 1e-5f);
    EXPECT_LT(coarse, 0.1f) << "a quarter texel of a 256-texel crop of the cube's view";
    EXPECT_NEAR(coarse / fine, 2.0f, 0.02f) << "the dolly's step follows the map's texel";
}

// The window checks every step's debug view when the tour is loaded, not when the step comes up.
TEST(TourPlayer, TheWindowRefusesAMissingDebugViewBeforeTheFirstStep) {
    auto app = test::makeHeadlessApp("cube", {96, 54});
    ASSERT_TRUE(app);
    auto tour = std::make_shared<Tour>();
    std::string error;
    ASSERT_TRUE(parseTour(json::parse(R"({"title": "t", "steps": [
        {"title": "fine", "scene": "cube", "technique": "shadowmap", "caption": "c"},
        {"title": "no such view", "scene": "cube", "technique": "pcf", "view": "moments", "caption": "c"}]})"),
                          "t.json", {}, *tour, error)) << error;
    ASSERT_TRUE(checkTour(*tour, realTechniques(), error)) << error;   // the view exists only once pcf draws
    EXPECT_FALSE(checkTourDebugViews(*app, *tour, error));
    EXPECT_NE(error.find("t.json: steps[1] (\"no such view\"): view 'moments': pcf has no such view"), std::string::npos)
        << error;
    TempDir dir;
    InteractiveOptions options;
    options.tour = tour;
    options.tourStep = 0;
    options.frames = 2;
    options.showUi = false;
    options.screenshot = (dir.path / "never.png").string();
    EXPECT_EQ(app->runInteractive(options), 2);
    EXPECT_FALSE(std::filesystem::exists(options.screenshot)) << "a frame was drawn before the tour was refused";
}

// The large-scenes tour's two LiSPSM views (seed 002 Figs. 8.10 and 8.11): with view and light
// perpendicular the warp puts the texels where the pixels are, so the nearest third of the view
// gets smaller texels (texel footprint m, eq. 8.1) than when the camera looks into the light, where
// no warp can help and LiSPSM is a uniform focused map again.
TEST(Tours, LargeScenesShowsLispsmsBestCaseAndTheDuellingFrusta) {
    std::string error;
    Tour tour;
    auto app = test::makeHeadlessApp("forest-002", {160, 96});
    ASSERT_TRUE(app);
    ASSERT_TRUE(loadTour("large-scenes", realTechniques(), tour, error)) << error;
    auto nearThirdM = [&](const std::string& titleStart) {
        const auto step = std::find_if(tour.steps.begin(), tour.steps.end(),
                                       [&](const TourStep& s) { return s.title.rfind(titleStart, 0) == 0; });
        EXPECT_NE(step, tour.steps.end()) << titleStart;
        if (step == tour.steps.end()) return 0.0;
        UiState state;
        EXPECT_TRUE(applyTourStep(*app, *step, state, error)) << error;
        const Evaluation e = test::evaluateTechnique(*app, "lispsm", {}, ReferenceOptions::Mode::Hard);
        std::printf("%s: median m near / mid / far third %.2f / %.2f / %.2f\n", titleStart.c_str(),
                    e.footprint.medianByViewDepth[0], e.footprint.medianByViewDepth[1], e.footprint.medianByViewDepth[2]);
        EXPECT_GT(e.footprint.measuredPixels, 1000u);
        return e.footprint.medianByViewDepth[0];
    };
    const double perpendicular = nearThirdM("LiSPSM's best case"), duelling = nearThirdM("Duelling frusta");
    EXPECT_GT(perpendicular, 0.0);
    EXPECT_LT(perpendicular * 2.0, duelling);
}

// Issue 29: a step's "expect", what its caption claims as data.
TEST(TourExpect, AStepsExpectationsParseAndRoundTrip) {
    json tour = validTour();
    tour["steps"][1]["expect"] = {{"mae", "< 0.01"},
                                  {"B.false_shadow", json::array({"< 1%", ">= 0.5 * A"})},
                                  {"frame_ms", "< 2 * previous"},
                                  {"mae_near", "> 3 * mae_far"}};
    Tour parsed;
    std::string error;
    ASSERT_TRUE(parseTour(tour, "t.json", {}, parsed, error)) << error;
    ASSERT_TRUE(checkTour(parsed, realTechniques(), error)) << error;
    const std::vector<TourExpectation>& expect = parsed.steps[1].expect;
    ASSERT_EQ(expect.size(), 5u);
    // nlohmann::json keeps keys sorted: B.false_shadow (2), frame_ms, mae, mae_near.
    EXPECT_EQ(expect[0].key, "B.false_shadow");
    EXPECT_EQ(expect[0].side, 1);
    EXPECT_TRUE(expect[0].absolute);
    EXPECT_DOUBLE_EQ(expect[0].value, 0.01) << "1% is a rate of 0.01";
    EXPECT_FALSE(expect[1].absolute);
    EXPECT_EQ(expect[1].op, TourExpectation::Op::GreaterEqual);
    EXPECT_DOUBLE_EQ(expect[1].factor, 0.5);
    EXPECT_EQ(expect[1].operandSide, 0);
    EXPECT_EQ(expect[1].operandMetric, "false_shadow");
    EXPECT_TRUE(expect[2].previous);
    EXPECT_EQ(expect[2].operandMetric, "frame_ms");
    EXPECT_EQ(expect[4].operandMetric, "mae_far");
    EXPECT_FALSE(expect[4].previous);
    // Written back (a session, a tool editing tours) it reads back the same.
    TourStep again;
    ASSERT_TRUE(parseTourStep(tourStepJson(parsed.steps[1]), "again", {}, again, error)) << error;
    EXPECT_EQ(tourStepJson(again), tourStepJson(parsed.steps[1]));
    EXPECT_EQ(tourStepJson(again)["expect"]["B.false_shadow"], json::array({"< 1%", ">= 0.5 * A"}));
}

TEST(TourExpect, ABadExpectationIsNamedWithItsFileStepAndKey) {
    const std::pair<json, std::string> cases[] = {
        {{{"expect", {{"mea", "< 0.1"}}}}, "steps[1].expect.mea: unknown metric 'mea'"},
        {{{"expect", {{"C.mae", "< 0.1"}}}}, "steps[1].expect.C.mae: unknown metric 'C.mae'"},
        {{{"expect", {{"mae", "about 0.1"}}}}, "steps[1].expect.mae: 'about 0.1': expected a comparison starting with <"},
        {{{"expect", {{"mae", "< lots"}}}}, "expect.mae: '< lots': expected a number or [factor *]"},
        {{{"expect", {{"mae", "< previous.C"}}}}, "expect.mae: '< previous.C': expected a number or"},
        {{{"expect", {{"mae", "< -2 * B"}}}}, "the factor before '*' must be a positive number"},
        {{{"expect", {{"mae", "< mae"}}}}, "compares mae with itself"},
        {{{"expect", {{"mae", "< 5%"}}}}, "'%' is for rates"},
        {{{"expect", {{"frame_ms", "< 10"}}}}, "expect.frame_ms: '< 10': frame_ms depends on the machine or the image size"},
        {{{"expect", {{"footprint_near", "< 1"}}}}, "footprint_near depends on the machine or the image size"},
        {{{"expect", {{"flicker", "< 0.1"}}}}, "expect.flicker: flicker is measured along the step's path"},
        {{{"expect", {{"mae", "< previous.flicker"}}}}, "flicker is measured along the step's path"},
        {{{"expect", {{"mae", 0.1}}}}, "expect.mae: expected a comparison (\"< 0.01\") or an array of them"},
        {{{"expect", {{"mae", json::array()}}}}, "expect.mae: expected a comparison"},
        {{{"expect", {{"mae", json::array({"< 0.1", 3})}}}}, "expect.mae: '': expected a comparison"},
        {{{"expect", json::object()}}, "steps[1].expect: expected a non-empty object"},
        {{{"expect", "< 0.1"}}, "steps[1].expect: expected a non-empty object"},
        {{{"expect", {{"mae", "< previous.B"}}}}, "steps[1].expect.mae: '< previous.B': compares with previous.B, and the previous step has no 'compare'"},
        {{{"compare", nullptr}, {"layout", nullptr}, {"parameters", {{"shadowmap.depth_format", nullptr}}},
          {"expect", {{"B.mae", "< 0.1"}}}},
         "expect.B.mae: B is the compared technique and this step has no 'compare'"},
        {{{"compare", nullptr}, {"layout", nullptr}, {"parameters", {{"shadowmap.depth_format", nullptr}}},
          {"expect", {{"mae", "< B"}}}},
         "expect.mae: '< B': B is the compared technique"},
        {{{"compare", "reference"}, {"parameters", {{"shadowmap.depth_format", nullptr}}}, {"expect", {{"B.mae", "< 0.1"}}}},
         "expect.B.mae: reference is the ground truth itself; it has no mae"},
    };
    for (const auto& [patch, expected] : cases) {
        SCOPED_TRACE(patch.dump());
        const std::string error = errorOf(patch);
        EXPECT_NE(error.find("t.json: steps[1]"), std::string::npos) << error;
        EXPECT_NE(error.find(expected), std::string::npos) << error;
    }
    // "previous" on the first step, and in a session (one step: nothing before it).
    json tour = validTour();
    tour["steps"][0]["expect"] = {{"mae", "< previous"}};
    Tour parsed;
    std::string error;
    EXPECT_FALSE(parseTour(tour, "t.json", {}, parsed, error));
    EXPECT_NE(error.find("t.json: steps[0].expect.mae: '< previous': compares with the previous step, and this is the first"), std::string::npos)
        << error;
    TourStep step;
    EXPECT_FALSE(parseSessionText(tour["steps"][0].dump(), "s.json", {}, realTechniques(), step, error));
    EXPECT_NE(error.find("s.json.expect.mae: '< previous': compares with the previous step, and a session is one step"), std::string::npos) << error;
}

TEST(TourExpect, ExpectationsAreJudgedOnTheMeasuredFigures) {
    json tour = validTour();
    tour["steps"][1]["expect"] = {{"mae", json::array({"< 0.01", "> previous"})},
                                  {"B.mae", "< 0.5 * A"},
                                  {"false_shadow", "< 1%"},
                                  {"translucent_mae", "< 0.1"},
                                  {"B.penumbra", "> previous.A.penumbra"}};
    Tour parsed;
    std::string error;
    ASSERT_TRUE(parseTour(tour, "t.json", {}, parsed, error)) << error;
    TourStepFigures previous, now;
    previous.side[0] = {{"mae", 0.002}, {"penumbra", 0.05}};
    now.side[0] = {{"mae", 0.004}, {"false_shadow", 0.02}};
    now.side[1] = {{"mae", 0.003}, {"penumbra", 0.01}};
    const auto results = evaluateTourExpectations(parsed.steps[1].expect, now, &previous);
    ASSERT_EQ(results.size(), 6u);
    std::map<std::string, const TourExpectResult*> byText;
    for (const auto& r : results) byText[r.expectation->key + " " + r.expectation->text] = &r;
    EXPECT_TRUE(byText["mae < 0.01"]->passed);
    EXPECT_TRUE(byText["mae > previous"]->passed);
    EXPECT_DOUBLE_EQ(byText["mae > previous"]->against, 0.002);
    // 0.003 is not below half of A's 0.004: the deliberately wrong claim fails, its figures named.
    const TourExpectResult& half = *byText["B.mae < 0.5 * A"];
    EXPECT_FALSE(half.passed);
    EXPECT_DOUBLE_EQ(half.against, 0.002);
    EXPECT_EQ(tourExpectLine(half), "B.mae < 0.5 * A: measured 0.0030, bound 0.0020 (0.500 * A.mae 0.0040)");
    EXPECT_FALSE(byText["false_shadow < 1%"]->passed);
    EXPECT_NE(byText["false_shadow < 1%"]->detail.find("measured 2.00%"), std::string::npos) << "rates in percent, as the page";
    // Nothing measured (no translucent receiver in view) is a failure, not a pass.
    EXPECT_FALSE(byText["translucent_mae < 0.1"]->passed);
    EXPECT_NE(byText["translucent_mae < 0.1"]->detail.find("not measured"), std::string::npos);
    EXPECT_FALSE(byText["B.penumbra > previous.A.penumbra"]->passed) << "B's 0.01 against the previous step's A 0.05";
    // Without a previous step's figures a relative expectation cannot pass either.
    const auto alone = evaluateTourExpectations(parsed.steps[1].expect, now, nullptr);
    for (const auto& r : alone)
        if (r.expectation->previous) {
            EXPECT_FALSE(r.passed) << r.detail;
        }
}

// The window's default reference and the tour pages' are one rule (issue 29).
TEST(TourExpect, TheWindowAndTheToursJudgeATechniqueAgainstTheSameReference) {
    const auto techniques = realTechniques();
    std::map<std::string, ReferenceOptions::Mode> seen;
    for (const TechniqueInfo& info : techniques) seen[info.id] = ownReferenceMode(info);
    EXPECT_EQ(seen.at("shadowmap"), ReferenceOptions::Mode::Hard);
    EXPECT_EQ(seen.at("shadow-volumes"), ReferenceOptions::Mode::Hard);
    for (const char* soft : {"pcf", "pcss", "vsm", "adaptive-pcf", "raytraced"}) EXPECT_EQ(seen.at(soft), ReferenceOptions::Mode::Soft) << soft;
    for (const TechniqueInfo& info : techniques) {
        const bool hard = info.category == "hard" || info.category == "baseline";
        EXPECT_EQ(seen.at(info.id) == ReferenceOptions::Mode::Hard, hard) << info.id << " (" << info.category << ")";
    }
    // The window starts on that rule (0: each technique's own), unless --measure-reference says hard or soft.
    EXPECT_EQ(UiState{}.referenceMode, 0);
    EXPECT_EQ(InteractiveOptions{}.referenceMode, 0);
}

// Issue 29: a session saved while a path plays keeps the path: the saved step is the path's start
// (camera and light) and the path itself, so loading it plays the same frames again rather than
// freezing the frame it was saved on.
TEST(Sessions, ASessionSavedOnAPathKeepsItsPath) {
    auto app = test::makeHeadlessApp("cube", {160, 96});
    ASSERT_TRUE(app);
    std::string error;
    TourStep start;
    start.title = "orbiting";
    start.scene = "cube";
    start.technique = "shadowmap";
    start.path = "orbit";
    start.pathFrames = 24;
    start.camera = TourCamera{{3.0f, 2.0f, 4.0f}, {0.0f, 0.4f, 0.0f}, 45.0};
    start.caption = "c";
    UiState state;
    ASSERT_TRUE(applyTourStep(*app, start, state, error)) << error;
    ASSERT_TRUE(state.path.has_value());
    setPathFrame(*app, *state.path, 7, state.pathCamera, state.pathLight);   // the window on frame 8
    const SceneCamera onFrame7 = app->camera().pose();
    ASSERT_GT(glm::distance(onFrame7.position, start.camera->position), 0.1f);

    const json saved = tourStepJson(captureSession(*app, state));
    EXPECT_EQ(saved.value("path", ""), "orbit");
    EXPECT_EQ(saved.value("pathFrames", 0), 24);
    TourStep step;
    ASSERT_TRUE(parseTourStep(json::parse(saved.dump()), "session.json", {}, step, error)) << error;
    ASSERT_TRUE(checkTourStep(step, "session.json", realTechniques(), error)) << error;
    ASSERT_TRUE(step.camera.has_value());
    EXPECT_LT(glm::distance(step.camera->position, start.camera->position), 1e-4f) << "saved the path's start, not frame 8";

    auto other = test::makeHeadlessApp("spheres", {160, 96});
    ASSERT_TRUE(other);
    UiState restored;
    ASSERT_TRUE(applyTourStep(*other, step, restored, error)) << error;
    ASSERT_TRUE(restored.path.has_value()) << "the restored session lost its path";
    EXPECT_EQ(restored.path->frames, 24);
    setPathFrame(*other, *restored.path, 7, restored.pathCamera, restored.pathLight);
    EXPECT_LT(glm::distance(other->camera().pose().position, onFrame7.position), 1e-3f) << "frame 8 of the restored path differs";
}
