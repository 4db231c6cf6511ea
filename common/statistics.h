// Statistics of measured series (the benchmarks' figures).
#pragma once

#include <algorithm>
#include <vector>

namespace sward {

// The median of `values`: the upper of the middle two for an even count, 0 for none.
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const auto middle = values.begin() + std::ptrdiff_t(values.size() / 2);
    std::nth_element(values.begin(), middle, values.end());
    return *middle;
}

} // namespace sward
