#pragma once
// Huber's loss for point-to-plane residuals: quadratic within k, linear beyond, so a return on
// furniture or a person in front of a wall pulls with a bounded force.
//   ρ(e) = e²/2 within k, k|e| − k²/2 beyond; its IRLS weight w(e) = ψ(e)/e with ψ = ρ', and
//   its curvature ψ'(e): 1 within k, 0 beyond (what the M-estimator's covariance needs).

#include <cmath>
#include <cstddef>

namespace conicloc::calib {

inline double huber_cost(double e, double k) {
  return std::abs(e) <= k ? 0.5 * e * e : k * std::abs(e) - 0.5 * k * k;
}

inline double huber_weight(double e, double k) { return std::abs(e) <= k ? 1.0 : k / std::abs(e); }

inline double huber_curvature(double e, double k) {
  return std::abs(e) <= k ? 1.0 : 0.0;
}

// The scalar sums of a Huber fit's residuals behind its σ, its rms and Huber's M-estimator
// covariance, (Eψ²/(Eψ')²)·(JᵀJ)⁻¹: with H = Σψ'·JJᵀ ≈ ρ·ΣJJᵀ, ρ = Σψ'/n the share within k,
//   Σ = model_scale(dof)·H⁻¹,  model_scale = (Σψ²/dof)/ρ   (σ² when every return lies within k).
struct HuberSums {
  double weighted_sq = 0.0;  ///< Σ ψ(e)·e
  double sq = 0.0;           ///< Σ e²
  double psi_sq = 0.0;       ///< Σ ψ(e)²
  double within = 0.0;       ///< Σ ψ'(e): the returns within k
  std::size_t count = 0;

  void add(double e, double k) {
    const double psi = huber_weight(e, k) * e;
    weighted_sq += psi * e;
    sq += e * e;
    psi_sq += psi * psi;
    within += huber_curvature(e, k);
    ++count;
  }
  HuberSums& operator+=(const HuberSums& other) {
    weighted_sq += other.weighted_sq;
    sq += other.sq;
    psi_sq += other.psi_sq;
    within += other.within;
    count += other.count;
    return *this;
  }
  /// σ = √(Σψ·e/dof), the residuals' scale as the fit weighs them.
  double sigma(double dof) const { return std::sqrt(weighted_sq / dof); }
  double rms() const { return count > 0 ? std::sqrt(sq / static_cast<double>(count)) : 0.0; }
  double model_scale(double dof) const {
    const double within_share =
        count > 0 && within > 0.0 ? within / static_cast<double>(count) : 1.0;
    return psi_sq / dof / within_share;
  }
};

}  // namespace conicloc::calib
