#pragma once
// Association cells that differ only in yaw share one scan prediction. Turning the sensor by ψ
// about its spin axis turns every ring's scan line by −ψ in azimuth: a map direction seen at
// azimuth θ₀ from yaw 0 is seen at θ = θ₀ − ψ, so r_ψ(θ) = r_0(θ + ψ), and each piece
// 1/r = a cos θ₀ + b sin θ₀ + c becomes
//   1/r = (a cos ψ + b sin ψ) cos θ + (b cos ψ − a sin ψ) sin θ + c.
// That holds for a level cell centre (roll = pitch = 0, the mounting pose's cell): its rotation is
// Rz(ψ), the yaw-0 rotation turned about the spin axis. Other centres are predicted directly.

#include <cstdint>
#include <span>
#include <vector>

#include "localizer/conic/association_grid.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"

namespace conicloc::localizer {

/// `config` for a predictor whose predictions the poses of an association cell of `cell` share:
/// surfaces are kept out to `max_range_m` plus the cell's range_margin_m() there, since the
/// cell's other poses take the centre's surfaces up and can see them that much nearer.
PredictorConfig cell_predictor_config(PredictorConfig config, const AssociationCellSize& cell,
                                      double max_range_m);

/// `in` (a ring predicted at yaw 0) as predicted at yaw `yaw_rad` (any value) from the same
/// position. Neighbouring pieces of one surface with equal coefficients are merged.
void turn_ring(const PredictedRing& in, double yaw_rad, PredictedRing& out);

/// One thread's predictions at association-cell centres for the current scan.
class YawSharedPrediction {
 public:
  /// Fills `out.rings` with the scan `predictor` predicts at `centre` (an association-cell centre
  /// of `grid`) from `candidates`, for `rings` (ascending; the others empty). With `share`, a
  /// level centre's scan is turned from the level prediction at the same position, made once per
  /// position and scan; returns true then. Precondition: within one `scan_generation`, the same
  /// `candidates` and `rings`.
  bool predict(const ConicScanPredictor& predictor, const Pose3& centre,
               std::span<const int> candidates, std::span<const int> rings,
               std::uint64_t scan_generation, const AssociationGrid& grid, bool share,
               PredictedScan& out);

 private:
  struct LevelPrediction {
    std::vector<PredictedRing> rings;
    /// The level prediction's counts (PredictedScan), handed on with its turned rings.
    std::size_t polygons_outside_field_of_view = 0, ring_polygons_occluded = 0,
                ring_polygons_beyond_range = 0, ring_polygons_clipped = 0, polygons_prepared = 0;
  };
  AssociationCache<LevelPrediction> level_;  ///< keyed by the yaw-0 centre
  PredictedScan work_;
};

}  // namespace conicloc::localizer
