#include "localizer/filter/storey_twins.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "localizer/filter/log_weights.hpp"

namespace conicloc::localizer {

void StoreyTwins::start(const PoseState& estimate, double mounting_height_m) {
  twins_.clear();
  if (!config_.enabled) return;
  const std::optional<Footing> own = footing(estimate, mounting_height_m);
  last_storey_ = own ? own->storey : -1;
  const int storeys = static_cast<int>(map_.storeys.size());
  for (int offset = 1 - storeys; offset < storeys; ++offset) {
    if (offset != 0 && (!own || storey_exists(own->storey + offset)))
      twins_.push_back({offset, 0.0, 0});
  }
}

std::optional<StoreyTwins::Footing> StoreyTwins::footing(const PoseState& estimate,
                                                         double mounting_height_m) const {
  const double floor_hint_m = estimate.z - mounting_height_m;
  const int cell = free_space_.cell_at(estimate.x, estimate.y, floor_hint_m);
  if (cell < 0 || map_.cells[static_cast<std::size_t>(cell)].storey < 0) return std::nullopt;
  return Footing{map_.cells[static_cast<std::size_t>(cell)].storey,
                 free_space_.floor_z_at(cell, estimate.x, estimate.y, floor_hint_m)};
}

double StoreyTwins::storey_rise_m(int storey, int offset) const {
  const int other = storey + offset;
  if (!storey_exists(storey) || !storey_exists(other)) return 0.0;
  return map_.storeys[static_cast<std::size_t>(other)].floor_z -
         map_.storeys[static_cast<std::size_t>(storey)].floor_z;
}

bool StoreyTwins::storey_exists(int storey) const {
  return storey >= 0 && storey < static_cast<int>(map_.storeys.size());
}

std::optional<PoseState> StoreyTwins::twin_pose(const PoseState& estimate, double mounting_height_m,
                                                int offset) const {
  const std::optional<Footing> own = footing(estimate, mounting_height_m);
  if (!own) return std::nullopt;
  return twin_at(estimate, *own, offset);
}

std::optional<PoseState> StoreyTwins::twin_at(const PoseState& estimate, const Footing& own,
                                              int offset) const {
  const int storey = own.storey + offset;
  if (offset == 0 || !storey_exists(storey)) return std::nullopt;
  // That storey's floor where the estimate's is, moved by the storeys' spacing: a stair of
  // that storey at the same height on it, not the floor of a landing above or below.
  const double floor_hint_m = own.floor_z + storey_rise_m(own.storey, offset);
  const int cell = free_space_.cell_at(estimate.x, estimate.y, floor_hint_m);
  if (cell < 0 || map_.cells[static_cast<std::size_t>(cell)].storey != storey) return std::nullopt;
  const double floor_z = free_space_.floor_z_at(cell, estimate.x, estimate.y, floor_hint_m);
  if (!(std::abs(floor_z - floor_hint_m) <= config_.floor_tolerance_m)) return std::nullopt;
  PoseState twin = estimate;
  twin.z = floor_z + (estimate.z - own.floor_z);
  return twin;
}

double StoreyTwins::log_total() const {
  // log(1 + Σ e^{L_k}): the estimate's odds (1) and its twins', in the log domain, so that
  // overwhelming evidence for one twin leaves the others' shares at 0, not at NaN.
  std::vector<double> log_odds{0.0};
  for (const StoreyTwin& twin : twins_) log_odds.push_back(twin.log_odds);
  return log_sum_exp(log_odds);
}

void StoreyTwins::drop_refuted() {
  const double refuted_below = log_total() + std::log(config_.min_share);
  std::erase_if(twins_, [&](const StoreyTwin& twin) { return !(twin.log_odds >= refuted_below); });
}

StoreyTwinsUpdate StoreyTwins::summarise(int storey) const {
  const double log_normaliser = log_total();
  StoreyTwinsUpdate summary;
  summary.estimate_share = std::exp(-log_normaliser);
  // The mixture's variance in z: Σ p_d Δz_d² − (Σ p_d Δz_d)², Δz_0 = 0 for the estimate.
  double mean = 0.0;
  double square = 0.0;
  for (const StoreyTwin& twin : twins_) {
    const double share = std::exp(twin.log_odds - log_normaliser);
    const double rise_m = storey_rise_m(storey, twin.offset);
    mean += share * rise_m;
    square += share * rise_m * rise_m;
  }
  summary.z_variance_m2 = std::max(square - mean * mean, 0.0);
  return summary;
}

StoreyTwinsUpdate StoreyTwins::current(const PoseState& estimate, double mounting_height_m) const {
  const std::optional<Footing> own = footing(estimate, mounting_height_m);
  return summarise(own ? own->storey : last_storey_);
}

StoreyTwinsUpdate StoreyTwins::update(const PoseState& estimate, double mounting_height_m,
                                      double tempering, const ScorePoses& score) {
  const std::optional<Footing> own = footing(estimate, mounting_height_m);
  if (twins_.empty() || !own) return summarise(own ? own->storey : last_storey_);
  last_storey_ = own->storey;

  // No storey that far from the estimate's: the hypothesis that the sensor stands that many
  // storeys off it is refuted (it moves with the estimate, up a stair too).
  std::erase_if(twins_,
                [&](const StoreyTwin& twin) { return !storey_exists(own->storey + twin.offset); });
  std::vector<PoseState> poses{estimate};
  std::vector<int> pose_of(twins_.size(), -1);  // per twin: its index in `poses`, or −1
  for (std::size_t i = 0; i < twins_.size(); ++i) {
    const std::optional<PoseState> pose = twin_at(estimate, *own, twins_[i].offset);
    if (pose) {
      pose_of[i] = static_cast<int>(poses.size());
      poses.push_back(*pose);
    }
    twins_[i].missing_scans = pose ? 0 : twins_[i].missing_scans + 1;
  }
  const std::vector<double> log_likelihoods =
      poses.size() > 1 ? score(poses) : std::vector<double>{};
  // An estimate that explains nothing is no yardstick (the lost test answers for it); a twin
  // that explains nothing loses all its odds.
  const bool measured = !log_likelihoods.empty() && std::isfinite(log_likelihoods[0]);
  for (std::size_t i = 0; i < twins_.size() && measured; ++i) {
    if (pose_of[i] < 0) continue;
    const double gain = log_likelihoods[static_cast<std::size_t>(pose_of[i])] - log_likelihoods[0];
    const double evidence = tempering * gain;  // NaN (0·∞, a NaN score) carries none
    if (std::isfinite(evidence) || evidence == -std::numeric_limits<double>::infinity())
      twins_[i].log_odds += evidence;
  }

  // Drop twins that had no floor for too long, then those the scans have refuted.
  std::erase_if(twins_, [&](const StoreyTwin& twin) {
    return twin.missing_scans > config_.max_missing_scans;
  });
  drop_refuted();
  const StoreyTwinsUpdate summary = summarise(own->storey);

  // The twin holding switch_share takes the cloud: the odds are counted from its storey.
  const double takes_from = log_total() + std::log(config_.switch_share);
  const auto leader = std::find_if(twins_.begin(), twins_.end(), [&](const StoreyTwin& twin) {
    return twin.log_odds >= takes_from;
  });
  if (leader == twins_.end()) return summary;
  const StoreyTwin taken = *leader;
  const std::optional<PoseState> taken_pose = twin_at(estimate, *own, taken.offset);
  if (!taken_pose) return summary;
  for (StoreyTwin& twin : twins_) {
    twin.offset -= taken.offset;
    twin.log_odds -= taken.log_odds;
  }
  // The taken twin becomes the estimate, the estimate's storey a twin of it; a twin the move
  // leaves under min_share (the old storey after overwhelming evidence) is dropped now.
  *leader = StoreyTwin{-taken.offset, -taken.log_odds, 0};
  drop_refuted();
  last_storey_ = own->storey + taken.offset;
  StoreyTwinsUpdate after = summarise(last_storey_);
  after.move_z_m = taken_pose->z - estimate.z;
  return after;
}

}  // namespace conicloc::localizer
