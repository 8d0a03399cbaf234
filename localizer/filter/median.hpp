#pragma once
// The median of a sample: the middle value, or the mean of the two middle values of an even
// count (the upper one alone is biased upward by a fraction of the spread for small counts).

#include <algorithm>
#include <cstddef>
#include <vector>

namespace conicloc::localizer {

/// The median of `values`, which it reorders; 0 when empty.
inline double median_of(std::vector<double>& values) {
  if (values.empty()) return 0.0;
  const std::size_t mid = values.size() / 2;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(mid);
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return 0.5 * (*middle + *std::max_element(values.begin(), middle));
}

}  // namespace conicloc::localizer
