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

// The current state as a step: scene and its parameters, technique (and B) with every parameter
// value, camera, light, layout and view. applyTourStep of it restores the same frame.
TourStep captureSession(App& app, const UiState& state);

// The view a step names ("lit", "visibility", "error", or a debug image) and back.
ViewSelection viewFromStepName(const std::string& name);
std::string stepViewName(const ViewSelection& view);

} // namespace shadowlab
