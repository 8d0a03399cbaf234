#pragma once
// Returns on objects the map lacks that stand by a mapped surface: a box against a wall, a
// radiator, a cupboard's side within the association gate of the wall behind it.
//
// Why: the gate (plane_association.hpp) keeps every return within 10 cm of a polygon, and
// the Huber loss weighs a residual of 5–10 cm almost fully at 3 cm of range noise. A box's face
// 6 cm before a wall is on one side only, so it pulls the lasers that see it: the −1° laser of
// the example building's seed 5 (tilted mount, clutter) was 0.143° off, 0.021° without clutter.
// One return cannot tell a box from the noise, but a scan line can: the returns of a surface
// scatter about zero residual, an object's stand a few centimetres off together, for as many
// returns as the object is wide. So a return is left out when the median residual of its
// neighbours on the scan line (the same laser in the same scan, ±half_window returns in
// azimuth, on the same polygon) is farther from zero than the noise lets a median stray:
//   |med| > κ·σ_med,   σ_med = √(π/2)·σ/√n
// (the median of n Gaussian residuals of σ; σ the residuals' robust scale, 1.4826 times their
// median magnitude: the fit's residuals are centred on zero). With κ = 4 and n = 15 the bound is
// 1.3σ (4 cm at σ 3 cm): a surface whose residuals are white noise loses one return in 10⁴, and
// an object from about 2σ off and 8 returns (1.6°) wide is left out, at its edges less surely.
// What stays is an object nearer its surface or narrower than that.
//
// It needs a model that explains each surface up to white noise: a steady error along a scan
// line (a laser's own error not fitted, a plane held fixed where the map is off) is not an
// object, but a long run off zero all the same. So it is used where the lasers and the planes
// are fitted (calibration_solver.hpp).

#include <cstddef>
#include <span>
#include <vector>

#include "calib/calibration_model.hpp"

namespace conicloc::calib {

struct UnmappedObjectConfig {
  int half_window = 7;         ///< neighbours each side on the scan line (0.2° apart: ±1.4°)
  double median_sigmas = 4.0;  ///< κ above
  int min_neighbours = 5;      ///< fewer on the same polygon (a sliver): the return is kept
  /// Floor of σ (m), as the solver's residual variance is: noise-free returns would leave no
  /// median within bounds.
  double min_sigma_m = 1e-3;
};

/// The returns' indices per scan line (one laser in one scan), each line in azimuth order.
std::vector<std::vector<std::size_t>> scan_lines(std::span<const Return> returns);

/// 1.4826 times the median absolute residual of the returns with plane ≥ 0 (0 when none).
double robust_sigma(std::span<const double> residual_m, std::span<const int> plane);

/// Sets plane[i] = −1 for every return whose neighbours' median residual (see above; the return
/// itself included) lies beyond κ·σ_med; returns how many. `residual_m[i]` is read only where
/// plane[i] ≥ 0, and the medians are taken before any return is left out.
std::size_t leave_out_unmapped_objects(const std::vector<std::vector<std::size_t>>& lines,
                                       std::span<const double> residual_m, std::vector<int>& plane,
                                       double sigma_m, const UnmappedObjectConfig& config);

/// The same with σ = max(robust_sigma(residual_m, plane), config.min_sigma_m).
std::size_t leave_out_unmapped_objects(const std::vector<std::vector<std::size_t>>& lines,
                                       std::span<const double> residual_m, std::vector<int>& plane,
                                       const UnmappedObjectConfig& config);

}  // namespace conicloc::calib
