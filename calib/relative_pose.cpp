#include "calib/relative_pose.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "calib/huber.hpp"
#include "calib/levenberg_marquardt.hpp"
#include "calib/plane_association.hpp"
#include "calib/return_noise.hpp"
#include "localizer/conic/pose.hpp"
#include "maps/plane_index.hpp"

namespace conicloc::calib {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Which way each parameter moves, for the message of what is missing.
constexpr std::array<const char*, kRelativePoseParameters> kNames = {"x", "y", "z",
                                                                      "roll", "pitch", "yaw"};
// A parameter with at least this share (squared component) of an unmeasured direction is
// flagged: a direction shared by two parameters flags both.
constexpr double kFlaggedShare = 0.1;

Eigen::Isometry3d moved(const Eigen::Isometry3d& T, const Vector6& delta) {
  Eigen::Isometry3d out = T;
  out.translation() += delta.head<3>();
  const double angle = delta.tail<3>().norm();
  if (angle > 0.0) {
    out.linear() =
        T.linear() * Eigen::AngleAxisd(angle, delta.tail<3>() / angle).toRotationMatrix();
  }
  return out;
}

struct Problem {
  const maps::PlaneMap& map;
  const std::vector<Return>& returns;
  std::vector<Eigen::Vector3d> sensor_points;   ///< p_S per return
  std::vector<Eigen::Vector3d> laser_origins;   ///< (0, 0, o) of its laser, sensor frame
  std::vector<Eigen::Isometry3d> map_from_fire;  ///< the first's T_map_sensor at each firing
  std::vector<PlaneCorrection> correction;       ///< per polygon (zero where not adjusted)
  std::vector<int> plane;                        ///< associated polygon per return, −1: none
  double huber_m = 0.05;
  double edge_margin_m = 0.0;

