// Percentiles (see stats.h).
#include "util/stats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace shadowlab {

double percentile(std::vector<double> values, double fraction) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const double rank = std::clamp(fraction, 0.0, 1.0) * double(values.size() - 1);
    const size_t below = size_t(std::floor(rank));
    const size_t above = std::min(below + 1, values.size() - 1);
    return values[below] + (values[above] - values[below]) * (rank - double(below));
}

TimingSummary summarize(const std::vector<double>& values) {
    TimingSummary s;
    s.count = values.size();
    if (values.empty()) return s;
    s.median = percentile(values, 0.5);
    s.p5 = percentile(values, 0.05);
    s.p95 = percentile(values, 0.95);
    s.mean = std::accumulate(values.begin(), values.end(), 0.0) / double(values.size());
    return s;
}

} // namespace shadowlab
