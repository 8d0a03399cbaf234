#pragma once
// Where a segment's polygon ends on the scan line, and how that end moves with the pose.
//
// conic-segment compares each measured segment with its polygon's plane only. A plane says
// nothing of a motion within it: along a corridor, every side wall has the same conic at any x,
// and the position along it was fixed by the few segments on end walls and jamb faces (a per-scan
// σ of 13–15 cm in the generated corridor of seed 2, against 3.5 cm for conic-beam, which sees
// where each ring passes from one surface to the next). The polygon's bounds carry that
// information: a particle too far along the corridor sees the wall end before the measured
// segment does, and the returns past that end are ones the wall does not explain.
//
// So each (segment, candidate) term keeps the ends of the candidate's arc on the segment's ring
// as the cell's centre predicts them (the arc: contiguous pieces of the candidate's surface, so a
// wall split into coplanar polygons is one arc), each with the rate at which its azimuth moves
// with the pose (boundary_motion.hpp): δθ = rate·(δt, δω). A particle moves each end, and the
// segment's returns beyond it are scored as returns the map does not explain (the mixture's
// floor) instead of on the plane. Returns are about evenly spaced in azimuth, so the count beyond
// an end at θ_e, of a segment whose last return is at θ_s, with spacing Δ, is the step function
// ⌊(θ_s − θ_e)/Δ⌋ + 1 (for θ_e ≤ θ_s), of which
//   beyond = max(0, (θ_s − θ_e)/Δ + ½)
// is the continuous mean: the likelihood stays continuous in the pose. A segment shorter than its
// arc (occluded by clutter, or past the range limits) is never penalised: only what it holds
// beyond the arc counts, and the returns on the other side of the edge, in the neighbouring
// segment, are held to that segment's own arc.
//
// Ends that no edge explains (boundary_motion's nullopt), or that lie more than kMaxReach_rad
// from the segment's outermost return, do not bound it: beyond it, they never bind; inside it,
// the segment runs past its polygon by more than 0.2 rad and lies mostly on another surface,
// which its plane's rms difference already says. Nor do ends whose first-order motion cannot be
// trusted over the cell: the neglected second-order term of an edge's azimuth is about the square
// of its shift (boundary_motion.hpp), and an end is kept only where that stays below
// kMaxCornerError_returns return spacings at the cell's corners, s_max² / Δ ≤ 4 with
// s_max = |∂θ/∂δt|·(half diagonal) + |∂θ/∂δω|₁·(half angle): below one spacing over the inner
// half of the cell. That drops the edges nearest the sensor, where the cell's centre sees a scene
// unlike its corners' (a vertical edge within about 2.2 m with the VLP-16's 0.2° spacing and the
// default 25 cm, 2° cells; a floor line the ring meets near tangency at any distance). FJK-Haus,
// seed 4, showed why: a jamb 0.4 m away, its arc moved to first order over 7 cm, turned inside
// out and put 250 returns of one scan beyond it at the true pose. An end that a particle would
// move further than kMaxShift_rad (possible only on a sparse segment, whose spacing lets the
// rule above pass larger shifts) counts nothing for that particle.
//
// The returns beyond an arc are not inliers either: the scan's inlier fraction (the lost test,
// the tilt) counts only the returns its polygons explain.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/boundary_motion.hpp"
#include "localizer/conic/predicted_scan.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/segment_landmarks.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::localizer {

/// The bounded ends of an association's terms, by column (one row per end).
struct SegmentRims {
  static constexpr double kMaxReach_rad = 0.2;
  static constexpr double kMaxShift_rad = 0.2;
  static constexpr double kMaxCornerError_returns = 4.0;

  BoundaryRates rates;            ///< negated for an arc's beginning, like its limit
  std::vector<double> limit_rad;  ///< the arc's end at the centre, unwrapped like the segment
  /// The segment's outermost return on that side, signed so that returns beyond the end make
  /// (outermost − limit) positive: end_rad for an arc's end, −begin_rad for its beginning (whose
  /// limit and rates are stored negated too).
  std::vector<double> outermost_rad;
  std::vector<double> returns_per_rad;  ///< 1/Δ, the segment's mean return spacing
  std::vector<int> term;                ///< index into Association::terms

  std::size_t size() const { return term.size(); }
  void clear();
};

/// The rims of every term of `association` (made at `centre` from its predicted scan
/// `predicted`): for each (segment, candidate), the ends of the candidate's surface's arc around
/// the segment on its ring, and how they move (boundary_motion), for poses within `cell` of the
/// centre. A term whose candidate the centre sees nowhere within the segment gets none.
void find_segment_rims(const Association& association, const std::vector<SegmentFit>& fits,
                       const PredictedScan& predicted, const maps::PlaneMap& map,
                       const std::vector<RingGeometry>& rings, const Surfaces& surfaces,
                       const Pose3& centre, const AssociationCellSize& cell, SegmentRims& out);

/// Per term of the association, the segment's returns beyond its candidate's arc at a pose
/// `offset` from the centre (the sum over the term's rims of max(0, (θ_s − θ_e)/Δ + ½)).
/// `shifts` is working memory.
void returns_beyond_rims(const SegmentRims& rims, const PoseOffset& offset, std::size_t terms,
                         std::vector<double>& shifts, Eigen::ArrayXd& beyond);

}  // namespace conicloc::localizer
