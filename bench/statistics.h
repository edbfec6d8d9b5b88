// Statistics of per-step times, shared by the benchmark programs.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace cyclone::bench {

/// The value at `fraction` (0 to 1] of the values in ascending order (nearest rank).
inline double percentile(std::vector<double> values, double fraction) {
    std::sort(values.begin(), values.end());
    const std::size_t rank = static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(values.size())));
    return values[std::max<std::size_t>(rank, 1) - 1];
}

/// The arithmetic mean (0 for no values).
inline double mean(const std::vector<double> &values) {
    double sum = 0;
    for (double v : values) sum += v;
    return values.empty() ? 0 : sum / static_cast<double>(values.size());
}

/// The middle value (the mean of the two middle ones for an even count).
inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
}

}  // namespace cyclone::bench
