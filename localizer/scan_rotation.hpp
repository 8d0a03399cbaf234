#pragma once
// The sensor's turn between two consecutive scans, measured from the scans themselves: the motion
// estimate of a run without odometry (DESIGN.md "What the filter must guarantee": without
// odometry the motion must be estimated, from the filter's history or from the scan).
//
// A turn by ψ about the spin axis turns every ring's scan line by −ψ in azimuth: a point seen at
// θ before is seen at θ − ψ after, so r_now(θ) = r_before(θ + ψ) for every ring. The
// translation between the scans moves near points in azimuth too (a wall 2 m to the side flows
// back by 3° for 0.1 m forward), so the previous scan's points are first moved by the expected
// translation t (the filter's mean velocity): p ← p − t, in its own frame. Then ψ is the shift
// that best aligns the horizontal range profiles of all rings under a robust, clipped cost:
//   ψ* = argmin_ψ  mean over bins b seen in both  min(|r_now(b) − r_before(b + ψ)| / max(r, 1 m), c).
// Searched coarse to fine (1° over ±max_rotation, then 0.25° around the best, then a parabola
// through the three costs around the minimum). The estimate is refused where it is not sharp:
// too few bins in common, or a second minimum almost as good at least 5° away (a symmetric room).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct ScanRotationConfig {
  double sigma_rad = 0.005;            ///< alignment error of a steady turn (a fraction of a bin)
  double max_rotation_rad = 0.6;       ///< ±34°: 6 rad/s at 10 Hz
  double clip = 0.2;                   ///< relative range difference counted at most as this
  double min_overlap = 0.25;           ///< share of the bins that must be seen in both scans
  double min_distinctness = 0.1;       ///< second-best minimum (≥ 5° away) costs this much more
};

class ScanRotation {
 public:
  explicit ScanRotation(const ScanRotationConfig& config = {}) : config_(config) {}

  /// Takes the next scan and the translation expected since the previous one (m, in the previous
  /// scan's sensor frame, planar); returns the turn ψ (rad, counter-clockwise about z) relative to
  /// the previous scan, or nullopt for the first scan or where the estimate is not sharp.
  std::optional<double> update(const sensor::Scan& scan, const Eigen::Vector2d& translation_m);

  /// The turn between the two scans' end times, from the last two turns measured. Aligning whole
  /// rotations measures the turn between the scans' middles, half a scan late: extrapolated by
  /// half the change since the previous turn, ψ_end ≈ ψ_k + (ψ_k − ψ_(k−1))/2, with the std. dev.
  /// sigma_rad + |ψ_k − ψ_(k−1)|/2 (the turn rate may change anywhere in between).
  struct Turn {
    double yaw_rad = 0.0;
    double sigma_rad = 0.0;
  };
  static Turn end_to_end(double turn_rad, std::optional<double> previous_turn_rad,
                         double sigma_rad);

  void reset() { previous_.clear(); }

 private:
  /// Per ring, the horizontal sensor-frame points of its valid returns.
  using Points = std::vector<std::vector<Eigen::Vector2d>>;
  /// Per ring, the mean horizontal range of each 0.25° azimuth bin (0: no return there).
  using Profile = std::vector<std::vector<float>>;
  static Points points_of(const sensor::Scan& scan);
  static Profile profile_of(const Points& points, const Eigen::Vector2d& offset);
  double cost(const Profile& now, const Profile& before, int shift_bins, int stride,
              std::size_t& overlap) const;

  ScanRotationConfig config_;
  Points previous_;
};

}  // namespace conicloc::localizer