  Eigen::Vector3d map_point(const Eigen::Isometry3d& T, std::size_t i) const {
    return map_from_fire[i] * (T * sensor_points[i]);
  }
  Eigen::Vector3d map_origin(const Eigen::Isometry3d& T, std::size_t i) const {
    return map_from_fire[i] * (T * laser_origins[i]);
  }
  double range_e(const Eigen::Isometry3d& T, std::size_t i) const {
    return range_residual(map.polygons[plane[i]], correction[plane[i]], map_origin(T, i),
                          map_point(T, i));
  }
  // The incidence cosines c and the residuals' scales q(c) (return_noise.hpp), held through a
  // step (calibration_solver.cpp: the cost a step is judged by and its gradient agree; at
  // convergence Σ q²·J·(r − r̂) = 0).
  std::vector<double> cosines;
  std::vector<double> scales;
  ReturnNoise noise;  ///< this sensor's, fitted each round from the second on; none (q = c) before
  void hold_cosines(const Eigen::Isometry3d& T) {
    cosines.assign(plane.size(), 0.0);
    scales.assign(plane.size(), 0.0);
    for (std::size_t i = 0; i < plane.size(); ++i) {
      if (plane[i] < 0) continue;
      cosines[i] = incidence_cosine(map.polygons[plane[i]], correction[plane[i]],
                                    map_origin(T, i), map_point(T, i));
      scales[i] = noise.residual_scale(cosines[i]);
    }
  }
  // σ_r and σ_s of this sensor's returns from their residuals at `T` (return_noise.hpp).
  void fit_noise(const Eigen::Isometry3d& T, const ReturnNoiseConfig& config) {
    hold_cosines(T);
    std::vector<double> residual, cosine;
    for (std::size_t i = 0; i < plane.size(); ++i) {
      if (plane[i] < 0) continue;
      residual.push_back(range_e(T, i));
      cosine.push_back(cosines[i]);
    }
    noise = fit_return_noise(residual, cosine, config);
    for (std::size_t i = 0; i < plane.size(); ++i)
      if (plane[i] >= 0) scales[i] = noise.residual_scale(cosines[i]);
  }
  // The fitted residual q(c)·(r − r̂) (calibration_model.hpp).
  double residual(const Eigen::Isometry3d& T, std::size_t i) const {
    return scales[i] * range_e(T, i);
  }
  double cost(const Eigen::Isometry3d& T) const {
    double total = 0.0;
    for (std::size_t i = 0; i < plane.size(); ++i) {
      if (plane[i] >= 0) total += huber_cost(residual(T, i), huber_m);
    }
    return total;
  }
  // ∂e/∂(δt, δω) of an associated return, q held (module comment).
  Vector6 jacobian(const Eigen::Isometry3d& T, std::size_t i) const {
    const Eigen::Vector3d a = corrected_normal(map.polygons[plane[i]], correction[plane[i]]);
    const Eigen::Vector3d d_sensor = (sensor_points[i] - laser_origins[i]).normalized();
    const Eigen::Vector3d predicted = sensor_points[i] - range_e(T, i) * d_sensor;  // p̂_S
    const Eigen::RowVector3d aR = a.transpose() * map_from_fire[i].linear();
    const double scale = scales[i] / aR.dot(T.linear() * d_sensor);
    Vector6 J;
    J.head<3>() = scale * aR.transpose();
    J.tail<3>() = -scale * (aR * T.linear() * localizer::hat(predicted)).transpose();
    return J;
  }
  // H = Σ h·JᵀJ, b = Σ w·Jᵀe (module comment) with w = ψ(e)/e, and the sums behind σ and the
  // rms. h is the fit's weight w, or (for the covariance) the curvature ψ'(e) of the cost the fit
  // minimises: 0 beyond Huber's k, where a return pulls with a constant force and holds nothing
  // (calibration_solver.cpp).
  enum class HessianWeight { Fit, Curvature };
  struct Sums {
    Matrix6 H = Matrix6::Zero();
    Vector6 b = Vector6::Zero();
    HuberSums residuals;
  };
  Sums normal_sums(const Eigen::Isometry3d& T, HessianWeight weight) const {
    Sums sums;
    for (std::size_t i = 0; i < plane.size(); ++i) {
      if (plane[i] < 0) continue;
      const double e = residual(T, i);
      const Vector6 J = jacobian(T, i);
      const double w = huber_weight(e, huber_m);
      const double h = weight == HessianWeight::Fit ? w : huber_curvature(e, huber_m);
      sums.H.noalias() += h * J * J.transpose();
      sums.b.noalias() += w * J * e;
      sums.residuals.add(e, huber_m);
    }
    return sums;
  }
};

void associate(Problem& problem, const Eigen::Isometry3d& T, const maps::PlaneIndex& index,
               double gate_m) {
  for (std::size_t i = 0; i < problem.returns.size(); ++i) {
    const Eigen::Vector3d origin = problem.map_from_fire[i] * (T * problem.laser_origins[i]);
    problem.plane[i] = associated_polygon(problem.map, index, origin, problem.map_point(T, i),
                                          gate_m, problem.edge_margin_m);
  }
}

// What the first sensor's mounting error does to the fit: the solution of Σ ψ(e)·J = 0 moves by
// S·Δm, S = −H⁻¹·Σ ψ'(e)·J·(∂e/∂m)ᵀ over its height, roll and pitch (central differences; H the
// curvature's, fit_relative_pose), so its covariance adds S·diag(σ_m²)·Sᵀ. The scans' planar
// poses, known better, are held.
Matrix6 mounting_covariance(const Problem& problem, const CalibrationResult& first,
                            const Eigen::Isometry3d& T, const Matrix6& H) {
  constexpr double kStep = 1e-6;
  using Sensitivity = Eigen::Matrix<double, 6, kMountParameters>;
  Sensitivity C = Sensitivity::Zero();
  for (std::size_t i = 0; i < problem.plane.size(); ++i) {
    if (problem.plane[i] < 0) continue;
    const Return& ret = problem.returns[i];
    const Eigen::Vector3d p_first = T * problem.sensor_points[i];
    const Eigen::Vector3d o_first = T * problem.laser_origins[i];
    const maps::PlanarPolygon& polygon = problem.map.polygons[problem.plane[i]];
    const PlaneCorrection& c = problem.correction[problem.plane[i]];
    const ScanPose& pose = first.poses[ret.scan];
    const double scale = problem.scales[i];  // held, as in the fit
    const auto residual = [&](const Mounting& m) {
      const Eigen::Isometry3d T_map_first = map_from_fire(m, pose, ret.time_s);
      return scale * range_residual(polygon, c, T_map_first * o_first, T_map_first * p_first);
    };
    Eigen::Matrix<double, kMountParameters, 1> de;
    for (int j = 0; j < kMountParameters; ++j) {
      Mounting plus = first.mounting, minus = first.mounting;
      double* const plus_value[] = {&plus.height_m, &plus.roll_rad, &plus.pitch_rad};
      double* const minus_value[] = {&minus.height_m, &minus.roll_rad, &minus.pitch_rad};
      *plus_value[j] += kStep;
      *minus_value[j] -= kStep;
      de(j) = (residual(plus) - residual(minus)) / (2.0 * kStep);
    }
    C.noalias() += huber_curvature(problem.residual(T, i), problem.huber_m) *
                   problem.jacobian(T, i) * de.transpose();
  }
  const Sensitivity S = -H.ldlt().solve(C);
  const Eigen::Vector3d sigma(first.mounting_sigma[0], first.mounting_sigma[1],
                              first.mounting_sigma[2]);
  return S * sigma.cwiseAbs2().asDiagonal() * S.transpose();
}

// Σ over (δt, δω) → over (x, y, z, roll, pitch, yaw): x, y, z move as δt; the angles of
// R·exp([δω]×) by their central-difference Jacobian.
Matrix6 pose_covariance(const Eigen::Isometry3d& T, const Matrix6& increment_covariance) {
  constexpr double kStep = 1e-6;
  Matrix6 E = Matrix6::Zero();
  E.topLeftCorner<3, 3>().setIdentity();
  for (int j = 0; j < 3; ++j) {
    Vector6 step = Vector6::Zero();
    step(3 + j) = kStep;
    const auto plus = localizer::roll_pitch_yaw(moved(T, step).linear());
    const auto minus = localizer::roll_pitch_yaw(moved(T, -step).linear());
    E(3, 3 + j) = localizer::angle_difference(plus.roll, minus.roll) / (2.0 * kStep);
    E(4, 3 + j) = localizer::angle_difference(plus.pitch, minus.pitch) / (2.0 * kStep);
    E(5, 3 + j) = localizer::angle_difference(plus.yaw, minus.yaw) / (2.0 * kStep);
  }
  return E * increment_covariance * E.transpose();
}

// The directions of (δt, δω) the returns do not measure: eigenvalues of the unit-diagonal
// information under the threshold; a parameter holding kFlaggedShare of one is not observable.
void judge_observability(const Matrix6& H, double min_scaled_eigenvalue,
                         RelativePoseEstimate& out) {
  out.observable.fill(true);
  const Vector6 diagonal = H.diagonal();
  if ((diagonal.array() <= 0.0).any()) {
    for (int i = 0; i < kRelativePoseParameters; ++i) out.observable[i] = diagonal(i) > 0.0;
  } else {
    const Vector6 scale = diagonal.cwiseSqrt().cwiseInverse();
    const Matrix6 scaled = scale.asDiagonal() * H * scale.asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Matrix6> eigen(scaled);
    for (int k = 0; k < kRelativePoseParameters; ++k) {
      if (eigen.eigenvalues()(k) >= min_scaled_eigenvalue) continue;
      for (int i = 0; i < kRelativePoseParameters; ++i) {
        if (eigen.eigenvectors()(i, k) * eigen.eigenvectors()(i, k) >= kFlaggedShare) {
          out.observable[i] = false;
        }
      }
    }
  }
  out.missing.clear();
  for (int i = 0; i < kRelativePoseParameters; ++i) {
    if (out.observable[i]) continue;
    out.missing += out.missing.empty() ? "" : ", ";
    out.missing += kNames[i];
  }
  if (!out.missing.empty()) {
    out.missing = "not measured by the planes seen (too few directions): " + out.missing;
  }
}

// The start moved along the first sensor's z by the offset within ±span (2 cm steps) at which
// the most of ~5,000 returns lie on a plane (within the Huber width of it, under the last
// gate): a robust vote that the shrinking gates alone cannot make from decimetres off.
Eigen::Isometry3d search_height(Problem& problem, const maps::PlaneIndex& index,
                                const Eigen::Isometry3d& initial, double span_m,
                                const CalibrationConfig& config) {
  constexpr double kStepM = 0.02;
  constexpr std::size_t kVoters = 5000;
  const std::size_t stride = std::max<std::size_t>(1, problem.returns.size() / kVoters);
  const double gate_m = config.gates_m.back();
  Eigen::Isometry3d best = initial;
  std::size_t best_votes = 0;
  const int steps = static_cast<int>(std::floor(span_m / kStepM));
  // 0, +1, −1, +2, −2, …: of offsets with as many votes, the one nearest the start wins.
  for (int n = 0; n <= 2 * steps; ++n) {
    const int k = n % 2 == 1 ? (n + 1) / 2 : -(n / 2);
    Eigen::Isometry3d T = initial;
    T.translation().z() += k * kStepM;
    std::size_t votes = 0;
    for (std::size_t i = 0; i < problem.returns.size(); i += stride) {
      const Eigen::Vector3d point = problem.map_point(T, i);
      const int j = associated_polygon(problem.map, index, problem.map_origin(T, i), point, gate_m,
                                       problem.edge_margin_m);
      votes += j >= 0 && std::abs(corrected_distance(problem.map.polygons[j], problem.correction[j],
                                                     point)) <= problem.huber_m;
    }
    if (votes > best_votes) {
      best_votes = votes;
      best = T;
    }
  }
  return best;
}

}  // namespace

