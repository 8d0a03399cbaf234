#pragma once
// The sensor's turn between two consecutive scans, measured from the scans themselves: the
// motion estimate of a run without odometry (DESIGN.md "What the filter must guarantee":
// without odometry the motion must be estimated, from the filter's history or from the scan).
// The translation is left to the particles' own velocities, which the scans select among: a
// scan-to-scan translation measured by aligning these profiles, or by point-to-line ICP, sticks
// to its initial guess along a corridor's axis (wall returns with noise-tilted normals anchor
// it) and would claim to know the one thing a corridor does not show.
//
// A turn by ψ about the spin axis turns every ring's scan line by −ψ in azimuth: a point
// seen at θ before is seen at θ − ψ after, so r_now(θ) = r_before(θ + ψ) for every ring. The
// translation between the scans moves near points in azimuth too (a wall 2 m to the side flows
// back by 3° for 0.1 m forward), so the previous scan's points are first seen from where the
// sensor was expected to go (the filter's mean velocity). ψ is the shift that best aligns the
// range profiles of all rings (range_profile.hpp), searched coarse to fine (1° over
// ±max_rotation, 0.25° around the best, a parabola through the three costs at the minimum). It
// is refused where not sharp: too few bins in common, or a second minimum almost as good at
// least 5° away (a symmetric room).

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "localizer/filter/range_profile.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct ScanTurnConfig {
  double max_rotation_rad = 0.6;  ///< ±34°: 6 rad/s at 10 Hz
  double clip = 0.2;              ///< relative range difference counted at most as this
  double min_overlap = 0.25;      ///< share of the bins that must be seen in both scans
  double min_distinctness = 0.1;  ///< second-best turn (≥ 5° away) costs this much more
  double sigma_rad = 0.005;       ///< alignment error of a steady turn (a fraction of a bin)
  /// Scans this far apart are consecutive rotations (300–1200 rpm); over a longer gap the turn
  /// may exceed the search, over a shorter step (a partial scan) a rotation's motion is no speed.
  double min_scan_step_s = 0.03;
  double max_scan_step_s = 0.25;
};

class ScanTurn {
 public:
  /// `threads` workers share the rings and the shifts searched (parallel_for.hpp); the turn is
  /// the same for any count.
  explicit ScanTurn(const ScanTurnConfig& config = {}, int threads = 1)
      : config_(config), threads_(threads) {}

  /// Takes the next scan and the translation expected since the previous one (m, in the previous
  /// scan's sensor frame, planar); returns the turn ψ (rad, counter-clockwise about z) since the
  /// previous scan where it is sharp, nothing for the first scan.
  std::optional<double> update(const sensor::Scan& scan,
                               const Eigen::Vector2d& expected_translation_m);

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
  struct FineTurn {
    int shift_bins = 0;
    double turn_rad = 0.0;
    double cost = std::numeric_limits<double>::infinity();
    std::size_t overlap = 0;
  };
  FineTurn fine_turn(const RangeProfile& now, const RangeProfile& before, int centre_shift) const;

  ScanTurnConfig config_;
  int threads_ = 1;
  RingPoints previous_;
};

}  // namespace conicloc::localizer
