#include "localizer/models/inverse_range_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::localizer {

bool fit_inverse_range(const double* azimuth_rad, const double* range_m, std::size_t count,
                       double& a, double& b, double& c) {
  std::vector<double> cos_theta(count), sin_theta(count);
  for (std::size_t i = 0; i < count; ++i) {
    cos_theta[i] = std::cos(azimuth_rad[i]);
    sin_theta[i] = std::sin(azimuth_rad[i]);
  }
  return fit_inverse_range_trig(cos_theta.data(), sin_theta.data(), range_m, count, a, b, c);
}

bool fit_inverse_range_trig(const double* cos_azimuth, const double* sin_azimuth,
                            const double* range_m, std::size_t count, double& a, double& b,
                            double& c) {
  if (count < 3) return false;
  Eigen::MatrixX3d rows(static_cast<Eigen::Index>(count), 3);
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(count));
  for (std::size_t i = 0; i < count; ++i) {
    const double r2 = range_m[i] * range_m[i];  // weight: residual of 1/r × r² ≈ range residual
    const auto row = static_cast<Eigen::Index>(i);
    rows(row, 0) = r2 * cos_azimuth[i];
    rows(row, 1) = r2 * sin_azimuth[i];
    rows(row, 2) = r2;
    rhs[row] = range_m[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixX3d> qr(rows);
  if (qr.rank() < 3) return false;
  const Eigen::Vector3d solution = qr.solve(rhs);
  if (!solution.allFinite()) return false;
  a = solution[0];
  b = solution[1];
  c = solution[2];
  return true;
}

void InverseRangeSums::build(const std::vector<double>& cos_theta,
                             const std::vector<double>& sin_theta,
                             const std::vector<double>& range_m) {
  terms_.resize(range_m.size());
  sums_.assign(range_m.size() + 1, Terms::Zero());
  for (std::size_t i = 0; i < range_m.size(); ++i) {
    const double r2 = range_m[i] * range_m[i];
    const double x0 = r2 * cos_theta[i], x1 = r2 * sin_theta[i], x2 = r2;
    const double y = range_m[i];
    terms_[i] << x0 * x0, x0 * x1, x0 * x2, x1 * x1, x1 * x2, x2 * x2, x0 * y, x1 * y, x2 * y,
        y * y;
    sums_[i + 1] = sums_[i] + terms_[i];
  }
}

double InverseRangeSums::sse(std::size_t first, std::size_t end) const {
  Terms s;
  if (end - first < kDirectWindow) {
    s.setZero();
    for (std::size_t i = first; i < end; ++i) s += terms_[i];
  } else {
    s = sums_[end] - sums_[first];
  }
  constexpr double kNotAConic = std::numeric_limits<double>::infinity();
  const double d0 = s[0];
  if (!(d0 > 0.0)) return kNotAConic;
  const double l10 = s[1] / d0, l20 = s[2] / d0;
  const double d1 = s[3] - l10 * s[1];
  if (!(d1 > 0.0)) return kNotAConic;
  const double l21 = (s[4] - l20 * s[1]) / d1;
  const double d2 = s[5] - l20 * s[2] - l21 * l21 * d1;
  if (!(d2 > 0.0)) return kNotAConic;
  const double z0 = s[6], z1 = s[7] - l10 * z0, z2 = s[8] - l20 * z0 - l21 * z1;
  const double value = s[9] - (z0 * z0 / d0 + z1 * z1 / d1 + z2 * z2 / d2);
  return std::isfinite(value) ? std::max(value, 0.0) : kNotAConic;
}

}  // namespace conicloc::localizer
