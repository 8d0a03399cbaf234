#pragma once
// What the observation models know of the sensor's ranges, set once for the localizer
// (ObservationConfig::sensor) and handed by each model to the parts that need it: how far the
// sensor sees (beam selection, culling, prediction, segmentation, the mixture's uniform part) and
// how noisy one range is (the hit term's σ, the part of it one surface shares, the inlier gate).

#include <algorithm>
#include <cmath>

#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

/// The error of a range residual: a Gaussian of σ, part of which every return from one surface
/// shares, and the gate within which a residual counts as explained.
struct RangeNoise {
  double sigma_m = 0.05;  ///< range noise plus map error
  /// The part of sigma_m shared by every return from one surface (its map error, the
  /// calibration): sets how many independent terms a scan is worth (correlated_terms.hpp).
  double shared_sigma_m = 0.03;
  double inlier_sigmas = 3.0;  ///< |residual| below this many σ counts as explained

  double inlier_gate_m() const { return inlier_sigmas * sigma_m; }
  /// ρ = σ_s² / σ², the correlation of two returns from one surface, in [0, 1]
  /// (correlated_terms.hpp).
  double shared_error_correlation() const {
    if (!(sigma_m > 0.0)) return 0.0;
    const double ratio = shared_sigma_m / sigma_m;
    return std::clamp(ratio * ratio, 0.0, 1.0);
  }
};

/// `noise` for a pose known only to within a range error `blur_m` (localizer/pose_blur.hpp): σ and
/// its shared part widened to √(σ² + b²). A blur within σ leaves the noise as it is: the
/// likelihood at the particle then already stands for its cell, to O(b²/σ²).
inline RangeNoise with_pose_blur(RangeNoise noise, double blur_m) {
  if (!(blur_m > noise.sigma_m)) return noise;
  noise.sigma_m = std::hypot(noise.sigma_m, blur_m);
  noise.shared_sigma_m = std::hypot(noise.shared_sigma_m, blur_m);
  return noise;
}

/// The sensor's ranges as every observation model sees them.
struct RangeSensor {
  double max_range_m = sensor::kMaxRange_m;  ///< farther surfaces return nothing
  RangeNoise noise;                          ///< of one return's range
};

}  // namespace conicloc::localizer
