// The classroom panel (Dear ImGui): technique picker, the parameter panel generated from the
// technique's descriptor, light and camera controls, per-pass GPU timings, memory, debug images,
// screenshots and the log, including hot-reload errors.
#pragma once

#include <string>

#include "app.h"

struct GLFWwindow;

namespace shadowlab {

struct UiState {
    std::string technique;
    std::string compareTechnique;     // non-empty: side by side, `technique` left, this one right
    ViewSelection view;
    int msaaSamples = 0;
    float scroll = 0.0f;              // mouse wheel since last frame
    bool screenshotRequested = false;
    bool quitRequested = false;
    bool measureRequested = false;  // measure accuracy on this frame (button or smoke test)
    std::string frameError;
    int screenshotCounter = 0;
    std::string nextScreenshotName();

    // Accuracy measured on demand ("Measure accuracy"), and every measurement of this session for
    // the error-against-milliseconds plot.
    int referenceMode = 0;            // 0 hard, 1 soft
    int referenceSamples = 64;
    int referenceModel = 0;           // 0 physical, 1 the technique's own translucency model
    std::string accuracyText;
    Image heatmap;                    // shown by the ErrorHeatmap view while the size matches
    bool heatmapUploaded = false;     // in the display texture already (uploaded once, not per frame)
    struct MeasuredPoint {
        std::string label;
        double gpuMs;
        double mae;
    };
    std::vector<MeasuredPoint> measured;
};

class Ui {
public:
    bool init(GLFWwindow* window);
    void shutdown();
    // Builds and renders the UI over the current framebuffer.
    void draw(App& app, UiState& state, float frameSeconds);
    bool wantsMouse() const;
    bool wantsKeyboard() const;

private:
    bool initialised_ = false;
    GLFWwindow* window_ = nullptr;
    float smoothedFrameMs_ = 0.0f;
    std::string sceneInput_;
    std::string sceneError_;
};

} // namespace shadowlab
