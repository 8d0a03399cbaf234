#pragma once
// The landmark form of the conic-segment model (DESIGN.md "Observation models" 2). A measured
// segment of ring k fitted as 1/r = p_fit·x(θ), x(θ) = (cos θ, sin θ, 1), is compared with the
// conic p = (A, B, C)/E of a map plane (ring_conic.hpp) over its returns in closed form:
//   Σ_i (r_i² (p − p_fit)·x_i)² = (p − p_fit)ᵀ M (p − p_fit),   M = Σ_i r_i⁴ x_i x_iᵀ,
// the sum of squared range differences (to first order, r − r̂ ≈ r²(1/r̂ − 1/r)) between the
// fitted and the predicted conic at the segment's azimuths. The same r⁴ weights are the fit's
// (fit_inverse_range), so nothing but M and p_fit is kept. Segments of one ring on one plane add
// up: Σ_s (p − p_s)ᵀ M_s (p − p_s) = pᵀ(ΣM_s)p − 2pᵀ(ΣM_s p_s) + Σ p_sᵀM_s p_s.
//
// Association (which segment lies on which map polygon) is done once for a reference pose from
// its predicted scan (best fit among the polygons the prediction shows over the segment's span);
// per particle only the associated planes are moved into the particle's sensor frame.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "localizer/conic/predicted_scan.hpp"
#include "localizer/conic/ring_conic.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "localizer/models/scan_line_segmentation.hpp"
#include "maps/plane_map.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// One measured segment's fit and second moments. Symmetric 3×3 matrices are stored as their
/// upper triangle (xx, xy, xz, yy, yz, zz).
struct SegmentFit {
  int ring = 0;                            ///< index into the predictor's rings
  double begin_rad = 0.0, end_rad = 0.0;   ///< azimuth span (end may exceed 2π)
  double p[3] = {0, 0, 0};                 ///< fitted (a, b, c)
  double moments[6] = {0, 0, 0, 0, 0, 0};  ///< M = Σ r⁴ x xᵀ
  double returns = 0.0;                    ///< returns in the fit
};

/// The fit of `segment` (found by segment_scan_line on `ring_scan`) with the moments of the
/// returns it was fitted to: the usable returns (valid, range within [min, max]) from
/// segment.first to segment.last, wrapping past the ring's end.
SegmentFit make_segment_fit(const sensor::RingScan& ring_scan, const ConicSegment& segment,
                            int ring, double min_range_m, double max_range_m);

/// (p − p_fit)ᵀ M (p − p_fit): squared range differences summed over the segment's returns.
double squared_range_difference(const SegmentFit& fit, const double p[3]);

