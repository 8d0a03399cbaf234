#include "localizer/filter/see_through_history.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace conicloc::localizer {

void SeeThroughHistory::add(double time_s, double fraction) {
  history_.emplace_back(time_s, fraction);
  // Keep the newest scan older than the window's start: it shows the window is covered.
  while (history_.size() > 2 && history_[1].first <= time_s - config_.window_s)
    history_.pop_front();
}

double SeeThroughHistory::tested_quantile() const {
  if (history_.empty()) return 0.0;
  std::vector<double> fractions;
  fractions.reserve(history_.size());
  for (const auto& [time_s, fraction] : history_) fractions.push_back(fraction);
  // The order statistic at floor(q·(n − 1)): the lower quartile of 21 scans is the 6th smallest.
  const auto k = static_cast<std::size_t>(
      std::floor(config_.quantile * static_cast<double>(fractions.size() - 1)));
  std::nth_element(fractions.begin(), fractions.begin() + static_cast<std::ptrdiff_t>(k),
                   fractions.end());
  return fractions[k];
}

bool SeeThroughHistory::spans(double duration_s) const {
  return !history_.empty() && history_.back().first - history_.front().first >= duration_s;
}

}  // namespace conicloc::localizer
