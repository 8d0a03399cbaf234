#include "localizer/filter/see_through_history.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <vector>

namespace conicloc::localizer {

SeeThroughHistory::SeeThroughHistory(const SeeThroughHistoryConfig& config) : config_(config) {
  assert(config.quantile >= 0.0 && config.quantile <= 1.0);
  assert(config.check_s > 0.0 && config.check_s <= config.window_s);
}

void SeeThroughHistory::add(double time_s, double fraction) {
  if (!history_.empty() &&
      !(time_s >= history_.back().first && time_s - history_.back().first <= config_.max_gap_s))
    history_.clear();
  history_.emplace_back(time_s, fraction);
  // Keep the newest scan older than the window's start: it shows the window is covered.
  while (history_.size() > 2 && history_[1].first <= time_s - config_.window_s)
    history_.pop_front();
}

double SeeThroughHistory::tested_quantile(double within_s) const {
  if (history_.empty()) return 0.0;
  std::vector<double> fractions;
  fractions.reserve(history_.size());
  const double start_s = history_.back().first - within_s;
  for (const auto& [time_s, fraction] : history_) {
    if (time_s >= start_s) fractions.push_back(fraction);
  }
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
