#include "eval/report_frame.hpp"

#include <cmath>
#include <numbers>

namespace conicloc::eval {

std::size_t sampling_stride(std::size_t count, std::size_t limit) {
  if (limit == 0 || count <= limit) return 1;
  return (count + limit - 1) / limit;
}

ReportFrame make_report_frame(double time_s, std::size_t scan_index,
                              const localizer::Pose3& T_map_sensor, const sensor::Scan& scan,
                              const localizer::ParticleSet* particles,
                              const localizer::ConicScanPredictor& predictor,
                              const ReportFrameLimits& limits) {
  ReportFrame frame;
  frame.time_s = time_s;
  frame.scan = scan_index;
  frame.T_map_sensor = T_map_sensor;
  if (particles != nullptr) {
    frame.particle_count = particles->size();
    const std::size_t stride = sampling_stride(particles->size(), limits.max_particles);
    for (std::size_t i = 0; i < particles->size(); i += stride)
      frame.particles.push_back((*particles)[i].state);
  }

  frame.measured.resize(scan.rings.size());
  for (std::size_t k = 0; k < scan.rings.size(); ++k) {
    std::vector<std::pair<double, double>> valid;
    for (const auto& ret : scan.rings[k].returns) {
      if (ret.status == sensor::ReturnStatus::Valid)
        valid.emplace_back(ret.azimuth_rad, ret.range_m);
    }
    const std::size_t stride = sampling_stride(valid.size(), limits.points_per_ring);
    for (std::size_t i = 0; i < valid.size(); i += stride) frame.measured[k].push_back(valid[i]);
  }

  localizer::PredictedScan predicted;
  predictor.predict(T_map_sensor, predicted);
  std::vector<double> azimuths;
  for (int i = 0; i * limits.conic_step_rad < 2.0 * std::numbers::pi - 1e-12; ++i)
    azimuths.push_back(i * limits.conic_step_rad);
  frame.predicted.resize(predicted.rings.size());
  for (std::size_t k = 0; k < predicted.rings.size(); ++k) {
    auto& ranges = frame.predicted[k];
    ranges.resize(azimuths.size());
    predicted.rings[k].evaluate_sorted(azimuths, ranges);
    for (double& range : ranges) {
      if (!std::isfinite(range)) range = 0.0;
    }
  }
  return frame;
}

}  // namespace conicloc::eval
