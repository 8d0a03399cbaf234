#pragma once
// One run of an evaluation sweep (`conicloc evaluate --sweep`): a scenario simulated in a
// building, and one localizer setting run over that recording from the scenario's start. The
// sweep's order, folders, scores and report: sweep_runner.hpp.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "eval/sweep_plan.hpp"
#include "eval/sweep_scenario.hpp"
#include "io/tum_trajectory.hpp"
#include "localizer/filter/localizer.hpp"
#include "maps/plane_map.hpp"
#include "run/localize_run.hpp"

namespace conicloc::run {

/// One simulated recording, shared by every localizer setting run on it.
struct SweepRecording {
  std::string name;  ///< <building>-<scenario>-s<seed>
  std::string pcap_path;
  std::vector<io::StampedPose> truth;
  std::vector<io::StampedPose> odometry;
  double sensor_height_m = 0.8;
};

/// Simulates `scenario` in `map` for `duration_s` with `seed` and writes the capture, the truth
/// and the odometry into `runs_dir` as <name>.pcap, <name>.truth.tum and <name>.odom.tum.
SweepRecording simulate_recording(const maps::PlaneMap& map, const std::string& building_name,
                                  const eval::Scenario& scenario, std::uint64_t seed,
                                  double duration_s, const std::filesystem::path& runs_dir);

/// Where a sweep run starts the filter, from the first true pose: tracking around it, kidnapped
/// (confident at a pose 3 m and 90° from it), or globally.
FilterStart sweep_filter_start(const maps::PlaneMap& map, eval::FilterStartMode mode,
                               const localizer::Pose3& first_truth);

/// Which scans belong to a search: from a global start, or from any scan that ended unsure or
/// lost, up to and including the scan that ended in `tracking`. That scan is the search's (a
/// global start's first scan draws and scores the whole start's particles even when it
/// converges).
class SearchPhase {
 public:
  explicit SearchPhase(bool global_start) : searching_(global_start) {}
  /// Whether the scan whose update ended with `status` belongs to a search.
  bool add(localizer::LocalizerStatus status) {
    const bool tracking = status == localizer::LocalizerStatus::Tracking;
    const bool searched = searching_ || !tracking;
    searching_ = !tracking;
    return searched;
  }

 private:
  bool searching_;  ///< the next scan begins while the filter searches
};

/// What one localizer setting made of a recording.
struct SweepRunResult {
  std::vector<io::StampedPose> estimate;  ///< the pose at every localized scan
  std::vector<io::StampedPose> alarms;    ///< the estimate at each scan that declared itself lost
  double mean_particles = 0.0;            ///< over the localized scans
  /// Wall time of each update by SearchPhase: searching (a global start's or a recovery's scans,
  /// up to and including the one that converged) or tracking.
  std::vector<double> tracking_times_ms;
  std::vector<double> search_times_ms;
  LocalizeRunSummary summary;
};

/// Localizes `recording` with `setting` (`default` keeps LocalizerConfig's values: what
/// `conicloc localize` runs without options) on `threads` threads with `seed`, started as
/// `scenario` says, with the recording's odometry when the scenario uses it.
SweepRunResult localize_recording(const maps::PlaneMap& map, bool two_sided_walls,
                                  const eval::Scenario& scenario, std::uint64_t seed,
                                  const SweepRecording& recording,
                                  const eval::LocalizerSetting& setting, int threads);

}  // namespace conicloc::run
