// Percentiles of a set of timings (linear interpolation between closest ranks).
#pragma once

#include <cstddef>
#include <vector>

namespace shadowlab {

struct TimingSummary {
    double median = 0.0;
    double p5 = 0.0;
    double p95 = 0.0;
    double mean = 0.0;
    size_t count = 0;
};

double percentile(std::vector<double> values, double fraction);
TimingSummary summarize(const std::vector<double>& values);

} // namespace shadowlab
