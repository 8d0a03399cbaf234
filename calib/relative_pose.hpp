#pragma once
// Where a second sensor sits on the carrier, from its returns on the map's planes (issue 20: two
// sensors in one capture). The first sensor's calibration (calibration_solver.hpp) gives every
// chosen scan's pose, the mounting, the carrier's motion within the scan (de-skew) and where the
// planes really stand; the second sensor rides the same carrier, so its return fired at t lands at
//   p_map = T_map_first(t) · T_fs · p_S,  T_map_first(t) = C_k · E_k(t − t_k) · M
// with T_fs = (R, t) the second sensor's pose in the first's frame, T_map_first(t) the first
// sensor's pose at the firing: scan k's carrier pose, its motion through the scan and the
// mounting (calibration_model.hpp; held at the first calibration's values) and p_S the second
// sensor's ray (calibration_model.hpp, its decode calibration uncorrected). Fitted by
// Levenberg–Marquardt on Huber-weighted residuals e = q(c)·(r − r̂) against the associated polygon
// (moved by the first calibration's plane corrections; calibration_model.hpp: the range residual,
// where the noise is, over its standard deviation at the incidence cosine c held at each step,
// return_noise.hpp: this sensor's range noise and surface error, fitted from the second round on),
// re-associated under the same shrinking gates.
//
// Increment: R ← R·exp([δω]×), t ← t + δt (δt in the first sensor's frame), so with
// a = n − s_u·e_u − s_v·e_v the corrected plane's gradient, d the ray's map direction and
// p̂_S = p_S − (r − r̂)·d_S the predicted hit (the point-to-plane Jacobian at p̂, not at the
// measured point), s = sign(a·d):
//   ∂e/∂δt = s·aᵀ·R_k,  ∂e/∂δω = −s·aᵀ·R_k·R·[p̂_S]×,
// R_k the rotation of T_map_first(t). Nothing in it carries the range noise.
// Covariance: Huber's M-estimator's (Σψ²/dof)/ρ·(Σψ'·JJᵀ)⁻¹ over (δt, δω), ρ the share of
// returns within k (calibration_solver.hpp; σ²·(JᵀJ)⁻¹ when all lie within k), plus what the first
// calibration's mounting σ (height, roll, pitch) carries into the fit, then to (x, y, z, roll,
// pitch, yaw) of T_fs by the Jacobian of the Z-Y-X angles. The first sensor's scan poses are held
// as known; its mounting is the larger error (a height off by 1 cm moves the second sensor's z by 1
// cm).
//
// Observability: the covariance's information matrix (Σ ψ'·JJᵀ: a direction only returns beyond
// Huber's k measure counts as unmeasured) scaled to unit diagonal; an eigenvalue under
// ObservabilityConfig::min_scaled_eigenvalue is a direction the returns do not measure (a
// translation along the only corridor seen, every plane parallel to one axis), and each
// parameter with a share of it is flagged with what is missing.

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "calib/calibration_model.hpp"
#include "calib/calibration_solver.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::calib {

/// Parameters of the relative pose, in the order of its covariance.
constexpr int kRelativePoseParameters = 6;  ///< x, y, z (m), roll, pitch, yaw (rad)
using RelativePoseCovariance = Eigen::Matrix<double, 6, 6>;

struct RelativePoseEstimate {
  Eigen::Isometry3d T_first_second = Eigen::Isometry3d::Identity();
  /// Over (x, y, z, roll, pitch, yaw) of T_first_second, Z-Y-X angles (localizer make_pose);
  /// NaN in the rows and columns of what is not observable. It leaves out both sensors' own
  /// laser errors: a common azimuth offset of a sensor's lasers is a turn of that sensor, which
  /// no plane tells apart (σ_ψ/√lasers of yaw each), and the second sensor's lasers are not fitted.
  RelativePoseCovariance covariance = RelativePoseCovariance::Zero();
  std::array<bool, kRelativePoseParameters> observable{};
  std::string missing;  ///< what the returns do not measure, empty when all six are observable
  std::size_t returns = 0;  ///< associated in the last round
  int planes = 0;           ///< polygons with any associated return
  double rms_m = 0.0;       ///< of the associated residuals, unweighted
  double sigma_m = 0.0;     ///< √(Σψ·e/dof), the weighted residual σ (the covariance's is
                            ///< √(Σψ²/dof/ρ), the same when every return lies within k)
  int iterations = 0;
  bool converged = false;

  bool all_observable() const;
};

/// Fits T_first_second from `initial`. `first` is the first sensor's calibration (its poses,
/// mounting and plane corrections; its lasers are not used); `returns` are the second sensor's,
/// each naming its scan in `first.poses` and its firing time from that scan's reference (the
/// first sensor's fitted velocity through the scan carries it);
/// `decode` is the second sensor's calibration. Uses `config`'s gates, iterations, tolerances,
/// Huber width and observability threshold. `height_search_m` > 0: the start's z is known only
/// within ± this (a sensor localized on its own gets its height from the filter's assumption,
/// not from its returns) and is first chosen by a vote of the returns on planes, 2 cm steps.
/// Throws std::invalid_argument when a return names a laser or scan that does not exist, or no
/// return lies on a map plane.
RelativePoseEstimate fit_relative_pose(const maps::PlaneMap& map, const CalibrationResult& first,
                                       const sensor::LaserCalibration& decode,
                                       const std::vector<Return>& returns,
                                       const Eigen::Isometry3d& initial,
                                       const CalibrationConfig& config,
                                       double height_search_m = 0.0);

}  // namespace conicloc::calib
