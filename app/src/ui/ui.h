// The classroom panel (Dear ImGui): technique picker, the parameter panel generated from the
// technique's descriptor, light and camera controls, per-pass GPU timings, memory, debug images,
// screenshots and the log, including hot-reload errors. The panel only edits state and emits
// commands; the session (session.cpp) runs them between frames.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app.h"
#include "ui/classroom.h"
#include "ui/imgui_gl.h"
#include "ui/session.h"
#include "ui/tour.h"

struct GLFWwindow;

namespace shadowlab {

// Work the panel asks for that must not run inside the ImGui frame (ray tracing, read-backs,
// scene loads): queued in UiState::commands, run by the session after the frame is drawn.
// Tours and sessions go through the same queue: the window's buttons and keys, --tour and
// --session at the start, and the headless `tour` command (one step per run) all apply a step
// with the same command.
struct UiCommand {
    enum class Kind { Measure, CancelMeasure, Screenshot, LoadScene, TourStep, LoadTour, SaveSession, LoadSession, PlayPath, ExportPath } kind;
    // LoadScene, LoadTour, LoadSession: name or path; SaveSession: path ("" = a new name under
    // the session folder); TourStep: "next", "previous", "restart" or a step index from 0;
    // PlayPath: a built-in path or a path file, from the camera and light on screen ("" stops it).
    std::string argument;
};

struct UiState {
    std::string technique;
    std::string compareTechnique;     // non-empty: `technique` is A (left), this one B (right)
    std::vector<std::string> gridTechniques;   // Grid: C and D (one or two) beside A and B
    CompareLayout compareLayout = CompareLayout::SideBySide;
    float wipe = 0.5f;                // Wipe: divider across the view, 0..1 (dragged in the view)
    bool draggingWipe = false;
    ViewSelection view;
    int msaaSamples = 0;
    float scroll = 0.0f;              // mouse wheel since last frame
    std::vector<int> pressedKeys;     // GLFW keys pressed since last frame
    glm::vec2 eventCursor{0.0f};      // the cursor as of the last event read
    std::vector<glm::vec2> leftPresses;   // where the left button went down since last frame
    std::optional<glm::vec2> leftRelease; // where it went up since last frame
    bool quitRequested = false;
    bool showUi = true;               // F1 or H toggles; false: nothing over the view but labels
    float uiScale = 1.0f;             // fonts and sizes (a projector wants 1.5 to 2)
    // Presenter mode (P, --presenter): full screen, the panel hidden, the step's caption large
    // on the view with its figures beside it. `showHelp`: the overlay of every key (`?`).
    bool presenter = false;
    bool showHelp = false;
    ViewLayout layout;                // this frame's (the session computes it before the panel)
    std::string frameError;
    std::vector<UiCommand> commands;
    std::string lastScreenshot;       // path of the last F12 screenshot, or its error
    std::string sceneError;           // of the last LoadScene command

    // The guided tour being played (none: no tour player), its step, and what the last tour or
    // session command said.
    std::shared_ptr<const Tour> tour;
    int tourStep = 0;
    std::string tourStatus;
    bool tourStatusIsError = false;
    std::string sessionStatus;
    bool sessionStatusIsError = false;
    // The shown step's camera and light path (a step with "path"): one path frame per window
    // frame from `pathCamera` and `pathLight` (the step's), looping; restarting the step starts
    // it again. Paused, the camera is the user's again.
    // Outside tours the panel's "Paths" section plays one the same way. `pathName` and
    // `pathFrames` are what the step (or the panel) asked for, so a saved session keeps them;
    // `pathSpeed` path frames per window frame (the fraction accumulates in `pathClock`).
    std::optional<CameraPath> path;
    std::string pathName;
    int pathFrames = 0;
    SceneCamera pathCamera;
    LightInfo pathLight;
    int pathFrame = 0;
    float pathSpeed = 1.0f;
    float pathClock = 0.0f;
    bool pathPlaying = true;
    std::string pathStatus;           // what the panel's last PlayPath said (an error names the path)

