#pragma once
// The pose a map gives a scan: where the map's planes best fit, in least squares, what a sensor at
// the true pose sees of the real walls. With map errors (map_errors.hpp) the real walls stand off
// the model's, and a localizer that trusts the model is pulled off the truth with them. This pose
// is a reference for that pull, not a bound: it weighs every return alike, and a localizer that
// weighs surfaces otherwise lands elsewhere within the map's error. Its error against the truth
// is the map's share, a localizer's error against it the localizer's own (the sweep's map-fit
// columns).

#include <cmath>
#include <span>
#include <vector>

#include "io/tum_trajectory.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"
#include "sim/world.hpp"

namespace conicloc::sim {

struct MapFitConfig {
  double azimuth_step_rad = M_PI / 180.0;  ///< between the cast rays of one laser
  double min_range_m = 0.3;                ///< as the simulated sensor (SensorConfig)
  double max_range_m = sensor::kMaxRange_m;
  int iterations = 8;  ///< Gauss–Newton steps; the fit converges in 2–3 from the truth
  /// Directions of the correction whose information is below this share of the largest (the
  /// rotation scaled by the returns' RMS range) are left at the truth: the returns do not fix
  /// them (along a corridor whose end walls are out of sight).
  double min_information_ratio = 1e-6;
  int threads = 1;  ///< poses fitted at once; the result does not depend on it
};

/// For each `truth` pose T (T_map_sensor), the pose T·Δ minimising Σ_i (n_k·(T·Δ·p_i) + d_k)², p_i
/// the returns (sensor frame) of rays cast from T into `world` at the elevations of `calibration`
/// every azimuth step, each on the map plane n_k·x + d_k = 0 of the surface it hit: world polygon k
/// is `map` polygon k moved by the map error; returns from clutter and people, which the map does
/// not hold, are left out. Each Gauss–Newton step Δ = (R(ω), v), ω a rotation vector and v a
/// translation in the sensor frame (exp(ξ) to first order), with the association fixed: r_i =
/// n_k·q_i + d_k, q_i = T·p_i, and ∂r_i/∂ω = p_i × m_i, ∂r_i/∂v = m_i, m_i = Rᵀn_k. Without map
/// error every residual is 0 at the truth and the truth is returned; so is it where no map surface
/// is in sight.
std::vector<io::StampedPose> map_fit_poses(const maps::PlaneMap& map, const World& world,
                                           const sensor::LaserCalibration& calibration,
                                           std::span<const io::StampedPose> truth,
                                           const MapFitConfig& config = {});

}  // namespace conicloc::sim
