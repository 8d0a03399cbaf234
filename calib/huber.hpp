#pragma once
// Huber's loss for point-to-plane residuals: quadratic within k, linear beyond, so a return on
// furniture or a person in front of a wall pulls with a bounded force.
//   ρ(e) = e²/2 within k, k|e| − k²/2 beyond; its IRLS weight w(e) = ψ(e)/e with ψ = ρ', and
//   its curvature ψ'(e): 1 within k, 0 beyond (what the M-estimator's covariance needs).

#include <cmath>

namespace conicloc::calib {

inline double huber_cost(double e, double k) {
  return std::abs(e) <= k ? 0.5 * e * e : k * std::abs(e) - 0.5 * k * k;
}

inline double huber_weight(double e, double k) { return std::abs(e) <= k ? 1.0 : k / std::abs(e); }

inline double huber_curvature(double e, double k) {
  return std::abs(e) <= k ? 1.0 : 0.0;
}

}  // namespace conicloc::calib
