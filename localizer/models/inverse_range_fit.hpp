#pragma once
// Linear least squares on the conic of one ring and one plane (DESIGN.md "Linear in 1/r"):
//   1/r = a cos θ + b sin θ + c,
// each equation r²(cos θ, sin θ, 1)·(a, b, c) = r weighted by r² so the residual is about the
// range residual in metres. One fit (QR), or, for choosing where to split a scan line, the
// residual of the best fit over any window of a run in O(1) from running sums.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace conicloc::localizer {

/// Fits 1/r = a cos θ + b sin θ + c to the given (θ, r) samples by linear least squares, each
/// equation weighted by r² so the residual is approximately in range metres. False when fewer
/// than 3 samples or the system is singular.
bool fit_inverse_range(const double* azimuth_rad, const double* range_m, std::size_t count,
                       double& a, double& b, double& c);
/// The same from each sample's cos θ and sin θ.
bool fit_inverse_range_trig(const double* cos_azimuth, const double* sin_azimuth,
                            const double* range_m, std::size_t count, double& a, double& b,
                            double& c);

/// The weighted normal equations of a run of samples, accumulated, so that the residual of the
/// best fit over any window [first, end) costs O(1).
class InverseRangeSums {
 public:
  /// Windows shorter than this are summed from their own samples: a difference of running sums
  /// carries the rounding of every earlier sample, and a short window late in a run with far
  /// returns could come out not positive definite.
  static constexpr std::size_t kDirectWindow = 16;

  void build(const std::vector<double>& cos_theta, const std::vector<double>& sin_theta,
             const std::vector<double>& range_m);
  /// Weighted sum of squared residuals (m²) of the best fit over samples [first, end):
  /// y² − bᵀM⁻¹b for the normal equations Mβ = b, through M = LDLᵀ (unit lower L, no pivoting:
  /// M is a Gram matrix), bᵀM⁻¹b = Σ z_i²/d_i with Lz = b. +∞ when M is not positive definite
  /// in rounding: the samples do not fix a conic (too few, or too close in azimuth).
  double sse(std::size_t first, std::size_t end) const;

 private:
  using Terms = Eigen::Matrix<double, 10, 1>;  ///< xxᵀ (6), xᵀy (3), y² (1)
  std::vector<Terms> terms_;                   ///< per sample
  std::vector<Terms> sums_;                    ///< sums_[i] = Σ terms_[0, i)
};

}  // namespace conicloc::localizer
