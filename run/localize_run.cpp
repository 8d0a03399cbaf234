#include "run/localize_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "io/scan_source.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "localizer/models/observation_factory.hpp"

namespace conicloc::run {

double mean_of(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  return std::accumulate(values.begin(), values.end(), 0.0) / static_cast<double>(values.size());
}

double max_of(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

double LocalizeRunSummary::mean_time_ms() const {
  return mean_of(scan_times_ms);
}

double LocalizeRunSummary::max_time_ms() const {
  return max_of(scan_times_ms);
}

double LocalizeRunSummary::quantile_time_ms(double q) const {
  if (scan_times_ms.empty()) return 0.0;
  std::vector<double> sorted = scan_times_ms;
  // Nearest rank: the smallest time with at least a fraction q of the updates at or below it.
  const auto rank = static_cast<std::size_t>(
      std::ceil(std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size())));
  const std::size_t index = rank == 0 ? 0 : rank - 1;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(index),
                   sorted.end());
  return sorted[index];
}

double LocalizeRunSummary::realtime_factor() const {
  const double total_ms = std::accumulate(scan_times_ms.begin(), scan_times_ms.end(), 0.0);
  if (scans < 2 || total_ms <= 0.0) return 0.0;
  // The first scan's period is not covered by [first, last]: scale to the scans in between.
  const double capture_s =
      (last_time_s - first_time_s) * static_cast<double>(scans) / static_cast<double>(scans - 1);
  return capture_s * 1000.0 / total_ms;
}

FilterStart start_around(const localizer::Pose3& pose, double sigma_x_m, double sigma_y_m,
                         double sigma_yaw_rad) {
  FilterStart start;
  start.pose = pose;
  start.sigma << sigma_x_m, sigma_y_m, 0.02, 0.01, 0.01, sigma_yaw_rad;
  return start;
}

std::optional<localizer::Pose3> odometry_at(const std::vector<io::StampedPose>& odometry,
                                            double time_s) {
  if (odometry.empty() || time_s < odometry.front().time_s || time_s > odometry.back().time_s)
    return std::nullopt;
  const auto after =
      std::lower_bound(odometry.begin(), odometry.end(), time_s,
                       [](const io::StampedPose& p, double t) { return p.time_s < t; });
  if (after == odometry.begin()) return after->pose;
  const auto before = after - 1;
  const double span = after->time_s - before->time_s;
  return localizer::interpolate_pose(before->pose, after->pose,
                                     span > 0 ? (time_s - before->time_s) / span : 0.0);
}

LocalizeRunSummary run_localization(const maps::PlaneMap& map, const LocalizeRunConfig& config,
                                    const ScanCallback& on_scan,
                                    const ScanStateCallback& on_state) {
  // The capture first: a file that cannot be read is reported before any filter work.
  io::ScanSourceOptions source_options;
  source_options.capture.topic = config.topic;
  source_options.capture.ports = {config.stream.data_port, config.stream.position_port};
  source_options.stream = config.stream;
  const auto source = io::open_scan_source(config.pcap_path, config.calibration, source_options);
  return run_localization(map, config, *source, on_scan, on_state);
}

LocalizeRunSummary run_localization(const maps::PlaneMap& map, const LocalizeRunConfig& config,
                                    io::ScanSource& source, const ScanCallback& on_scan,
                                    const ScanStateCallback& on_state) {
  localizer::LocalizerConfig filter_config = config.localizer;
  if (config.two_sided_walls) {
    // One polygon serves both sides of a wall: a wall seen from behind is still a wall.
    for (const auto& model : localizer::observation_models()) {
      if (model.cull_back_faces) model.cull_back_faces(filter_config.observation) = false;
    }
  }
  localizer::Localizer localizer(map, config.calibration, filter_config);
  const auto start_clock = std::chrono::steady_clock::now();
  if (config.start.global) {
    localizer.initialise_global();
    if (localizer.particles().empty()) {
      throw std::runtime_error("no navigable cell with a floor area for a global start");
    }
  } else {
    localizer.initialise(config.start.pose, config.start.sigma);
  }

  std::optional<localizer::Pose3> last_odometry;
  LocalizeRunSummary summary;
  summary.start_time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_clock)
          .count();
  summary.plan_search_bytes = localizer.plan_search_bytes();

  const auto process = [&](const sensor::Scan& scan) {
    if (scan.partial && config.skip_empty_partial && scan.valid_returns() == 0) {
      ++summary.skipped_partial;
      return;
    }
    const double rpm = source.rotation_rpm();
    if (scan.partial && rpm > 0.0 &&
        scan.end_time_s - scan.start_time_s < config.min_partial_fraction * 60.0 / rpm) {
      ++summary.skipped_partial;
      return;
    }
    const double utc_s = scan.end_time_s + source.utc_offset_s().value_or(0.0);
    std::optional<localizer::Pose3> motion;
    if (!config.odometry.empty()) {
      const auto now = odometry_at(config.odometry, utc_s);
      if (now && last_odometry) motion = last_odometry->inverse() * *now;
      last_odometry = now;
    }
    const localizer::UpdateResult result = localizer.update(scan, motion);
    if (summary.scans == 0) summary.first_time_s = utc_s;
    summary.last_time_s = utc_s;
    ++summary.scans;
    summary.scan_times_ms.push_back(result.run_time_ms);
    summary.recoveries += result.recovered ? 1 : 0;
    if (on_scan) on_scan(utc_s, result);
    if (on_state) on_state(utc_s, result, ScanState{scan, localizer.particles()});
  };

  while (const auto scan = source.next()) process(*scan);

  if (const io::VelodyneStream* stream = source.stream()) {
    summary.stream = stream->stats();
    summary.stream_warnings = stream->warnings();
    summary.first_rejections = stream->first_rejections();
  } else {
    summary.point_clouds = true;
  }
  summary.capture = source.counts();
  return summary;
}

}  // namespace conicloc::run
