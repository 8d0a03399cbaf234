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

/// One thread's predictions at association-cell centres, kept from scan to scan
/// (RecentCellCache) while they are made from the same candidates and rings: a prediction is a
/// function of the map, the centre, the candidates and the rings, so a kept one is the one the
/// scan would make, whichever thread or scan made it.
class YawSharedPrediction {
 public:
  /// Fills `out.rings` with the scan `predictor` predicts at the centre of `grid`'s `cell` from
  /// `candidates`, for `rings` (ascending; the others empty). With `share`, a level centre's scan
  /// is turned from the level prediction at the same position; returns true then. A cell
  /// predicted in this scan or the one before (`scan_generation`) is not predicted again; another
  /// `candidates_version` (CloudCull::version: it changes with the candidates) or other `rings`
  /// than the last call's forget every prediction.
  bool predict(const ConicScanPredictor& predictor, const AssociationCellKey& cell,
               std::span<const int> candidates, std::uint64_t candidates_version,
               std::span<const int> rings, std::uint64_t scan_generation,
               const AssociationGrid& grid, bool share, PredictedScan& out);

 private:
  struct CellPrediction {
    std::vector<PredictedRing> rings;
    /// The prediction's counts (PredictedScan), handed on with its rings.
    std::size_t polygons_considered = 0, polygons_outside_field_of_view = 0,
                ring_polygons_occluded = 0, ring_polygons_beyond_range = 0,
                ring_polygons_clipped = 0, polygons_prepared = 0;
  };
  /// Level centres by their yaw-0 centre, tilted ones by their own (never level: no clash).
  RecentCellCache<CellPrediction> cells_;
  std::uint64_t candidates_version_ = 0;  ///< of the candidates cells_ was predicted from
  std::vector<int> rings_;                ///< the rings cells_ holds
  PredictedScan work_;
};

}  // namespace conicloc::localizer