/// One segment's comparison with any plane, as a particle scores it, in terms of the plane in the
/// particle's sensor frame u = (n_s, D_s) (4 numbers per polygon and particle). With the
/// ring's conic p = n'/E, n' = (n_x cos φ, n_y cos φ, n_z sin φ), E = −(D_s + o n_z)
/// (ring_conic.hpp), w = (n', E) = L u is linear in u, so
///   E² (p − p_fit)ᵀ M (p − p_fit) = n'ᵀMn' − 2E n'ᵀM p_fit + E² p_fitᵀM p_fit = wᵀ K w =
///   uᵀ(LᵀKL)u, K = [[M, −M p_fit], [−(M p_fit)ᵀ, p_fitᵀ M p_fit]],
/// a dot product of LᵀKL's 10 coefficients with u's 10 quadratic monomials (computed once per
/// polygon and particle: SensorPlaneTerms) and one division per pair (candidate_costs).
struct CandidateTerm {
  /// LᵀKL's upper triangle (00, 01, 02, 03, 11, 12, 13, 22, 23, 33), off-diagonals doubled.
  double quadratic[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  /// Where the plane must be seen at a range within limits: for three azimuths θ_c inside the
  /// span, x_c = (cos φ cos θ_c, cos φ sin θ_c, sin φ), so that n'·(cos θ_c, sin θ_c, 1) = x_c·n_s.
  double checks[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  double vertical_offset_m = 0.0;  ///< o of the segment's ring
};

/// A plane u = (n_s, D_s) in a particle's sensor frame with u's quadratic monomials, in
/// CandidateTerm::quadratic's order.
struct SensorPlaneTerms {
  double u[4] = {0, 0, 1, 0};
  double monomials[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
};

inline SensorPlaneTerms sensor_plane_terms(double n_x, double n_y, double n_z, double offset) {
  // The monomials u_i u_j (i ≤ j) in row order, written out: built through a loop over a stack
  // copy of u they cost a store-forwarding stall per particle and landmark.
  return {{n_x, n_y, n_z, offset},
          {n_x * n_x, n_x * n_y, n_x * n_z, n_x * offset, n_y * n_y, n_y * n_z, n_y * offset,
           n_z * n_z, n_z * offset, offset * offset}};
}

/// True when the ring sees the plane u at a range within [1/max_inverse, 1/min_inverse) at all
/// three checks: 1/r = x_c·n_s / E in (min_inverse, max_inverse] (multiplied through by |E|), so
/// not behind the sensor, not too far, and not E = 0 (the cone parallel to the plane's line).
inline bool candidate_visible(const CandidateTerm& term, const double u[4], double min_inverse,
                              double max_inverse) {
  const double E = -(u[3] + term.vertical_offset_m * u[2]);
  const double magnitude = std::abs(E), sign = E < 0.0 ? -1.0 : 1.0;
  bool visible = true;
  for (int c = 0; c < 3; ++c) {
    const double* x = &term.checks[3 * c];
    const double v = sign * (x[0] * u[0] + x[1] * u[1] + x[2] * u[2]);
    visible &= (v > min_inverse * magnitude) & (v <= max_inverse * magnitude);
  }
  return visible;
}

/// One measured segment with the polygons it may lie on (the best few at the reference pose);
/// per pose the closest visible one is taken (nearest-plane association).
struct LandmarkSegment {
  static constexpr int kMaxCandidates = 3;
  int candidates[kMaxCandidates] = {-1, -1, -1};  ///< indices into Association::landmarks
  int candidate_count = 0;
  int terms[kMaxCandidates] = {-1, -1, -1};  ///< their terms: indices into Association::terms
  double returns = 0.0;
  double inverse_returns = 0.0;
};

/// One (associated segment, candidate polygon) pair.
struct AssociatedTerm {
  int fit = -1;       ///< index into the scan's fits and their CandidateTerms
  int landmark = -1;  ///< index into Association::landmarks
  /// False when every pose of the association's grid cell sees the plane at all three checks
  /// (mark_seen_throughout_cell), so a particle need not test them.
  bool check_visibility = true;
};

/// One candidate map polygon: its plane in the map frame.
struct Landmark {
  int polygon = -1;
  double normal_map[3] = {0, 0, 1};
  double offset_map = 0.0;
};

/// A landmark's plane in the sensor frame of T_map_sensor (to_sensor_plane) with its monomials.
inline SensorPlaneTerms landmark_plane_terms(const Landmark& landmark, const Pose3& T_map_sensor) {
  const SensorPlane plane =
      to_sensor_plane(Eigen::Map<const Eigen::Vector3d>(landmark.normal_map), landmark.offset_map,
                      T_map_sensor.linear(), T_map_sensor.translation());
  return sensor_plane_terms(plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset);
}

struct Association {
  std::vector<Landmark> landmarks;
  std::vector<LandmarkSegment> segments;  ///< the associated ones
  /// One per (associated segment, candidate), ordered by landmark: landmark l's terms are
  /// [landmark_terms[l], landmark_terms[l + 1]).
  std::vector<AssociatedTerm> terms;
  std::vector<int> landmark_terms;
  /// The terms' quadratic coefficients and vertical offsets as columns (a row per term), so that
  /// a particle's pass over one landmark's terms is a vector loop with the plane held fixed.
  Eigen::Array<double, Eigen::Dynamic, 10> quadratic;
  Eigen::ArrayXd vertical_offset_m;
  std::vector<int> checked_terms;     ///< the terms with check_visibility set
  int unassociated_segments = 0;      ///< no polygon fits within the gate: clutter
  double unassociated_returns = 0.0;  ///< their returns
};

/// The fit's CandidateTerm for a segment of the ring `geometry`: it depends on the scan only, so
/// it is made once per scan and each cell's association refers to it.
CandidateTerm candidate_term(const SegmentFit& fit, const RingGeometry& geometry);

/// For every fit, the polygons of `predicted` (the scan predicted at the reference pose) seen
/// over its span (widened by 20 % each side) whose rms range difference is below `gate_m`, best
/// first. Deterministic: depends on its inputs only.
/// `fit_terms` holds candidate_term() of each fit.
void associate_segments(const std::vector<SegmentFit>& fits,
                        const std::vector<CandidateTerm>& fit_terms, const PredictedScan& predicted,
                        const maps::PlaneMap& map, double gate_m, Association& out);

/// Clears check_visibility on the terms whose plane every pose within `translation_m` (metres)
/// and `rotation_rad` (rotation angle) of `centre` sees at all three checks. Over such poses a
/// unit normal n_s = Rᵀn moves by at most the rotation angle δ_R and D_s = D + n·t by at most δ_t,
/// so, with |x_c| = 1, x_c·n_s moves by at most δ_R and E by at most δ_t + |o| δ_R; a term is
/// marked when its checks hold at the centre with those margins.
void mark_seen_throughout_cell(Association& association,
                               const std::vector<CandidateTerm>& fit_terms, const Pose3& centre,
                               double translation_m, double rotation_rad, double min_inverse,
                               double max_inverse);

/// Every term's (p − p_fit)ᵀ M (p − p_fit) for the landmarks' planes in a particle's sensor frame
/// (`planes`, one per landmark), or +∞ for a checked term whose plane the ring does not see
/// (candidate_visible).
void candidate_costs(const Association& association, const std::vector<CandidateTerm>& fit_terms,
                     const std::vector<SensorPlaneTerms>& planes, double min_inverse,
                     double max_inverse, Eigen::ArrayXd& costs);

}  // namespace conicloc::localizer
