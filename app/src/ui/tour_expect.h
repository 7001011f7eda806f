// A tour step's expectations (issue 29): what its caption claims, as data checked against the
// figures `shadowlab tour` measures, so a caption that disagrees with its own numbers is a failing
// run rather than a reader's confusion. No GL here: parsed with the tour, evaluated from numbers.
//
//   "expect": {"mae": "< 0.01", "false_shadow": ["> 0.5%", "> 4 * previous"], "B.mae": "< A"}
//
// A key is [A. | B.]metric (no prefix: A, the step's technique; B: its "compare"); a value is one
// comparison or an array of them, each `OP OPERAND` with OP one of < <= > >= and OPERAND a number
// (a "%" after it divides by 100) or [FACTOR *] REF, REF being [previous.][A. | B.][metric]
// ("previous" alone: the same side and metric of the previous step; "A", "B": the same metric of
// that side of this step; "A.mae_far": another metric). The vocabulary: docs/classroom.md.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace shadowlab {

struct TourExpectation {
    std::string key;                // as written: "B.mae" (messages, round trip)
    std::string text;               // the comparison as written: "< 0.01"
    int side = 0;                   // 0: A (the step's technique), 1: B (its compare)
    std::string metric;             // one of tourExpectMetrics()
    enum class Op { Less, LessEqual, Greater, GreaterEqual } op = Op::Less;
    bool absolute = true;           // OPERAND is a number (`value`), else factor * a measured figure
    double value = 0.0;
    double factor = 1.0;
    bool previous = false;          // the figure is the previous step's
    int operandSide = 0;
    std::string operandMetric;
};

struct TourExpectMetric {
    const char* name;
    const char* meaning;
    bool relativeOnly;              // depends on the machine or the image size: compared with figures only
    bool percent;                   // a rate: "%" allowed after a number
};
const std::vector<TourExpectMetric>& tourExpectMetrics();

// The "expect" object of a step; `where` names file and step ("t.json: steps[2]"). `hasCompare`
// and `hasPath` say whether B and the path-only metrics exist.
bool parseTourExpect(const nlohmann::json& object, const std::string& where, bool hasCompare, bool hasPath,
                     std::vector<TourExpectation>& out, std::string& error);
nlohmann::json tourExpectJson(const std::vector<TourExpectation>& expect);
// The first expectation that needs the previous step (onlyB: its B side), or null: refused on a
// tour's first step, after a step without compare, and in sessions.
const TourExpectation* firstUseOfPreviousStep(const std::vector<TourExpectation>& expect, bool onlyB = false);

// What was measured on a step: per side (0 A, 1 B), metric name -> value; a side or metric that
// was not measured (the reference itself, no translucent receiver in view) is absent.
struct TourStepFigures {
    std::map<std::string, double> side[2];
};

struct TourExpectResult {
    const TourExpectation* expectation = nullptr;
    bool passed = false;
    double measured = 0.0;
    double against = 0.0;           // the bound it was compared with (factor * figure, or the number)
    std::string detail;             // "measured 0.0452, bound 0.0400 (2 * previous 0.0200)" or why not measured
};

std::vector<TourExpectResult> evaluateTourExpectations(const std::vector<TourExpectation>& expect,
                                                       const TourStepFigures& now, const TourStepFigures* previous);
// An expectation and its figures, for the page and messages: "mae < 0.01: measured 0.0042, bound 0.0100".
std::string tourExpectLine(const TourExpectResult& result);

} // namespace shadowlab
