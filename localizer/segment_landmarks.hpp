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

#include <cstddef>
#include <vector>

#include "localizer/predicted_scan.hpp"
#include "localizer/ring_geometry.hpp"
#include "localizer/scan_line_segmentation.hpp"
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

/// One measured segment with the polygons it may lie on (the best few at the reference pose);
/// per pose the closest visible one is taken (nearest-plane association).
struct LandmarkSegment {
  static constexpr int kMaxCandidates = 3;
  int candidates[kMaxCandidates] = {-1, -1, -1};  ///< indices into Association::landmarks
  int candidate_count = 0;
  double cos_elevation = 1.0, sin_elevation = 0.0, vertical_offset_m = 0.0;
  double m[6] = {0, 0, 0, 0, 0, 0};  ///< M
  double g[3] = {0, 0, 0};           ///< M p_fit
  double h = 0.0;                    ///< p_fitᵀ M p_fit
  double returns = 0.0;
  double inverse_returns = 0.0;
  /// Azimuths (cos, sin) where the plane must be seen at a positive range within range limits.
  double check_cos[3] = {1, 1, 1}, check_sin[3] = {0, 0, 0};
};

/// One candidate map polygon: its plane in the map frame.
struct Landmark {
  int polygon = -1;
  double normal_map[3] = {0, 0, 1};
  double offset_map = 0.0;
};

struct Association {
  std::vector<Landmark> landmarks;
  std::vector<LandmarkSegment> segments;  ///< the associated ones
  int unassociated_segments = 0;          ///< no polygon fits within the gate: clutter
  double unassociated_returns = 0.0;      ///< their returns
};

/// For every fit, the polygons of `predicted` (the scan predicted at the reference pose) seen
/// over its span (widened by 20 % each side) whose rms range difference is below `gate_m`, best
/// first. Deterministic: depends on its inputs only.
void associate_segments(const std::vector<SegmentFit>& fits, const PredictedScan& predicted,
                        const maps::PlaneMap& map, const std::vector<RingGeometry>& rings,
                        double gate_m, Association& out);

}  // namespace conicloc::localizer
