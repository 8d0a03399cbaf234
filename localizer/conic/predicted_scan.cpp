#include "localizer/conic/predicted_scan.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "localizer/conic/conic_ranges.hpp"

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

void AzimuthSamples::assign(std::span<const double> sorted_azimuths_rad) {
  azimuth_rad.assign(sorted_azimuths_rad.begin(), sorted_azimuths_rad.end());
  cos_azimuth.resize(azimuth_rad.size());
  sin_azimuth.resize(azimuth_rad.size());
  for (std::size_t i = 0; i < azimuth_rad.size(); ++i) {
    cos_azimuth[i] = std::cos(azimuth_rad[i]);
    sin_azimuth[i] = std::sin(azimuth_rad[i]);
  }
}

void PredictedRing::clear() {
  boundary_rad.clear();
  a.clear();
  b.clear();
  c.clear();
  polygon.clear();
  boundary_rad.push_back(0.0);
}

void PredictedRing::append(double end_rad, double a_piece, double b_piece, double c_piece,
                           int polygon_piece) {
  if (!polygon.empty() && polygon.back() == polygon_piece && a.back() == a_piece &&
      b.back() == b_piece && c.back() == c_piece) {
    boundary_rad.back() = end_rad;
    return;
  }
  a.push_back(a_piece);
  b.push_back(b_piece);
  c.push_back(c_piece);
  polygon.push_back(polygon_piece);
  boundary_rad.push_back(end_rad);
}

std::size_t PredictedRing::piece_at(double azimuth_rad) const {
  double theta = std::fmod(azimuth_rad, kTwoPi);
  if (theta < 0.0) theta += kTwoPi;
  // Last boundary ≤ θ; pieces are [b_i, b_{i+1}).
  const auto it = std::upper_bound(boundary_rad.begin(), boundary_rad.end(), theta);
  const std::size_t index = static_cast<std::size_t>(it - boundary_rad.begin());
  return std::min(index == 0 ? 0 : index - 1, piece_count() == 0 ? 0 : piece_count() - 1);
}

double PredictedRing::range(double azimuth_rad) const {
  if (piece_count() == 0) return kNoReturn;
  const std::size_t i = piece_at(azimuth_rad);
  const double inverse = a[i] * std::cos(azimuth_rad) + b[i] * std::sin(azimuth_rad) + c[i];
  return range_from_inverse(inverse, min_inverse_range, max_inverse_range);
}

void PredictedRing::evaluate_sorted(std::span<const double> azimuths_rad,
                                    std::span<double> ranges_out) const {
  assert(azimuths_rad.size() == ranges_out.size());
  const std::size_t pieces = piece_count();
  std::size_t p = 0;
  for (std::size_t i = 0; i < azimuths_rad.size(); ++i) {
    const double theta = azimuths_rad[i];
    while (p + 1 < pieces && theta >= boundary_rad[p + 1]) ++p;
    if (pieces == 0) {
      ranges_out[i] = kNoReturn;
      continue;
    }
    const double inverse = a[p] * std::cos(theta) + b[p] * std::sin(theta) + c[p];
    ranges_out[i] = range_from_inverse(inverse, min_inverse_range, max_inverse_range);
  }
}

void PredictedRing::evaluate_sorted(const AzimuthSamples& samples,
                                    std::span<double> ranges_out) const {
  assert(samples.size() == ranges_out.size());
  const std::size_t pieces = piece_count();
  const std::size_t n = samples.size();
  if (pieces == 0) {
    std::fill(ranges_out.begin(), ranges_out.end(), kNoReturn);
    return;
  }
  const double* azimuth = samples.azimuth_rad.data();
  const double* cos_az = samples.cos_azimuth.data();
  const double* sin_az = samples.sin_azimuth.data();
  double* out = ranges_out.data();
  std::size_t i = 0;
  // Merge walk: for each piece, the run of samples before its end boundary, evaluated together.
  for (std::size_t p = 0; p < pieces && i < n; ++p) {
    const double end = p + 1 < pieces ? boundary_rad[p + 1] : std::numeric_limits<double>::max();
    std::size_t j = i;
    while (j < n && azimuth[j] < end) ++j;
    conic_ranges(a[p], b[p], c[p], cos_az + i, sin_az + i, j - i, min_inverse_range,
                 max_inverse_range, out + i);
    i = j;
  }
}

}  // namespace conicloc::localizer
