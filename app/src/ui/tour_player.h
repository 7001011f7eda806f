// Tours and sessions on the running app: applying a step (scene, parameters, camera, light,
// view) and capturing the current state as a step (a saved session). The window's tour player,
// `--session`, the UI's "Load session" and the headless `tour` command all go through these, as
// UiCommands run by the session between frames (session.cpp).
#pragma once

#include <string>

#include "app.h"
#include "ui/tour.h"
#include "ui/ui.h"

namespace shadowlab {

// Puts `step` on screen: loads its scene with its parameters, resets the step's techniques to
// their defaults and sets the step's values (still editable afterwards), places camera and light
// (the scene's where the step gives none), and sets technique, comparison and view in `state`.
// The view "error" queues a measurement (run after the next frame, at the view's size).
bool applyTourStep(App& app, const TourStep& step, UiState& state, std::string& error);

// A technique's debug images exist only once it has drawn a frame (plugins register them when
// they create them): one frame of each technique a step's debug view names, so a view the
// technique does not have is refused when the tour is loaded, before any step is shown (the
// window's --tour and "Load tour", and `tour --out`). The error names the file, step and view.
bool checkTourDebugViews(App& app, const Tour& tour, std::string& error);
// The same check for one step (a session file has one), `where` naming the file and step: a
// session is checked as a tour's step is (App::viewProblem, the check of `render --view` too).
bool checkStepView(App& app, const TourStep& step, const std::string& where, std::string& error);

// The step's path (step.path: a built-in path or a path file) for the app's scene, made from
// `camera` and `light` (the step's, placed by applyTourStep), with step.pathFrames frames when
// set. The dolly moves by a fraction of the step technique's own map texel (its fit, snap and
// resolution as set now), as the stress suite's shimmer case. Errors name the path.
bool resolveTourPath(App& app, const TourStep& step, const SceneCamera& camera, const LightInfo& light, CameraPath& path,
                     std::string& error);

// The current state as a step: scene and its parameters, technique (and B) with every parameter
// value, camera, light, layout and view. applyTourStep of it restores the same frame.
TourStep captureSession(App& app, const UiState& state);

// The view a step names ("lit", "visibility", "error", or a debug image) and back.
ViewSelection viewFromStepName(const std::string& name);
std::string stepViewName(const ViewSelection& view);

} // namespace shadowlab
