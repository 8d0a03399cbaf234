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
//
// With the turn found, the translation is refined the same way, forward then sideways, over
// ±translation_search_m around the expected one, from the rings within ±8° of level (they see
// the door frames, pillars and furniture that a corridor's walls do not pin): the
// scan's own measure of how far the sensor went. It is refused where the cost does not dip at
// the minimum (a featureless corridor along its axis): there the filter's velocities decide.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct ScanRotationConfig {
  double translation_search_m = 0.15;  ///< ± around the expected translation, per axis
  double translation_step_m = 0.015;
  double min_translation_dip = 0.3;    ///< the cost 3 steps away exceeds the minimum by this share
  double translation_sigma_m = 0.02;   ///< error of an accepted translation
  double sigma_rad = 0.005;            ///< alignment error of a steady turn (a fraction of a bin)
  double max_rotation_rad = 0.6;       ///< ±34°: 6 rad/s at 10 Hz
  double clip = 0.2;                   ///< relative range difference counted at most as this
  double min_overlap = 0.25;           ///< share of the bins that must be seen in both scans
  double min_distinctness = 0.1;       ///< second-best minimum (≥ 5° away) costs this much more
};

class ScanRotation {
 public:
  explicit ScanRotation(const ScanRotationConfig& config = {}) : config_(config) {}

  /// What the scans tell of the motion since the previous scan: the turn ψ (rad, counter-clockwise
  /// about z) and the translation (m, planar, in the previous scan's frame), each where sharp.
  struct Motion {
    std::optional<double> turn_rad;
    std::optional<Eigen::Vector2d> translation_m;
  };

  /// Takes the next scan and the translation expected since the previous one (m, in the previous
  /// scan's sensor frame, planar); nothing is measured for the first scan.
  Motion update(const sensor::Scan& scan, const Eigen::Vector2d& translation_m);

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
  struct FineTurn {
    int shift_bins = 0;
    double turn_rad = 0.0;
    double cost = std::numeric_limits<double>::infinity();
    std::size_t overlap = 0;
  };
  FineTurn fine_turn(const Profile& now, const Profile& before, int centre_shift) const;
  /// The translation refined from `expected` along x then y, or nullopt where not sharp.
  std::optional<Eigen::Vector2d> refine_translation(const Points& now_points,
                                                    const Points& before_points,
                                                    const Eigen::Vector2d& expected,
                                                    int shift_bins) const;

  ScanRotationConfig config_;
  Points previous_;
  std::vector<double> elevations_rad_;  ///< of the previous scan's rings
};

}  // namespace conicloc::localizer
