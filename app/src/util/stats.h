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

// Half the width of the distribution-free 95% confidence interval of the median, relative to the
// median: the order statistics n/2 -+ 1.96 sqrt(n)/2 (the binomial(n, 1/2) normal approximation).
// Infinity for fewer than 6 samples (too few for the ranks to fall inside the set) or a median of 0.
double medianRelativeHalfWidth95(std::vector<double> values);

// When a timing may stop before its frame count (bench specs' minFrames and stableWithin): once
// `minFrames` GPU frame times are in and their median's relative 95% half-width is at most
// `within`. within 0: every frame is timed.
struct TimingStop {
    int minFrames = 10;
    double within = 0.0;
    bool active() const { return within > 0.0; }
    bool reached(const std::vector<double>& frameMs) const {
        return active() && int(frameMs.size()) >= minFrames && medianRelativeHalfWidth95(frameMs) <= within;
    }
};

} // namespace shadowlab
