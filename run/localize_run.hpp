#pragma once
// One localization run over a capture: map + capture (+ odometry) in, a pose per scan out. Shared
// by `conicloc localize` (which writes the poses) and `conicloc evaluate --sweep` (which scores
// them).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/capture_source.hpp"
#include "io/scan_source.hpp"
#include "io/tum_trajectory.hpp"
#include "io/velodyne_stream.hpp"
#include "localizer/filter/localizer.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::run {

/// Where the filter starts: around a pose with a std. dev., or globally over the free space.
struct FilterStart {
  bool global = false;
  localizer::Pose3 pose = localizer::Pose3::Identity();   ///< T_map_sensor, when not global
  localizer::Vector6 sigma = localizer::Vector6::Zero();  ///< (x, y, z, roll, pitch, yaw)
};

/// A start around `pose` with these σ of x, y and yaw; z, roll and pitch within what a mounted
/// sensor keeps (2 cm, 0.01 rad).
FilterStart start_around(const localizer::Pose3& pose, double sigma_x_m, double sigma_y_m,
                         double sigma_yaw_rad);

struct LocalizeRunConfig {
  std::string pcap_path;  ///< any capture of io/open_capture.hpp: pcap/pcapng, MCAP, db3, bag
  std::string topic;      ///< bags: the VelodyneScan or PointCloud2 topic ("": the only one)
  sensor::LaserCalibration calibration;
  /// Which sensor of the capture (its data and position ports, its address where several send to
  /// one port: tools/sensor_option.hpp); the default takes port 2368 from any sender.
  io::StreamConfig stream;
  localizer::LocalizerConfig localizer;
  FilterStart start;
  std::vector<io::StampedPose> odometry;  ///< UTC-stamped; empty: the filter's own motion
  bool two_sided_walls = false;           ///< the map serves both sides of a wall with one face
  bool skip_empty_partial = true;         ///< drop partial scans without a single return
  /// A capture's first and last rotations are cut short; one covering less than this fraction
  /// of a rotation holds too little geometry to weigh the cloud (yaw is barely constrained) and
  /// is skipped (0 keeps every partial scan).
  double min_partial_fraction = 0.5;
};

struct LocalizeRunSummary {
  std::size_t scans = 0;
  std::size_t skipped_partial = 0;  ///< empty or shorter than min_partial_fraction
  std::size_t recoveries = 0;
  std::vector<double> scan_times_ms;  ///< wall time of every update, in order
  /// Wall time of the start, before the first scan: a global start builds the plan search's
  /// fields (localizer/filter/plan_search.hpp), of plan_search_bytes.
  double start_time_ms = 0.0;
  std::size_t plan_search_bytes = 0;
  double first_time_s = 0.0;  ///< UTC of the first and last localized scan
  double last_time_s = 0.0;
  bool point_clouds = false;  ///< the scans came from sensor_msgs/PointCloud2 messages
  io::StreamStats stream;     ///< packets only (empty for point clouds)
  std::vector<std::string> stream_warnings;
  std::vector<io::RejectedPacket> first_rejections;
  io::CaptureCounts capture;

  double mean_time_ms() const;
  double max_time_ms() const;
  /// Time per scan at this quantile (0..1) of the updates; 0 without scans.
  double quantile_time_ms(double q) const;
  /// Capture seconds per processing second; 0 when unknown.
  double realtime_factor() const;
};

/// The mean and the largest of `values` (times per scan); 0 for none.
double mean_of(const std::vector<double>& values);
double max_of(const std::vector<double>& values);

/// Called once per localized scan with its UTC time (the scan's end) and the filter's result.
using ScanCallback = std::function<void(double utc_s, const localizer::UpdateResult& result)>;

/// What a run recorder sees of a localized scan besides the result: the scan itself and the
/// filter's particles after the update (read-only, valid during the call).
struct ScanState {
  const sensor::Scan& scan;
  const localizer::ParticleSet& particles;
};
/// Called after the ScanCallback for the same scan.
using ScanStateCallback = std::function<void(double utc_s, const localizer::UpdateResult& result,
                                             const ScanState& state)>;

/// Builds the localizer over `map`, starts it as configured and runs it over the capture. Device
/// times are moved onto the capture's UTC clock (truth and odometry files are stamped in UTC).
/// Throws std::runtime_error when a global start finds no navigable floor.
LocalizeRunSummary run_localization(const maps::PlaneMap& map, const LocalizeRunConfig& config,
                                    const ScanCallback& on_scan = {},
                                    const ScanStateCallback& on_state = {});

/// The same over scans from `source` (a live sensor: io/live_scan_source.hpp) instead of
/// `config.pcap_path`: one per-scan step for files and sensors, so both give the same poses for
/// the same scans.
LocalizeRunSummary run_localization(const maps::PlaneMap& map, const LocalizeRunConfig& config,
                                    io::ScanSource& source, const ScanCallback& on_scan = {},
                                    const ScanStateCallback& on_state = {});

/// Odometry pose at `time_s`, interpolated; nullopt outside the odometry's time span.
std::optional<localizer::Pose3> odometry_at(const std::vector<io::StampedPose>& odometry,
                                            double time_s);

}  // namespace conicloc::run
