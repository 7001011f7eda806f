// Legends drawn on the debug views (issue 29), so a student can read them without the source:
// the footprint's log2 colour scale, the colour of each map in the coverage view, what the texel
// grid's two line colours mean, the difference view's colour key, and a focus-body view without
// a focus body saying so. Drawn with the view's other overlays (Ui::drawViewOverlay), so they are
// in screenshots, slides and `render --view` images alike. The colours mirror
// shaders/shadow_map_view.frag and shaders/compare_difference.frag.
#include <algorithm>
#include <cmath>
#include <string>

#include <imgui.h>

#include "ui/ui.h"

namespace shadowlab {
namespace {

// Legend text is light grey, not white: white is the focus body's colour, which tests count.
constexpr ImU32 kLegendText = IM_COL32(225, 225, 225, 255);
constexpr ImU32 kLegendBox = IM_COL32(0, 0, 0, 200);

ImU32 legendColour(float r, float g, float b) { return IM_COL32(int(r * 255.0f), int(g * 255.0f), int(b * 255.0f), 255); }

// shadow_map_view.frag's kMapColours.
constexpr float kLegendMapColours[8][3] = {{0.9f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.2f}, {0.25f, 0.4f, 1.0f}, {0.95f, 0.8f, 0.1f},
                                           {0.8f, 0.3f, 0.9f}, {0.1f, 0.85f, 0.85f}, {1.0f, 0.55f, 0.1f}, {0.6f, 0.6f, 0.6f}};

// The footprint's colour at log2 m = t * 4 (shadow_map_view.frag, mode 0).
ImU32 footprintColour(float t) {
    const float low[3] = {40, 80, 230}, unit[3] = {120, 190, 120}, high[3] = {230, 40, 30};
    const float* end = t < 0.0f ? low : high;
    const float a = std::min(std::abs(t), 1.0f);
    return IM_COL32(int(unit[0] + (end[0] - unit[0]) * a), int(unit[1] + (end[1] - unit[1]) * a),
                    int(unit[2] + (end[2] - unit[2]) * a), 255);
}

// A legend's rows: a swatch (or none) and its text.
struct LegendRow {
    ImU32 swatch;
    bool hasSwatch;
    std::string text;
};

// A box in the view's top right corner: the title, an optional colour bar, then the rows.
void drawLegendBox(const PixelRect& view, const std::string& title, const std::vector<LegendRow>& rows, bool footprintBar) {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float font = ImGui::GetFontSize(), pad = 0.5f * font, swatch = font;
    float width = ImGui::CalcTextSize(title.c_str()).x;
    for (const LegendRow& row : rows) width = std::max(width, ImGui::CalcTextSize(row.text.c_str()).x + (row.hasSwatch ? swatch + pad : 0.0f));
    const float barWidth = 14.0f * font, barHeight = font;
    if (footprintBar) width = std::max(width, barWidth);
    float height = font * (1.0f + float(rows.size())) + pad * float(rows.size()) * 0.3f + (footprintBar ? barHeight + 1.4f * font : 0.0f);
    const float right = float(view.origin.x + view.size.x) - 8.0f, top = float(view.origin.y) + 8.0f;
    const ImVec2 min(right - width - 2.0f * pad, top);
    draw->AddRectFilled(min, ImVec2(right, top + height + 2.0f * pad), kLegendBox, pad);
    float y = top + pad;
    draw->AddText(ImVec2(min.x + pad, y), kLegendText, title.c_str());
    y += font * 1.15f;
    if (footprintBar) {
        // log2 m from -4 to 4, the shader's clamp: 1/16 .. 16 pixels per texel.
        const int steps = 32;
        for (int i = 0; i < steps; ++i) {
            const float x0 = min.x + pad + barWidth * float(i) / float(steps), x1 = min.x + pad + barWidth * float(i + 1) / float(steps);
            draw->AddRectFilled(ImVec2(x0, y), ImVec2(x1 + 0.5f, y + barHeight), footprintColour(-1.0f + 2.0f * (float(i) + 0.5f) / float(steps)));
        }
        const char* ticks[5] = {"1/16", "1/4", "1", "4", "16"};
        for (int i = 0; i < 5; ++i) {
            const float x = min.x + pad + barWidth * float(i) / 4.0f;
            draw->AddLine(ImVec2(x, y + barHeight), ImVec2(x, y + barHeight + 0.3f * font), kLegendText);
            const float w = ImGui::CalcTextSize(ticks[i]).x;
            draw->AddText(ImVec2(std::clamp(x - 0.5f * w, min.x + pad, min.x + pad + barWidth - w), y + barHeight + 0.3f * font), kLegendText,
                          ticks[i]);
        }
        y += barHeight + 1.4f * font;
    }
    for (const LegendRow& row : rows) {
        float x = min.x + pad;
        if (row.hasSwatch) {
            draw->AddRectFilled(ImVec2(x, y + 0.1f * font), ImVec2(x + swatch, y + 0.9f * font), row.swatch);
            draw->AddRect(ImVec2(x, y + 0.1f * font), ImVec2(x + swatch, y + 0.9f * font), IM_COL32(150, 150, 150, 255));   // dark swatches too
            x += swatch + pad;
        }
        draw->AddText(ImVec2(x, y), kLegendText, row.text.c_str());
        y += font + 0.3f * pad;
    }
}

} // namespace

void Ui::drawViewLegend(App& app, const UiState& state) {
    const PixelRect& view = state.layout.view;
    const bool comparing = state.layout.comparing;
    if (comparing && state.compareLayout == CompareLayout::Difference) {
        drawLegendBox(view, "difference |A - B| of the shadow terms",
                      {{IM_COL32(255, 140, 0, 255), true, "A darker than B"},
                       {IM_COL32(51, 140, 255, 255), true, "B darker than A"},
                       {0, false, "brighter: a larger difference"}},
                      false);
        return;
    }
    std::string error;
    LoadedTechnique* loaded = app.techniques().get(state.technique, error);
    const size_t maps = loaded ? loaded->host().shadowMaps().size() : 0;
    switch (state.view.kind) {
    case ViewSelection::Kind::Footprint:
        drawLegendBox(view, "texel footprint m: pixels per texel (log2)",
                      {{0, false, "red: texels larger than pixels (blocky edges)"},
                       {0, false, "green: one texel a pixel; blue: texels wasted"},
                       {IM_COL32(24, 24, 24, 255), true, "no map serves the pixel"}},
                      true);
        return;
    case ViewSelection::Kind::TexelGrid:
        drawLegendBox(view, "shadow-map texel grid",
                      {{IM_COL32(255, 217, 26, 255), true, "every texel edge"},
                       {IM_COL32(26, 217, 255, 255), true, "every n-th edge (n = 2, 4, 8 ...) where"},
                       {0, false, "edges would be under 8 pixels apart"}},
                      false);
        return;
    case ViewSelection::Kind::MapCoverage: {
        std::vector<LegendRow> rows;
        const auto& info = loaded ? loaded->host().shadowMaps() : std::vector<ShadowMapInfo>{};
        for (size_t i = 0; i < maps; ++i)
            rows.push_back({legendColour(kLegendMapColours[i % 8][0], kLegendMapColours[i % 8][1], kLegendMapColours[i % 8][2]), true,
                            "map " + std::to_string(i + 1) + ": " + std::to_string(info[i].size.x) + " x " + std::to_string(info[i].size.y) +
                                " texels" + (maps > 1 && i == 0 ? " (nearest)" : "")});
        if (rows.empty()) rows.push_back({0, false, "this technique reports no shadow map"});
        rows.push_back({IM_COL32(60, 60, 60, 255), true, "no map serves the pixel"});
        drawLegendBox(view, "which map serves each pixel, and each map's volume", rows, false);
        return;
    }
    case ViewSelection::Kind::FocusBody: {
        bool reported = false;
        if (loaded)
            for (const auto& edges : loaded->host().focusBodyEdges()) reported |= !edges.empty();
        std::vector<LegendRow> rows{{IM_COL32(255, 255, 255, 255), true, "edges of the focus body B (seed 002 eq. 4.2)"},
                                    {legendColour(0.9f, 0.2f, 0.2f), true, "the map's volume"}};
        if (!reported) rows.push_back({IM_COL32(255, 190, 60, 255), true, "no B here: set fit = focus-body"});
        drawLegendBox(view, reported ? "focus body B" : "focus body B: not computed (fit is not focus-body)", rows, false);
        return;
    }
    case ViewSelection::Kind::DebugImage:
        if (loaded)
            for (const DebugImage& image : loaded->host().debugImages())
                if (image.name == state.view.debugImage && image.kind == DebugImageKind::Depth)
                    drawLegendBox(view, "'" + image.name + "': depth seen from the light",
                                  {{IM_COL32(0, 0, 0, 255), true, "the nearest depth the map holds"},
                                   {IM_COL32(255, 255, 255, 255), true, "the farthest (and nothing stored)"},
                                   {0, false, "the map at its own aspect ratio"}},
                                  false);
        return;
    default: return;
    }
}

} // namespace shadowlab
