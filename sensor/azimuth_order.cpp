#include "sensor/azimuth_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace conicloc::sensor {
namespace {

// Runs beyond this many, or moves beyond this many per return, are left to std::stable_sort: the
// input is not de-skew's near order, and insertion sort's O(n·k) would exceed O(n log n).
constexpr std::size_t kMaxRuns = 4;
constexpr std::size_t kMovesPerReturn = 16;
// More than one return in this many out of order with its predecessor: not a near order.
constexpr std::size_t kDescentsPerReturn = 8;

bool before(const Return& a, const Return& b) {
  return a.azimuth_rad < b.azimuth_rad;
}

// Stable insertion sort of [first, last): each return moves left past the ones strictly after
// it, so equal azimuths keep their order. False once `budget` moves are spent (the range is then
// still a stable permutation of the input, partly sorted).
bool insertion_sort(std::vector<Return>::iterator first, std::vector<Return>::iterator last,
                    std::size_t& budget) {
  if (last - first < 2) return true;
  for (auto i = first + 1; i != last; ++i) {
    if (!before(*i, *(i - 1))) continue;
    Return moving = *i;
    auto j = i;
    do {
      *j = *(j - 1);
      --j;
    } while (j != first && before(moving, *(j - 1)));
    *j = moving;
    const auto moved = static_cast<std::size_t>(i - j);
    if (moved > budget) return false;
    budget -= moved;
  }
  return true;
}

}  // namespace

void sort_by_azimuth(std::vector<Return>& returns) {
  // The runs between wraps, each nearly in order.
  std::vector<std::size_t> starts{0};
  std::size_t descents = 0;
  for (std::size_t i = 1; i < returns.size() && starts.size() <= kMaxRuns; ++i) {
    if (returns[i].azimuth_rad < returns[i - 1].azimuth_rad - M_PI) {
      starts.push_back(i);
    } else if (before(returns[i], returns[i - 1])) {
      ++descents;
    }
  }
  std::size_t budget = kMovesPerReturn * returns.size();
  bool sorted = starts.size() <= kMaxRuns && descents <= returns.size() / kDescentsPerReturn;
  for (std::size_t r = 0; sorted && r < starts.size(); ++r) {
    const std::size_t end = r + 1 < starts.size() ? starts[r + 1] : returns.size();
    sorted = insertion_sort(returns.begin() + static_cast<std::ptrdiff_t>(starts[r]),
                            returns.begin() + static_cast<std::ptrdiff_t>(end), budget);
  }
  if (!sorted) {
    // A stable sort of a stable permutation of the input: the input's stable order.
    std::stable_sort(returns.begin(), returns.end(), before);
    return;
  }
  // Sorted runs merged in their order: on equal azimuths the earlier run's return comes first, as
  // in a stable sort of the whole.
  for (std::size_t r = 1; r < starts.size(); ++r) {
    const std::size_t end = r + 1 < starts.size() ? starts[r + 1] : returns.size();
    std::inplace_merge(returns.begin(), returns.begin() + static_cast<std::ptrdiff_t>(starts[r]),
                       returns.begin() + static_cast<std::ptrdiff_t>(end), before);
  }
}

}  // namespace conicloc::sensor
