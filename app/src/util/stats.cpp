// Percentiles (see stats.h).
#include "util/stats.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace shadowlab {

double percentile(std::vector<double> values, double fraction) {
    if (values.empty()) return 0.0;
    // The two order statistics around the rank, in linear time (a full sort of a 1080p frame's
    // values was most of an evaluation's cost): the same values a sort would put there.
    const double rank = std::clamp(fraction, 0.0, 1.0) * double(values.size() - 1);
    const size_t below = size_t(std::floor(rank));
    std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(below), values.end());
    const double low = values[below];
    const double high = below + 1 < values.size() ? *std::min_element(values.begin() + std::ptrdiff_t(below) + 1, values.end()) : low;
    return low + (high - low) * (rank - double(below));
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

double medianRelativeHalfWidth95(std::vector<double> values) {
    const size_t n = values.size();
    if (n < 6) return std::numeric_limits<double>::infinity();
    std::sort(values.begin(), values.end());
    const double spread = 1.96 * std::sqrt(double(n)) / 2.0;
    // 1-based ranks floor(n/2 - spread) and ceil(n/2 + 1 + spread), clamped to the set.
    const size_t low = size_t(std::max(std::floor(double(n) / 2.0 - spread), 1.0)) - 1;
    const size_t high = std::min(size_t(std::ceil(double(n) / 2.0 + 1.0 + spread)), n) - 1;
    const double median = percentile(values, 0.5);
    if (!(median > 0.0)) return std::numeric_limits<double>::infinity();
    return (values[high] - values[low]) / (2.0 * median);
}

} // namespace shadowlab
