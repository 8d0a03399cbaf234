#pragma once
// The report of an evaluation sweep: one record per localization run, rendered as runs.csv, a
// Markdown summary and SVG charts (Pareto front of error against time per scan, error over time).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "eval/sweep_spec.hpp"
#include "eval/trajectory_metrics.hpp"

namespace conicloc::eval {

struct RunRecord {
  /// The map's file name without extension; a generated building's `KIND-sSEED`.
  std::string building;
  std::string scenario;
  std::uint64_t seed = 0;
  std::string model;
  int particles = 0;  ///< configured maximum; kDefaultSetting: the localizer's defaults
  /// Beams / points per scan the model scores; 0: all (segments: all returns); kDefaultSetting.
  int beams = 0;
  int threads = 0;
  int cores = 0;  ///< hardware threads of the machine
  bool failed = false;
  std::string error;  ///< why the run failed

  TrajectoryMetrics metrics;
  bool converged = false;         ///< the error settles below the convergence thresholds to the end
  double time_per_scan_ms = 0.0;  ///< mean wall time of one update
  double time_p95_ms = 0.0;
  double realtime_factor = 0.0;  ///< capture seconds per processing second
  double mean_particles = 0.0;
  std::size_t scans = 0;
  std::size_t recoveries = 0;
  std::string estimate_file;  ///< relative to the report folder

  // Robustness (issue 14's targets; robustness_report.hpp).
  /// The robustness table's row: the building, or `KIND-s*` for a building generated anew for
  /// every seed (its runs are taken together); empty: the building.
  std::string building_group;
  bool odometry = true;                  ///< the localizer was given odometry
  double capture_s = 0.0;                ///< capture time localized, first to last scan
  std::size_t false_alarms = 0;          ///< recoveries raised while the estimate was < 0.5 m off
  std::optional<double> time_to_10cm_s;  ///< until the xy error stays ≤ 10 cm (time_to_settle_s)

  // Cost against building size (issue 15; scale_report.hpp): the building's size, and the time per
  // scan split by what the filter was doing.
  int storeys = 0;
  std::size_t planes = 0;
  double floor_area_m2 = 0.0;    ///< navigable floor, plan view (FreeSpace::total_area_m2)
  double start_time_ms = 0.0;    ///< the start before the first scan (a global start's plan fields)
  std::size_t search_scans = 0;  ///< scans whose status was not `tracking`: searching or unsure
  double search_time_mean_ms = 0.0;
  double search_time_max_ms = 0.0;
  double tracking_time_mean_ms = 0.0;  ///< over the scans whose status was `tracking`

  /// Until the xy error stays ≤ 50 cm (time_to_settle_s), the lost bound of tracking: when a
  /// global start or a kidnap had found the place, whatever its accuracy then (time_to_10cm_s).
  std::optional<double> time_to_50cm_s;
  bool scored_at_50cm = true;  ///< false: read from a runs.csv written before that column

  /// Under map error, against the pose the map gives each scan (sim/map_fit.hpp): that pose's xy
  /// and heading RMSE against the truth (the map's share of the error, a reference rather than a
  /// bound), and the estimate's against it (the localizer's share), both at the estimate's times.
  /// Empty without map
  /// error.
  std::optional<double> map_fit_xy_rmse_m;
  std::optional<double> ate_xy_rmse_to_map_fit_m;
  std::optional<double> map_fit_heading_rmse_deg;
  std::optional<double> heading_rmse_to_map_fit_deg;
};

/// The runs.csv text: the columns `model,particles,beams,seed,scenario,ate_xy_rmse_m,
/// heading_rmse_deg,time_per_scan_ms,realtime_factor,converged` first, then more detail, and
/// last (added later, so scripts that index columns keep working) `building_group,odometry,
/// capture_s,false_alarms,time_to_10cm_s,lost`, then `storeys,planes,floor_area_m2,start_time_ms,
/// search_scans,search_time_mean_ms,search_time_max_ms,tracking_time_mean_ms`, then
/// `time_to_50cm_s`, then `map_fit_xy_rmse_m,ate_xy_rmse_to_map_fit_m,map_fit_heading_rmse_deg,
/// heading_rmse_to_map_fit_deg`.
std::string runs_csv(const std::vector<RunRecord>& runs);

/// A localizer configuration, and its runs averaged over scenarios and seeds.
struct ConfigSummary {
  std::string model;
  int particles = 0;
  int beams = 0;
  int runs = 0;
  int completed = 0;           ///< runs that did not fail
  int succeeded = 0;           ///< converged runs
  double ate_xy_rmse_m = 0.0;  ///< mean over its runs of each run's RMSE
  double heading_rmse_deg = 0.0;
  double time_per_scan_ms = 0.0;
  double time_p95_ms = 0.0;  ///< worst p95 of its runs
  double realtime_factor = 0.0;
  bool pareto = false;  ///< no other configuration is both faster and more accurate
};

/// One summary per (model, particles, beams) over the runs of tracking scenarios (global starts
/// and kidnaps are summarised by start_scenarios_markdown), in the order they first appear;
/// failed runs count as runs that did not succeed and do not enter the means.
std::vector<ConfigSummary> summarize_configs(const std::vector<RunRecord>& runs);

/// Indices of the points on the lower-left Pareto front of (cost, error), ordered by cost: a point
/// is on it when no other point has cost ≤ and error ≤ with one of them strictly smaller.
std::vector<std::size_t> pareto_front(const std::vector<double>& cost,
                                      const std::vector<double>& error);

/// Per global-start and kidnap scenario: success rate, mean time to converge or recover, and the
/// error once converged, per configuration.
std::string start_scenarios_markdown(const std::vector<RunRecord>& runs);

/// The summary.md text: settings, per-configuration table with the Pareto front marked, each
/// model's best configuration, per-scenario results (convergence and recovery times), the
/// robustness tables (robustness_markdown), every run.
std::string summary_markdown(const std::vector<RunRecord>& runs, const std::string& command,
                             const std::vector<std::string>& plots);

/// Error (ATE xy RMSE) against time per scan, log–log, one marker series and one front line per
/// model.
std::string pareto_svg(const std::vector<RunRecord>& runs);

/// Horizontal error over time of the given runs (one series each), for one recording.
std::string error_over_time_svg(const std::vector<RunRecord>& runs, const std::string& title);

}  // namespace conicloc::eval
