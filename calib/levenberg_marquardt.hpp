#pragma once
// One Levenberg–Marquardt step, shared by the calibration's solvers: solve
//   (H + λ·diag(max(H_ii, 10⁻⁶·max H)))·δ = −g,
// Marquardt's scaled damping floored so a weakly informed entry still gets some; try δ; on a
// cost no higher than the current one keep it and relax λ (÷4), else stiffen λ (×8) and retry.

#include <Eigen/Cholesky>
#include <algorithm>
#include <limits>

namespace conicloc::calib {

struct StepOutcome {
  bool stepped = false;    ///< a step was kept
  bool converged = false;  ///< its size or the cost's fall is below tolerance, or no step helps
};

/// `trial_cost(δ)` gives the cost after δ (+∞ for a step not allowed); `keep(δ)` applies the δ
/// last tried. `lambda` carries over between steps.
template <class Matrix, class Vector, class TrialCost, class Keep>
StepOutcome levenberg_marquardt_step(const Matrix& H, const Vector& g, double current_cost,
                                     double& lambda, const TrialCost& trial_cost, const Keep& keep,
                                     double step_tolerance, double cost_tolerance) {
  while (lambda < 1e10) {
    Matrix A = H;
    const double floor = 1e-6 * H.diagonal().maxCoeff();
    for (Eigen::Index i = 0; i < H.rows(); ++i) A(i, i) += lambda * std::max(H(i, i), floor);
    const Vector delta = A.ldlt().solve(-g);
    const double cost = trial_cost(delta);
    if (cost <= current_cost) {
      keep(delta);
      lambda = std::max(lambda / 4.0, 1e-12);
      return {true, delta.template lpNorm<Eigen::Infinity>() < step_tolerance ||
                        current_cost - cost <= cost_tolerance * current_cost};
    }
    lambda *= 8.0;
  }
  return {false, true};  // no step lowers the cost: at the minimum
}

}  // namespace conicloc::calib
