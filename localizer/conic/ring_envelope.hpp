#pragma once
// Nearest surface wins: the lower envelope in range (upper envelope in 1/r) of a ring's polygon
// arcs, as a partition of [0, 2π) into pieces. Inside an azimuth interval where several arcs
// overlap, two conics 1/r = a_i cos θ + b_i sin θ + c_i switch where
//   (a1 − a2) cos θ + (b1 − b2) sin θ + (c1 − c2) = 0,
// solved in closed form; between switch points one midpoint comparison picks the winner.

#include <vector>

#include "localizer/conic/predicted_scan.hpp"

namespace conicloc::localizer {

/// Builds `out` (cleared first) from `arcs` (any order; each within [0, 2π], begin < end, with
/// positive 1/r over it). Sorts `arcs` in place; uses workspace.events and workspace.active.
void build_ring_envelope(std::vector<PredictionWorkspace::Arc>& arcs,
                         PredictionWorkspace& workspace, PredictedRing& out);

}  // namespace conicloc::localizer
