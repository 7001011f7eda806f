// The report's pages (see report_page.h).
#include "bench/report_page.h"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>

#include "bench/tour_pages.h"
#include "util/strings.h"

namespace shadowlab {
namespace {

// The results table's columns, and what each means (both pages define every column).
const std::vector<std::string> kResultColumns = {"scene", "technique", "parameters", "size", "frame ms", "passes ms",
                                           "shadow term ms", "GPU MiB", "MAE hard", "false shadow hard",
                                           "false light hard", "MAE soft", "false shadow soft", "false light soft",
                                           "pre-pass"};

struct Definition {
    std::vector<std::string> names;
    std::string text;   // Markdown inline: `code` only
};

const std::vector<Definition>& columnDefinitions() {
    static const std::vector<Definition> definitions = {
        {{"scene", "technique"}, "the built-in scene and the technique's id."},
        {{"parameters"},
         "only those the sweep changes for that technique (every other parameter has its default, or the spec's base "
         "value listed above the table); all of them are in results.csv."},
        {{"size"}, "the output size in pixels."},
        {{"frame ms"}, "GPU time of a whole timed frame."},
        {{"passes ms"}, "the technique's own passes (shadow maps, filtering, the camera pre-pass it asks for)."},
        {{"shadow term ms"},
         "the technique's main pass minus `none`'s main pass, same view, same run: the cost of its shadow lookup."},
        {{"GPU MiB"}, "the technique's own GPU memory (its maps and scratch textures), not the host's targets."},
        {{"MAE hard", "MAE soft"},
         "mean absolute error of the shadow term against the ray-traced reference, on compared pixels (lit side, in "
         "the light's cone), against the hard reference (one ray to the light's centre) and the soft one (rays over "
         "the light's area). Hard techniques are measured against the hard reference, filtered and soft ones against "
         "both."},
        {{"false shadow hard", "false shadow soft"},
         "share of compared pixels the reference lights (>= 0.5) that the technique shadows (< 0.5): acne, "
         "over-darkening."},
        {{"false light hard", "false light soft"},
         "share of compared pixels the reference shadows that the technique lights: leaks, peter panning, light "
         "bleeding."},
        {{"pre-pass"},
         "the host depth pre-pass: its setting (`auto`, `on`, `off`) and whether the timed frames ran it (`auto` "
         "decides from the frame's depth complexity, docs/benchmarks.md \"Depth pre-pass\")."},
        {{"floors"},
         "`none`'s main pass (no shadow lookup) and the bare depth pass at the technique's resolution are in "
         "results.csv beside every row (floor_main_ms, floor_depth_ms)."},
    };
    return definitions;
}

const char* kIntroduction =
    "Medians of the timed frames after warm-up (p5 and p95 in results.csv). Timed frames write the lit colour only; "
    "accuracy is measured on a separate, untimed re-render of the last frame with the accuracy targets.";
const char* kSoftwareNote =
    "Rendered with llvmpipe (CPU): the timings show relative costs on a CPU rasteriser, not GPU speed. Speed figures "
    "come from the GPU runs in docs/results/.";
const char* kHeatmapNote =
    "beside it its error heatmap against the ray-traced reference: magenta where it is darker than the reference "
    "(false shadow), green where it is lighter (false light), stronger with the error, black where it agrees or the "
    "pixel is not compared.";

// The parameters a sweep changes: for each technique, the param.* and scene.* keys whose value
// differs between two of its rows. The others are its defaults or the spec's base, said once.
std::map<std::string, std::set<std::string>> changingSettings(const std::vector<nlohmann::json>& rows) {
    std::map<std::string, std::map<std::string, std::set<std::string>>> seen;
    for (const auto& row : rows)
        for (const auto& [key, value] : row.items())
            if (key.rfind("param.", 0) == 0 || key.rfind("scene.", 0) == 0)
                seen[row.value("technique", "")][key].insert(value.dump());
    std::map<std::string, std::set<std::string>> changing;
    for (const auto& [technique, keys] : seen)
        for (const auto& [key, values] : keys)
            if (values.size() > 1) changing[technique].insert(key);
    return changing;
}

std::string changedSettings(const nlohmann::json& row, const std::set<std::string>& keys) {
    std::string text;
    for (const std::string& key : keys) {
        if (!row.contains(key)) continue;
        if (!text.empty()) text += ' ';
        const auto& value = row[key];
        text += key.substr(key.find('.') + 1) + "=" + (value.is_string() ? value.get<std::string>() : value.dump());
    }
    return text.empty() ? "defaults" : text;
}

std::string percent(const nlohmann::json& row, const std::string& key) {
    return row.contains(key) ? fixed(100.0 * row[key].get<double>(), 2) + "%" : "-";
}

std::string decimals(const nlohmann::json& row, const std::string& key, int digits) {
    return row.contains(key) ? fixed(row[key].get<double>(), digits) : "-";
}

// One row of the results table, a cell per kResultColumns entry.
std::vector<std::string> resultCells(const nlohmann::json& row, const std::map<std::string, std::set<std::string>>& changing) {
    const std::string technique = row.value("technique", "");
    const auto keys = changing.find(technique);
    std::string prepass = "-";
    if (row.contains("depth_prepass_mode"))
        prepass = row["depth_prepass_mode"].get<std::string>() + ": " + (row.value("depth_prepass", 0) ? "on" : "off");
    return {row.value("scene", ""),
            technique,
            changedSettings(row, keys == changing.end() ? std::set<std::string>{} : keys->second),
            std::to_string(row.value("width", 0)) + "x" + std::to_string(row.value("height", 0)),
            fixed(row.value("frame_ms", 0.0), 3),
            fixed(row.value("technique_passes_ms", 0.0), 3),
            decimals(row, "shadow_term_ms", 3),
            fixed(double(row.value("gpu_bytes", size_t(0))) / 1048576.0, 2),
            decimals(row, "hard_mae", 4),
            percent(row, "hard_false_shadow"),
            percent(row, "hard_false_light"),
            decimals(row, "soft_mae", 4),
            percent(row, "soft_false_shadow"),
            percent(row, "soft_false_light"),
            prepass};
}

std::string baseSettings(const BenchSpec& spec) {
    std::string base;
    for (const auto& item : spec.base) base += (base.empty() ? "" : ", ") + ("`" + item + "`");
    return base;
}

std::string imageCaption(const ReportImage& image) {
    if (image.heatmap.empty()) return "the reference itself";
    return "against the " + image.reference + " reference, MAE " + fixed(image.metrics.mae, 4) + ", false shadow " +
           fixed(100.0 * image.metrics.falseShadowRate, 2) + "%, false light " +
           fixed(100.0 * image.metrics.falseLightRate, 2) + "%";
}

glm::ivec2 imageSize(const ReportContent& c) {
    return c.specs->empty() ? glm::ivec2(0) : c.specs->front().sizes.front();
}

bool softwareRenderer(const nlohmann::json& environment) {
    return environment.value("gpu", "").find("llvmpipe") != std::string::npos;
}

// Markdown inline text as HTML: escaped, `code` as <code>.
std::string inlineHtml(const std::string& markdown) {
    std::string out;
    bool code = false;
    for (char ch : markdown) {
        if (ch == '`') {
            out += code ? "</code>" : "<code>";
            code = !code;
        } else {
            out += htmlEscape(std::string(1, ch));
        }
    }
    return out;
}

const std::string& environmentValue(const nlohmann::json& environment, const char* key, std::string& storage) {
    storage = environment.contains(key) && environment[key].is_string() ? environment[key].get<std::string>() : "";
    return storage;
}

void markdownImages(std::ostringstream& page, const ReportContent& c) {
    const glm::ivec2 size = imageSize(c);
    page << "\n## Images\n\nEach technique with its defaults at " << size.x << "x" << size.y << ", and " << kHeatmapNote
         << " " << c.imageFiles << " images in images/.\n\n";
    std::string scene;
    for (const ReportImage& image : c.images) {
        if (image.scene != scene) {
            scene = image.scene;
            page << "### " << scene << "\n\n| technique | image | error heatmap |\n|---|---|---|\n";
        }
        page << "| **" << image.displayName << "** (`" << image.technique << "`): " << imageCaption(image) << " | !["
             << image.image << "](images/" << image.image << ") | ";
        if (image.heatmap.empty()) page << "- |\n";
        else page << "![" << image.heatmap << "](images/" << image.heatmap << ") |\n";
    }
    page << "\n";
}

} // namespace

std::string reportMarkdown(const ReportContent& c) {
    std::ostringstream page;
    std::string value;
    page << "# shadowlab report\n\n";
    for (const char* key : {"gpu", "driver", "backend", "date", "commit"})
        page << "- " << (std::string(key) == "gpu" ? "GPU" : key) << ": " << environmentValue(c.environment, key, value) << "\n";
    page << "\nThe same report as one HTML page: [index.html](index.html).\n\n" << kIntroduction << "\n\nColumns of the results table:\n\n";
    for (const Definition& d : columnDefinitions()) {
        std::string names;
        for (const std::string& name : d.names) names += (names.empty() ? "" : ", ") + ("**" + name + "**");
        page << "- " << names << ": " << d.text << "\n";
    }
    page << "\n";
    if (softwareRenderer(c.environment)) page << "**" << kSoftwareNote << "**\n\n";
    page << "## Speed against accuracy\n\n";
    for (const auto& chart : c.charts) page << "![" << chart << "](charts/" << chart << ")\n\n";
    page << "## Results\n\n";
    for (size_t i = 0; i < c.specs->size(); ++i)
        if (!(*c.specs)[i].base.empty())
            page << "Set for every row" << (c.specs->size() > 1 ? " of spec " + std::to_string(i) : std::string()) << ": "
                 << baseSettings((*c.specs)[i]) << ".\n\n";
    page << "|";
    for (const auto& column : kResultColumns) page << " " << column << " |";
    page << "\n|---|---|---|---|";
    for (size_t i = 4; i < kResultColumns.size(); ++i) page << (i + 1 == kResultColumns.size() ? "---|" : "---:|");
    page << "\n";
    const auto changing = changingSettings(*c.rows);
    for (const auto& row : *c.rows) {
        page << "|";
        for (const std::string& cell : resultCells(row, changing)) page << " " << cell << " |";
        page << "\n";
    }
    markdownImages(page, c);
    return page.str();
}

namespace {

const char* kStyle =
    "body{font-family:sans-serif;max-width:1400px;margin:2em auto;padding:0 1em;line-height:1.45;color:#222}\n"
    "img{max-width:100%;height:auto;border:1px solid #ccc;background:#fff}\n"
    "table{border-collapse:collapse;margin:.5em 0 2em;font-size:.9em}\n"
    "td,th{border:1px solid #ccc;padding:.2em .5em;text-align:right;white-space:nowrap}\n"
    "td:nth-child(-n+3),th:nth-child(-n+3){text-align:left}\n"
    "tbody tr:nth-child(even){background:#f6f6f6}\n"
    "table.machine td,table.machine th{text-align:left;white-space:normal}\n"
    "figure{margin:0 0 1.5em}\n.gallery{display:grid;gap:.5em 1.5em}\nfigure.technique{margin:0 0 1em}\n"
    "figure.technique img{margin-right:.3em}\n"
    "figcaption{margin-top:.3em;max-width:60em}\ndt{font-weight:bold}\ndd{margin:0 0 .4em 1.5em}\n"
    ".wide{overflow-x:auto}\nfigure.chart img{max-width:min(100%,1100px)}\n"
    ".note{background:#fff4d6;padding:.5em 1em;border-left:4px solid #e0a000}\ncode{font-size:.95em}\n";

void htmlHead(std::ostringstream& html, const ReportContent& c) {
    std::string value;
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>shadowlab report: "
         << htmlEscape(environmentValue(c.environment, "gpu", value)) << "</title>\n<style>\n" << kStyle
         << "</style>\n</head>\n<body>\n<h1>shadowlab report</h1>\n<table class=\"machine\" id=\"machine\">\n";
    for (const auto& [key, label] : std::vector<std::pair<const char*, const char*>>{
             {"gpu", "GPU"}, {"driver", "driver"}, {"backend", "backend"}, {"date", "date"}, {"commit", "commit"}})
        html << "<tr><th>" << label << "</th><td>" << htmlEscape(environmentValue(c.environment, key, value)) << "</td></tr>\n";
    html << "<tr><th>rows</th><td>" << c.rows->size() << " measured, in results.csv and results.json</td></tr>\n</table>\n"
         << "<p>" << kIntroduction << "</p>\n";
    if (softwareRenderer(c.environment)) html << "<p class=\"note\"><strong>" << kSoftwareNote << "</strong></p>\n";
    html << "<p><a href=\"#charts\">Speed against accuracy</a> | <a href=\"#results\">Results</a> | <a "
            "href=\"#images\">Images</a> | <a href=\"README.md\">README.md</a> (the same report in Markdown)</p>\n";
}

void htmlResults(std::ostringstream& html, const ReportContent& c) {
    html << "<h2 id=\"results\">Results</h2>\n";
    for (size_t i = 0; i < c.specs->size(); ++i)
        if (!(*c.specs)[i].base.empty())
            html << "<p>Set for every row" << (c.specs->size() > 1 ? " of spec " + std::to_string(i) : std::string())
                 << ": " << inlineHtml(baseSettings((*c.specs)[i])) << ".</p>\n";
    html << "<div class=\"wide\"><table id=\"results-table\">\n<thead><tr>";
    for (const auto& column : kResultColumns) html << "<th>" << htmlEscape(column) << "</th>";
    html << "</tr></thead>\n<tbody>\n";
    const auto changing = changingSettings(*c.rows);
    for (const auto& row : *c.rows) {
        html << "<tr class=\"result\">";
        for (const std::string& cell : resultCells(row, changing)) html << "<td>" << htmlEscape(cell) << "</td>";
        html << "</tr>\n";
    }
    html << "</tbody>\n</table></div>\n<dl id=\"columns\">\n";
    for (const Definition& d : columnDefinitions()) {
        std::string names;
        for (const std::string& name : d.names) names += (names.empty() ? "" : ", ") + name;
        html << "<dt>" << htmlEscape(names) << "</dt><dd>" << inlineHtml(d.text) << "</dd>\n";
    }
    html << "</dl>\n";
}

void htmlImages(std::ostringstream& html, const ReportContent& c) {
    const glm::ivec2 size = imageSize(c);
    html << "<h2 id=\"images\">Images</h2>\n<p>Each technique with its defaults at " << size.x << "x" << size.y << ", and "
         << kHeatmapNote << " " << c.imageFiles << " images in images/.</p>\n";
    std::string scene;
    for (const ReportImage& image : c.images) {
        if (image.scene != scene) {
            if (!scene.empty()) html << "</div>\n</section>\n";
            scene = image.scene;
            // As many image-and-heatmap pairs a line as fit.
            html << "<section id=\"scene-" << htmlEscape(scene) << "\">\n<h3>" << htmlEscape(scene)
                 << "</h3>\n<div class=\"gallery\" style=\"grid-template-columns:repeat(auto-fill,minmax("
                 << std::min(2 * size.x + 24, 1300) << "px,1fr))\">\n";
        }
        const std::string alt = image.displayName + " on " + image.scene;
        html << "<figure class=\"technique\" id=\"" << htmlEscape(image.scene + "-" + image.technique) << "\">\n<img src=\"images/"
             << htmlEscape(image.image) << "\" width=\"" << size.x << "\" height=\"" << size.y << "\" alt=\"" << htmlEscape(alt)
             << "\">";
        if (!image.heatmap.empty())
            html << "<img src=\"images/" << htmlEscape(image.heatmap) << "\" width=\"" << size.x << "\" height=\"" << size.y
                 << "\" alt=\"" << htmlEscape(alt) << ": error heatmap\">";
        html << "\n<figcaption><strong>" << htmlEscape(image.displayName) << "</strong> (<code>" << htmlEscape(image.technique)
             << "</code>): " << htmlEscape(imageCaption(image)) << "</figcaption>\n</figure>\n";
    }
    if (!scene.empty()) html << "</div>\n</section>\n";
}

} // namespace

std::string reportHtml(const ReportContent& c) {
    std::ostringstream html;
    htmlHead(html, c);
    html << "<h2 id=\"charts\">Speed against accuracy</h2>\n";
    if (c.charts.empty()) html << "<p>No charts: tools/charts.py did not run (python3-matplotlib missing?).</p>\n";
    for (const auto& chart : c.charts)
        html << "<figure class=\"chart\"><img src=\"charts/" << htmlEscape(chart) << "\" alt=\"" << htmlEscape(chart)
             << "\"><figcaption>" << htmlEscape(chart) << "</figcaption></figure>\n";
    htmlResults(html, c);
    htmlImages(html, c);
    html << "</body>\n</html>\n";
    return html.str();
}

} // namespace shadowlab