    // Accuracy measured on demand ("Measure accuracy"): one result per side of the view, and
    // every measurement of this session for the error-against-milliseconds plot.
    // 0: each side's technique's own reference (ownReferenceMode: hard for hard techniques, soft for
    // filtered and soft ones, as the tour pages measure), 1: hard, 2: soft.
    int referenceMode = 0;
    int referenceSamples = 64;
    int referenceModel = 0;           // 0 physical, 1 each side's technique's own translucency model
    std::vector<SideMeasurement> measurement;
    std::string measureError;
    // A measurement running on its worker (ui/async_measurement.h): the frame loop goes on; the
    // panel shows how far it is and offers Cancel. The result replaces `measurement` when done.
    bool measuring = false;
    float measureProgress = 0.0f;     // 0..1
    std::string measureStage;         // what it is doing ("tracing the reference, image 1 of 2")
    std::string staleReason;          // why the shown measurement no longer matches the view ("" = current)
    std::map<std::string, double> sideTimings[kMaxGridSides];   // GPU ms per pass of each side's latest frame
    struct MeasuredPoint {
        std::string label;
        double gpuMs;
        double mae;
    };
    std::vector<MeasuredPoint> measured;
};

// The techniques on screen, in the order of their cells: A; A and B when comparing; A, B, C (and
// D) in the grid layout.
std::vector<std::string> shownTechniques(const UiState& state);

// Presenter mode on or off: on hides the panel (and the help overlay); off shows it again.
void setPresenter(UiState& state, bool on);

class Ui {
public:
    // window = nullptr: offscreen (no platform input; the display size comes with each draw).
    bool init(GLFWwindow* window, float uiScale);
    void shutdown();
    // Builds and renders the UI into `framebuffer` (0 = the window) of size `display`.
    void draw(App& app, UiState& state, float frameSeconds, GLuint framebuffer, glm::ivec2 display);
    bool wantsMouse() const;
    bool wantsKeyboard() const;
    // Whether `p` (window pixels) grabs the wipe's divider: the frame loop asks before it moves
    // the camera, the overlay before it starts a drag, so a drag of the handle never orbits.
    bool onWipeHandle(const UiState& state, glm::vec2 p) const;

private:
    void applyScale(float scale);
    void drawViewOverlay(App& app, UiState& state);
    void drawPanel(App& app, UiState& state);
    void drawComparePicker(App& app, UiState& state);
    // Sections of the panel (ui.cpp).
    void drawViewSection(App& app, UiState& state);
    void drawAccuracySection(App& app, UiState& state);
    void drawLightSection(App& app);
    void drawTimingSection(App& app, UiState& state);
    void drawReloadSection(App& app);
    void drawHostSection(App& app);
    void drawStatusLine(App& app, const UiState& state, bool overlay);
    void drawPresenterOverlay(App& app, const UiState& state);   // presenter.cpp
    void drawHelpOverlay(const UiState& state);                   // presenter.cpp
    void drawViewLegend(App& app, const UiState& state);          // view_legends.cpp
    void drawKernelInset(App& app, const UiState& state, glm::ivec2 probe, bool top);
    void drawPathSection(App& app, UiState& state);               // tour_panel.cpp
    void drawTourPlayer(App& app, UiState& state);   // tour_panel.cpp
    void drawLessonSection(App& app, UiState& state); // tour_panel.cpp
    bool initialised_ = false;
    GLFWwindow* window_ = nullptr;
    ImGuiGlRenderer renderer_;
    ImFont* largeFont_ = nullptr;     // presenter captions (null: the panel's font, scaled)
    int scrolledToStep_ = -1;         // the tour step the panel last scrolled back to
    const Tour* scrolledTour_ = nullptr;
    std::string pathChoice_ = "orbit";
    glm::vec2 initialCursor_{0.0f};
    float appliedScale_ = 0.0f;
    float smoothedFrameMs_ = 0.0f;
    std::string sceneInput_;
    std::string tourInput_;
    std::string sessionInput_;
    std::string newestLogLine_;       // the log follows new lines
    float scaleSlider_ = 1.0f;
    std::string reloadStatus_;        // the latest hot-reload line of the log
    bool reloadStatusIsError_ = false;
    double reloadStatusSeconds_ = -1e9;   // ImGui time it appeared
};

} // namespace shadowlab
