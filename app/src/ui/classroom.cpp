// The classroom window's pure parts (see classroom.h).
#include "ui/classroom.h"

#include <algorithm>
#include <cmath>
#include <cctype>
#include <ctime>
#include <system_error>

namespace shadowlab {

const char* compareLayoutName(CompareLayout layout) {
    switch (layout) {
    case CompareLayout::SideBySide: return "side-by-side";
    case CompareLayout::Wipe: return "wipe";
    case CompareLayout::Difference: return "difference";
    case CompareLayout::Grid: return "grid";
    }
    return "?";
}

bool parseCompareLayout(const std::string& text, CompareLayout& layout) {
    for (CompareLayout l : {CompareLayout::SideBySide, CompareLayout::Wipe, CompareLayout::Difference, CompareLayout::Grid})
        if (text == compareLayoutName(l)) {
            layout = l;
            return true;
        }
    return false;
}

int panelWidthFor(float uiScale, int windowWidth) {
    // 360 px holds the longest label on one line beside nothing (labels sit above their widgets).
    const int wanted = int(std::lround(360.0f * std::clamp(uiScale, 0.5f, 4.0f)));
    // A large UI scale on a projector's 1280 px would take 45% (576 px at scale 2): the panel
    // stops at 36% of a wide window, labels wrap, and the view keeps two thirds. Narrow windows
    // keep 360 px up to 45%, since below that the parameter labels no longer fit.
    const double share = std::min(0.45 * windowWidth, std::max(360.0, 0.36 * windowWidth));
    return std::clamp(wanted, 1, std::max(1, int(std::floor(share))));
}

ViewLayout computeViewLayout(glm::ivec2 window, bool panelVisible, int panelWidth, bool comparing, CompareLayout layout,
                             float wipe) {
    ViewLayout out;
    window = glm::max(window, glm::ivec2(1));
    const int panel = panelVisible ? std::clamp(panelWidth, 0, window.x - 1) : 0;
    out.panel = {{0, 0}, {panel, panelVisible ? window.y : 0}};
    out.view = {{panel, 0}, {window.x - panel, window.y}};
    out.comparing = comparing;
    out.halves[0] = out.halves[1] = out.view;
    for (PixelRect& cell : out.cells) cell = out.view;
    out.renderSize = out.view.size;
    out.wipeX = out.view.origin.x + int(std::lround(std::clamp(wipe, 0.0f, 1.0f) * float(out.view.size.x)));
    if (!comparing) return out;
    if (layout == CompareLayout::Grid) {
        // Quarters of one size (a pixel row or column may stay unused), A B over C D.
        out.renderSize = glm::max(out.view.size / 2, glm::ivec2(1));
        for (int i = 0; i < kMaxGridSides; ++i)
            out.cells[i] = {out.view.origin + glm::ivec2(i % 2, i / 2) * out.renderSize, out.renderSize};
        out.halves[0] = out.cells[0];
        out.halves[1] = out.cells[1];
        return out;
    }
    if (layout == CompareLayout::SideBySide) {
        const int left = std::max(1, out.view.size.x / 2);
        out.halves[0] = {out.view.origin, {left, out.view.size.y}};
        out.halves[1] = {{out.view.origin.x + left, 0}, {std::max(1, out.view.size.x - left), out.view.size.y}};
        out.renderSize = out.halves[1].size;   // both halves render at this size (one pixel column may stay unused)
        out.halves[0].size = out.renderSize;
    } else if (layout == CompareLayout::Wipe) {
        out.halves[0] = {out.view.origin, {out.wipeX - out.view.origin.x, out.view.size.y}};
        out.halves[1] = {{out.wipeX, 0}, {out.view.origin.x + out.view.size.x - out.wipeX, out.view.size.y}};
    }
    out.cells[0] = out.halves[0];
    out.cells[1] = out.halves[1];
    return out;
}

namespace {

std::string fileSafe(const std::string& text) {
    std::string out;
    for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
    return out.empty() ? "unnamed" : out;
}

} // namespace

std::filesystem::path uniqueScreenshotPath(const std::filesystem::path& folder, const std::string& scene,
                                           const std::string& technique, const std::string& other,
                                           std::chrono::system_clock::time_point when) {
    const std::time_t t = std::chrono::system_clock::to_time_t(when);
    std::tm local{};
    localtime_r(&t, &local);
    char stamp[32];
    std::strftime(stamp, sizeof(stamp), "%Y%m%d-%H%M%S", &local);
    std::string base = fileSafe(scene) + "-" + fileSafe(technique);
    if (!other.empty()) base += "-vs-" + fileSafe(other);
    base += std::string("-") + stamp;
    std::error_code ec;
    std::filesystem::path path = folder / (base + ".png");
    for (int n = 2; std::filesystem::exists(path, ec); ++n) path = folder / (base + "-" + std::to_string(n) + ".png");
    return path;
}

Image heatmapOverLit(const Image& lit, const std::vector<glm::vec3>& technique, const std::vector<glm::vec3>& reference,
                     const std::vector<uint8_t>& mask, float dim) {
    Image out{lit.width, lit.height, 4, std::vector<uint8_t>(size_t(lit.width) * size_t(lit.height) * 4, 255)};
    const size_t pixels = size_t(lit.width) * size_t(lit.height);
    if (lit.channels != 4 || lit.pixels.size() < pixels * 4 || technique.size() < pixels || reference.size() < pixels ||
        mask.size() < pixels)
        return out;
    const glm::vec3 falseShadowHue(255.0f, 0.0f, 255.0f), falseLightHue(0.0f, 255.0f, 0.0f);
    auto scalar = [](glm::vec3 v) { return (v.r + v.g + v.b) / 3.0f; };
    for (size_t i = 0; i < pixels; ++i) {
        const glm::vec3 base = glm::vec3(lit.pixels[i * 4], lit.pixels[i * 4 + 1], lit.pixels[i * 4 + 2]) * dim;
        glm::vec3 colour = base;
        if (mask[i]) {
            const float error = std::clamp(scalar(technique[i]), 0.0f, 1.0f) - std::clamp(scalar(reference[i]), 0.0f, 1.0f);
            // sqrt: small errors (a pixel of acne, 5% of a penumbra) still show.
            const float a = std::sqrt(std::min(std::abs(error), 1.0f));
            colour = glm::mix(base, error < 0.0f ? falseShadowHue : falseLightHue, a);
        }
        for (int c = 0; c < 3; ++c) out.pixels[i * 4 + size_t(c)] = uint8_t(std::lround(std::clamp(colour[c], 0.0f, 255.0f)));
    }
    return out;
}

std::string staleReason(const MeasurementKey& measured, const MeasurementKey& now) {
    if (measured.scene != now.scene) return "the scene changed";
    if (measured.technique != now.technique) return "the technique changed";
    if (measured.size != now.size) return "the view changed size";
    if (measured.viewProjection != now.viewProjection) return "the camera moved";
    if (measured.lightDirection != now.lightDirection || measured.lightSize != now.lightSize) return "the light changed";
    if (measured.params != now.params) return "a parameter changed";
    return "";
}

} // namespace shadowlab
