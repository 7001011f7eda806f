// The classroom window's pure parts, testable without GL or ImGui: where the panel and the view
// go in the window, how a comparison splits the view, screenshot names that never overwrite, the
// error heatmap over the dimmed lit image, and whether a measurement still matches the frame.
#pragma once

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "util/image.h"

namespace shadowlab {

// How two techniques share the view.
//   SideBySide: the view split in two halves, each showing the whole camera framing (the same
//               camera, aspect of the half), so both techniques show the same objects.
//   Wipe:       one framing; technique A left of a draggable divider, B right of it, same pixels.
//   Difference: one framing; |shadow term A - shadow term B| (see shaders/compare_difference.frag).
//   Grid:       three or four techniques (A, B and C, D) in the quarters of the view, each quarter
//               with the whole camera framing, as side by side.
enum class CompareLayout { SideBySide, Wipe, Difference, Grid };
constexpr int kMaxGridSides = 4;
const char* compareLayoutName(CompareLayout layout);
bool parseCompareLayout(const std::string& text, CompareLayout& layout);

// A rectangle in window pixels, origin top left (ImGui's convention).
struct PixelRect {
    glm::ivec2 origin{0};
    glm::ivec2 size{0};
    bool contains(glm::vec2 p) const {
        return p.x >= float(origin.x) && p.y >= float(origin.y) && p.x < float(origin.x + size.x) && p.y < float(origin.y + size.y);
    }
    bool overlaps(const PixelRect& o) const {
        return origin.x < o.origin.x + o.size.x && o.origin.x < origin.x + size.x && origin.y < o.origin.y + o.size.y &&
               o.origin.y < origin.y + size.y;
    }
};

struct ViewLayout {
    PixelRect panel;          // empty when the UI is hidden
    PixelRect view;           // the free part of the window: the scene is framed here
    PixelRect halves[2];      // where technique A and B are shown (view itself when not comparing)
    PixelRect cells[kMaxGridSides];   // where each side is shown: halves[0..1], or Grid's quarters (A B / C D)
    glm::ivec2 renderSize{0}; // size of the main targets (a half for SideBySide, a quarter for Grid)
    int wipeX = 0;            // Wipe: divider position in window pixels
    bool comparing = false;
};

// Panel width for a UI scale: wide enough for the longest parameter label at that scale, at
// most 36% of a wide window (360 px, up to 45%, in a narrow one) so the view keeps the larger part.
int panelWidthFor(float uiScale, int windowWidth);
// `wipe` is the divider's position across the view, 0..1.
ViewLayout computeViewLayout(glm::ivec2 window, bool panelVisible, int panelWidth, bool comparing, CompareLayout layout,
                             float wipe);

// The camera framing the scenes are made for (1280x720): a narrower view widens the vertical
// field of view so the same horizontal extent stays in view (CameraController::setFramingAspect).
constexpr float kSceneFramingAspect = 16.0f / 9.0f;

// screenshots/<scene>-<technique>[-vs-<other>]-YYYYMMDD-HHMMSS.png under `folder`; a name that
// exists already gets -2, -3, ... so nothing is ever overwritten.
std::filesystem::path uniqueScreenshotPath(const std::filesystem::path& folder, const std::string& scene,
                                           const std::string& technique, const std::string& other,
                                           std::chrono::system_clock::time_point when);

// The error heatmap drawn over the lit image dimmed to `dim`: where a pixel has no error (or is
// not compared) the lit scene shows through, so the geometry stays readable; false shadow in
// magenta and false light in green, stronger with the error (the hues of errorHeatmap()).
// `lit` is display-referred RGBA8 (bottom-up, as readDisplay returns it); technique and reference
// are shadow terms per pixel in the same order.
Image heatmapOverLit(const Image& lit, const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                     const std::vector<uint8_t>& mask, float dim = 0.45f);

// What a measurement depends on: when any of it changes the heatmap and the figures are stale.
struct MeasurementKey {
    std::string scene;
    std::string technique;
    std::vector<double> params;
    glm::mat4 viewProjection{1.0f};
    glm::vec3 lightDirection{0.0f};
    float lightSize = 0.0f;
    glm::ivec2 size{0};
    bool operator==(const MeasurementKey&) const = default;
};
// What changed between a measurement and now, for the stale banner ("" when nothing did).
std::string staleReason(const MeasurementKey& measured, const MeasurementKey& now);

} // namespace shadowlab
