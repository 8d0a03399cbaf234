#include "localizer/conic/yaw_shared_prediction.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

}  // namespace

PredictorConfig cell_predictor_config(PredictorConfig config, const AssociationCellSize& cell,
                                      double max_range_m) {
  config.beyond_range_margin_m =
      std::max(config.beyond_range_margin_m, cell.range_margin_m(max_range_m));
  return config;
}

void turn_ring(const PredictedRing& in, double yaw_rad, PredictedRing& out) {
  out.clear();
  out.min_inverse_range = in.min_inverse_range;
  out.max_inverse_range = in.max_inverse_range;
  const std::size_t n = in.piece_count();
  if (n == 0) return;
  double psi = std::fmod(yaw_rad, kTwoPi);
  if (psi < 0.0) psi += kTwoPi;
  if (psi >= kTwoPi) psi = 0.0;  // a tiny negative yaw rounds up to 2π
  const double cos_psi = std::cos(psi), sin_psi = std::sin(psi);
  auto turned = [&](std::size_t i, double end_rad) {
    const double a = in.a[i], b = in.b[i];
    // Merged with the previous piece when the same (the yaw-0 ring's split at θ₀ = 0 is no
    // boundary once turned).
    out.append(end_rad, a * cos_psi + b * sin_psi, b * cos_psi - a * sin_psi, in.c[i],
               in.polygon[i]);
  };
  // θ = 0 of the turned ring is θ₀ = ψ: piece k holds it. Pieces k … n − 1 end at b − ψ, then
  // 0 … k − 1 at b + 2π − ψ, and piece k's part before ψ closes the circle at 2π.
  const std::size_t k = in.piece_at(psi);
  const double wrap_shift = kTwoPi - psi;
  for (std::size_t i = k; i < n; ++i) turned(i, std::max(in.boundary_rad[i + 1] - psi, 0.0));
  for (std::size_t i = 0; i < k; ++i) {
    turned(i, std::min(in.boundary_rad[i + 1] + wrap_shift, kTwoPi));
  }
  if (in.boundary_rad[k] < psi) turned(k, kTwoPi);
  out.boundary_rad.back() = kTwoPi;
}

bool YawSharedPrediction::predict(const ConicScanPredictor& predictor,
                                  const AssociationCellKey& cell, std::span<const int> candidates,
                                  std::uint64_t candidates_version, std::span<const int> rings,
                                  std::uint64_t scan_generation, const AssociationGrid& grid,
                                  bool share, PredictedScan& out) {
  if (candidates_version != candidates_version_ || !std::ranges::equal(rings, rings_)) {
    cells_.clear();
    candidates_version_ = candidates_version;
    rings_.assign(rings.begin(), rings.end());
  }
  const Pose3 centre = grid.centre(cell);
  const Eigen::Matrix3d& R = centre.linear();
  // Rz(ψ)·Ry(θ)·Rx(φ) has the bottom row (−sin θ, cos θ sin φ, cos θ cos φ): (0, 0, 1) exactly
  // for a level centre, whose roll and pitch bins are 0.
  const bool turned = share && R(2, 0) == 0.0 && R(2, 1) == 0.0 && R(2, 2) == 1.0;
  // Level centres by their yaw-0 cell (the same position), tilted ones by their own.
  AssociationCellKey kept = cell;
  if (turned) kept[6] = 0;
  const CellPrediction& prediction = cells_.get(kept, scan_generation, [&](CellPrediction& made) {
    predictor.predict(turned ? grid.centre(kept) : centre, candidates, rings, work_);
    made.rings = work_.rings;
    made.polygons_considered = work_.polygons_considered;
    made.polygons_outside_field_of_view = work_.polygons_outside_field_of_view;
    made.ring_polygons_occluded = work_.ring_polygons_occluded;
    made.ring_polygons_beyond_range = work_.ring_polygons_beyond_range;
    made.ring_polygons_clipped = work_.ring_polygons_clipped;
    made.polygons_prepared = work_.polygons_prepared;
  });
  out.polygons_considered = prediction.polygons_considered;
  out.polygons_outside_field_of_view = prediction.polygons_outside_field_of_view;
  out.ring_polygons_occluded = prediction.ring_polygons_occluded;
  out.ring_polygons_beyond_range = prediction.ring_polygons_beyond_range;
  out.ring_polygons_clipped = prediction.ring_polygons_clipped;
  out.polygons_prepared = prediction.polygons_prepared;
  if (!turned) {
    out.rings = prediction.rings;
    return false;
  }
  out.rings.resize(prediction.rings.size());
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  for (std::size_t k = 0; k < prediction.rings.size(); ++k) {
    turn_ring(prediction.rings[k], yaw, out.rings[k]);
  }
  return true;
}

}  // namespace conicloc::localizer
