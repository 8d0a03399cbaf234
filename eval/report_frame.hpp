#pragma once
// One sampled frame of a localization run for `conicloc report`: the estimate, a subsample of the
// particle cloud, a subsample of the scan's returns per ring and the scan lines the conic sensor
// model predicts at the estimate (the paper's picture: scan lines as conics). Measured and
// predicted returns stay in the sensor's polar form (azimuth, range per ring): the page places
// them with the estimate and the ring geometry, which keeps a frame a few kB.

#include <cstddef>
#include <numbers>
#include <vector>

#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/filter/particle.hpp"
#include "sensor/scan.hpp"

namespace conicloc::eval {

struct ReportFrameLimits {
  std::size_t max_particles = 300;   ///< particles kept per frame (an even subsample)
  std::size_t points_per_ring = 32;  ///< measured returns kept per ring (an even subsample)
  double conic_step_rad = 4.0 * std::numbers::pi / 180.0;  ///< azimuth step of the conics
};

struct ReportFrame {
  double time_s = 0.0;   ///< UTC of the scan's end
  std::size_t scan = 0;  ///< index of the localized scan (0 = first)
  localizer::Pose3 T_map_sensor = localizer::Pose3::Identity();  ///< the estimate
  /// x, y, z, yaw of the kept particles; empty when the particles were not recorded.
  std::vector<localizer::PoseState> particles;
  std::size_t particle_count = 0;  ///< the whole cloud
  /// Per ring: kept measured returns as (azimuth_rad, range_m) pairs, in azimuth order.
  std::vector<std::vector<std::pair<double, double>>> measured;
  /// Per ring: the predicted range at azimuths 0, step, 2·step, … (< 2π); 0 where the model
  /// predicts no return.
  std::vector<std::vector<double>> predicted;
};

/// Every `stride`-th of `count` items, evenly from the first: ⌈count / limit⌉ (1 when limit is 0
/// or count ≤ limit).
std::size_t sampling_stride(std::size_t count, std::size_t limit);

/// The frame of a scan localized at `T_map_sensor`. `particles`: the filter's cloud after the
/// update, or nullptr when it is not available (re-drawn estimates).
ReportFrame make_report_frame(double time_s, std::size_t scan_index,
                              const localizer::Pose3& T_map_sensor, const sensor::Scan& scan,
                              const localizer::ParticleSet* particles,
                              const localizer::ConicScanPredictor& predictor,
                              const ReportFrameLimits& limits = {});

}  // namespace conicloc::eval
