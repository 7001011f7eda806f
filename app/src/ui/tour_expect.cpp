// A tour step's expectations (see tour_expect.h).
#include "ui/tour_expect.h"

#include <cmath>
#include <cstdlib>
#include <utility>

#include "util/strings.h"

namespace shadowlab {
namespace {

using nlohmann::json;

std::string trimmed(const std::string& text) {
    const size_t first = text.find_first_not_of(" \t");
    if (first == std::string::npos) return "";
    return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

const TourExpectMetric* findMetric(const std::string& name) {
    for (const TourExpectMetric& m : tourExpectMetrics())
        if (name == m.name) return &m;
    return nullptr;
}

// A figure as the page shows it: rates in percent, the rest with four decimals.
std::string figureText(const std::string& metric, double value) {
    const TourExpectMetric* m = findMetric(metric);
    return m && m->percent ? fixed(100.0 * value, 2) + "%" : fixed(value, 4);
}

std::string metricNames() {
    std::string names;
    for (const TourExpectMetric& m : tourExpectMetrics()) appendListItem(names, m.name);
    return names;
}

// A whole finite number, nothing after it but (when `percent` is given) an optional '%'.
bool readNumber(const std::string& text, double& value, bool* percent) {
    if (text.empty()) return false;
    char* end = nullptr;
    value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || !std::isfinite(value)) return false;
    std::string rest = trimmed(end);
    if (percent) *percent = rest == "%";
    return rest.empty() || (percent && rest == "%");
}

// "[previous.][A.|B.][metric]" into the expectation's operand: the key's side and metric where none is named.
bool readReference(const std::string& text, TourExpectation& e, std::string& problem) {
    std::vector<std::string> tokens;
    for (size_t start = 0;;) {
        const size_t dot = text.find('.', start);
        tokens.push_back(text.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
        if (dot == std::string::npos) break;
        start = dot + 1;
    }
    size_t i = 0;
    e.previous = tokens[i] == "previous";
    if (e.previous) ++i;
    e.operandSide = e.side;
    if (i < tokens.size() && (tokens[i] == "A" || tokens[i] == "B")) e.operandSide = tokens[i++] == "B" ? 1 : 0;
    e.operandMetric = e.metric;
    if (i < tokens.size()) e.operandMetric = tokens[i++];
    if (i != tokens.size() || !findMetric(e.operandMetric)) {
        problem = "expected a number or [factor *] [previous.][A.|B.][metric] (metrics: " + metricNames() + ")";
        return false;
    }
    return true;
}

// One comparison: "OP OPERAND".
bool readComparison(const std::string& written, TourExpectation& e, std::string& problem) {
    const std::string text = trimmed(written);
    using Op = TourExpectation::Op;
    static const std::pair<const char*, Op> operators[] = {
        {"<=", Op::LessEqual}, {">=", Op::GreaterEqual}, {"<", Op::Less}, {">", Op::Greater}};   // longest first
    size_t opLength = 0;
    for (const auto& [symbol, op] : operators) {
        if (text.rfind(symbol, 0) != 0) continue;
        e.op = op;
        opLength = std::char_traits<char>::length(symbol);
        break;
    }
    if (opLength == 0) {
        problem = "expected a comparison starting with <, <=, > or >=";
        return false;
    }
    const std::string operand = trimmed(text.substr(opLength));
    const TourExpectMetric& metric = *findMetric(e.metric);
    bool percent = false;
    if (readNumber(operand, e.value, &percent)) {
        if (percent && !metric.percent) {
            problem = "'%' is for rates (false_shadow, false_light, penumbra, undersampled), not " + e.metric;
            return false;
        }
        if (metric.relativeOnly) {
            problem = e.metric + " depends on the machine or the image size: compare it with a figure "
                      "(previous, A, B), not a number";
            return false;
        }
        if (percent) e.value /= 100.0;
        e.absolute = true;
        return true;
    }
    e.absolute = false;
    std::string reference = operand;
    if (const size_t star = operand.find('*'); star != std::string::npos) {
        if (!readNumber(trimmed(operand.substr(0, star)), e.factor, nullptr) || e.factor <= 0.0) {
            problem = "the factor before '*' must be a positive number";
            return false;
        }
        reference = trimmed(operand.substr(star + 1));
    }
    if (reference.empty() || !readReference(reference, e, problem)) {
        if (problem.empty()) problem = "expected a number or [factor *] [previous.][A.|B.][metric]";
        return false;
    }
    if (!e.previous && e.operandSide == e.side && e.operandMetric == e.metric) {
        problem = "compares " + e.metric + " with itself";
        return false;
    }
    return true;
}

// The key "[A.|B.]metric" into side and metric.
bool readKey(const std::string& key, TourExpectation& e, bool hasCompare, bool hasPath, std::string& problem) {
    std::string metric = key;
    e.side = 0;
    if (key.rfind("A.", 0) == 0 || key.rfind("B.", 0) == 0) {
        e.side = key[0] == 'B' ? 1 : 0;
        metric = key.substr(2);
    }
    if (!findMetric(metric)) {
        problem = "unknown metric '" + metric + "' (expected [A.|B.] and one of " + metricNames() + ")";
        return false;
    }
    e.metric = metric;
    if (e.side == 1 && !hasCompare) {
        problem = "B is the compared technique and this step has no 'compare'";
        return false;
    }
    if (metric == "flicker" && !hasPath) {
        problem = "flicker is measured along the step's path and this step has no 'path'";
        return false;
    }
    return true;
}

} // namespace

const std::vector<TourExpectMetric>& tourExpectMetrics() {
    static const std::vector<TourExpectMetric> metrics = {
        {"mae", "mean absolute error of the shadow term against the step's reference (the page's MAE)", false, false},
        {"false_shadow", "rate of compared pixels the reference lights and the technique darkens", false, true},
        {"false_light", "rate of compared pixels the reference shadows and the technique lights", false, true},
        {"mae_penumbra", "mean error over the reference's penumbra pixels (0.02 < reference < 0.98)", false, false},
        {"penumbra", "rate of compared pixels where the technique itself draws penumbra (0.02 to 0.98)", false, true},
        {"edge_band_mae", "mean error within 3 px of the hard reference's shadow edges (hard reference only)", false, false},
        {"mae_near", "mean error in the nearest third of the camera's view depth", false, false},
        {"mae_mid", "mean error in the middle third of the view depth", false, false},
        {"mae_far", "mean error in the farthest third of the view depth", false, false},
        {"noise", "high-frequency error: mean |e - mean of e over the 4 neighbours|", false, false},
        {"translucent_mae", "mean error on the translucent receivers (none in view: not measured)", false, false},
        {"flicker", "temporal error along the step's path (path steps only)", false, false},
        {"gpu_mib", "the technique's own GPU memory in MiB", false, false},
        {"frame_ms", "median GPU ms of a frame (relative only: machines differ by orders of magnitude)", true, false},
        {"footprint_near", "median texel footprint m in the nearest third (pixels per texel: relative only)", true, false},
        {"footprint_far", "median texel footprint m in the farthest third (relative only)", true, false},
        {"undersampled", "rate of pixels with m > 1, texels larger than pixels (relative only)", true, true},
    };
    return metrics;
}

bool parseTourExpect(const json& object, const std::string& where, bool hasCompare, bool hasPath,
                     std::vector<TourExpectation>& out, std::string& error) {
    out.clear();
    const std::string at = where + ".expect";
    if (!object.is_object() || object.empty()) {
        error = at + ": expected a non-empty object of metric: comparison (docs/classroom.md, \"expect\")";
        return false;
    }
    for (const auto& [key, value] : object.items()) {
        std::vector<std::string> texts;
        if (value.is_string()) texts.push_back(value.get<std::string>());
        else if (value.is_array() && !value.empty())
            for (const json& item : value)
                texts.push_back(item.is_string() ? item.get<std::string>() : std::string());
        if (texts.empty()) {
            error = at + "." + key + ": expected a comparison (\"< 0.01\") or an array of them";
            return false;
        }
        for (const std::string& text : texts) {
            TourExpectation e;
            e.key = key;
            e.text = text;
            std::string problem;
            if (!readKey(key, e, hasCompare, hasPath, problem)) {
                error = at + "." + key + ": " + problem;
                return false;
            }
            if (text.size() > 200) problem = "at most 200 bytes";
            else if (!readComparison(text, e, problem)) {
            } else if (!e.absolute && e.operandSide == 1 && !e.previous && !hasCompare)
                problem = "B is the compared technique and this step has no 'compare'";
            else if (!e.absolute && e.operandMetric == "flicker" && !hasPath)
                problem = "flicker is measured along the step's path and this step has no 'path'";
            if (!problem.empty()) {
                error = at + "." + key + ": '" + text + "': " + problem;
                return false;
            }
            out.push_back(std::move(e));
        }
    }
    return true;
}

json tourExpectJson(const std::vector<TourExpectation>& expect) {
    json out = json::object();
    for (const TourExpectation& e : expect) {
        if (!out.contains(e.key)) out[e.key] = e.text;
        else if (out[e.key].is_string()) out[e.key] = json::array({out[e.key], e.text});
        else out[e.key].push_back(e.text);
    }
    return out;
}

const TourExpectation* firstUseOfPreviousStep(const std::vector<TourExpectation>& expect, bool onlyB) {
    for (const TourExpectation& e : expect)
        if (e.previous && !e.absolute && (!onlyB || e.operandSide == 1)) return &e;
    return nullptr;
}

std::vector<TourExpectResult> evaluateTourExpectations(const std::vector<TourExpectation>& expect,
                                                       const TourStepFigures& now, const TourStepFigures* previous) {
    std::vector<TourExpectResult> results;
    const char* sides[] = {"A", "B"};
    for (const TourExpectation& e : expect) {
        TourExpectResult r;
        r.expectation = &e;
        const auto& mine = now.side[e.side];
        const auto found = mine.find(e.metric);
        if (found == mine.end()) {
            r.detail = "not measured (" + std::string(sides[e.side]) + " has no " + e.metric + " on this step)";
            results.push_back(r);
            continue;
        }
        r.measured = found->second;
        r.against = e.value;
        std::string bound = "";
        if (!e.absolute) {
            const TourStepFigures* source = e.previous ? previous : &now;
            const std::string name = std::string(e.previous ? "previous." : "") + sides[e.operandSide] + "." + e.operandMetric;
            const auto* figures = source ? &source->side[e.operandSide] : nullptr;
            const auto other = figures ? figures->find(e.operandMetric) : std::map<std::string, double>::const_iterator{};
            if (!figures || other == figures->end()) {
                r.detail = "measured " + figureText(e.metric, r.measured) + ", but " + name + " was not measured";
                results.push_back(r);
                continue;
            }
            r.against = e.factor * other->second;
            bound = " (" + (e.factor == 1.0 ? std::string() : fixed(e.factor, 3) + " * ") + name + " " +
                    figureText(e.operandMetric, other->second) + ")";
        }
        switch (e.op) {
        case TourExpectation::Op::Less: r.passed = r.measured < r.against; break;
        case TourExpectation::Op::LessEqual: r.passed = r.measured <= r.against; break;
        case TourExpectation::Op::Greater: r.passed = r.measured > r.against; break;
        case TourExpectation::Op::GreaterEqual: r.passed = r.measured >= r.against; break;
        }
        r.detail = "measured " + figureText(e.metric, r.measured) + ", bound " + figureText(e.metric, r.against) + bound;
        results.push_back(r);
    }
    return results;
}

std::string tourExpectLine(const TourExpectResult& result) {
    const TourExpectation& e = *result.expectation;
    return e.key + " " + e.text + ": " + result.detail;
}

} // namespace shadowlab