bool RelativePoseEstimate::all_observable() const {
  for (const bool b : observable) {
    if (!b) return false;
  }
  return true;
}

RelativePoseEstimate fit_relative_pose(const maps::PlaneMap& map, const CalibrationResult& first,
                                       const sensor::LaserCalibration& decode,
                                       const std::vector<Return>& returns,
                                       const Eigen::Isometry3d& initial,
                                       const CalibrationConfig& config, double height_search_m) {
  if (config.gates_m.empty()) throw std::invalid_argument("fit_relative_pose: no association gate");
  Problem problem{map, returns, {}, {}, {}, {}, {}, config.huber_m, config.edge_margin_m,
                  {},  {},      {}};
  problem.correction.assign(map.polygons.size(), PlaneCorrection{});
  for (const PlaneEstimate& plane : first.planes) {
    problem.correction[plane.polygon] = plane.correction;
  }
  for (std::size_t i = 0; i < returns.size(); ++i) {
    const Return& ret = returns[i];
    if (ret.laser < 0 || ret.laser >= static_cast<int>(decode.lasers.size()) || ret.scan < 0 ||
        ret.scan >= static_cast<int>(first.poses.size())) {
      throw std::invalid_argument("fit_relative_pose: return " + std::to_string(i) +
                                  " names laser " + std::to_string(ret.laser) + " of " +
                                  std::to_string(decode.lasers.size()) + ", scan " +
                                  std::to_string(ret.scan) + " of " +
                                  std::to_string(first.poses.size()));
    }
    const sensor::Laser& laser = decode.lasers[ret.laser];
    problem.sensor_points.push_back(sensor_point(laser, {}, ret.azimuth_rad, ret.range_m));
    problem.laser_origins.push_back(laser_origin(laser, {}));
    problem.map_from_fire.push_back(
        map_from_fire(first.mounting, first.poses[ret.scan], ret.time_s));
  }
  problem.plane.assign(returns.size(), -1);

  const maps::PlaneIndex index(map);
  RelativePoseEstimate out;
  Eigen::Isometry3d T = initial;
  if (height_search_m > 0.0) T = search_height(problem, index, initial, height_search_m, config);
  for (std::size_t round = 0; round < config.gates_m.size() + config.max_extra_rounds; ++round) {
    const double gate_m = config.gates_m[std::min(round, config.gates_m.size() - 1)];
    const std::vector<int> previous = problem.plane;
    // Returns by objects the map lacks are not left out here (unmapped_objects.hpp): this fit
    // leaves the second sensor's lasers as decoded, and their errors run along whole scan lines
    // (left out, 2.7 % of the returns and the roll and pitch further off).
    associate(problem, T, index, gate_m);
    if (round >= config.gates_m.size() && problem.plane == previous) break;
    // From the second round: the first round's residuals are the start's errors.
    if (round > 0) problem.fit_noise(T, config.return_noise);
    double lambda = 1e-6;
    out.converged = false;
    for (int iteration = 0; iteration < config.max_iterations; ++iteration) {
      problem.hold_cosines(T);
      const Problem::Sums sums = problem.normal_sums(T, Problem::HessianWeight::Fit);
      if (sums.residuals.count == 0)
        throw std::invalid_argument("fit_relative_pose: no return lies on a plane");
      const StepOutcome step = levenberg_marquardt_step(
          sums.H, sums.b, problem.cost(T), lambda,
          [&](const Vector6& delta) { return problem.cost(moved(T, delta)); },
          [&](const Vector6& delta) { T = moved(T, delta); }, config.step_tolerance,
          config.cost_tolerance);
      ++out.iterations;
      out.converged = step.converged;
      if (out.converged) break;
    }
  }

  problem.hold_cosines(T);
  const Problem::Sums sums = problem.normal_sums(T, Problem::HessianWeight::Curvature);
  if (sums.residuals.count == 0)
    throw std::invalid_argument("fit_relative_pose: no return lies on a plane");
  const double dof =
      std::max(1.0, static_cast<double>(sums.residuals.count) - kRelativePoseParameters);
  out.T_first_second = T;
  out.returns = sums.residuals.count;
  out.rms_m = sums.residuals.rms();
  out.sigma_m = sums.residuals.sigma(dof);
  std::vector<bool> seen(map.polygons.size(), false);
  for (const int p : problem.plane) {
    if (p >= 0 && !seen[p]) {
      seen[p] = true;
      ++out.planes;
    }
  }
  judge_observability(sums.H, config.observability.min_scaled_eigenvalue, out);
  // Huber's M-estimator covariance (HuberSums::model_scale): (Σψ²/dof)/ρ · H⁻¹, H = Σ ψ'·JJᵀ.
  const Matrix6 increment_covariance =
      sums.H.ldlt().solve(Matrix6::Identity()) * sums.residuals.model_scale(dof) +
      mounting_covariance(problem, first, T, sums.H);
  out.covariance = pose_covariance(T, increment_covariance);
  // What the returns do not measure has no variance to give: H is singular there.
  for (int i = 0; i < kRelativePoseParameters; ++i) {
    if (out.observable[i]) continue;
    out.covariance.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
    out.covariance.col(i).setConstant(std::numeric_limits<double>::quiet_NaN());
  }
  return out;
}

}  // namespace conicloc::calib
