#pragma once
// Which map plane a measured point lies on: the nearest bounded polygon within a gate. The gate
// shrinks over the calibration's rounds as the model improves (coarse poses first, then tight).
//
// Near a polygon's edge the nearest polygon depends on the range noise: a return on the floor by
// a wall whose noise carries it past the wall's foot is nearer the wall (or outside the floor),
// one whose noise brings it nearer stays on the floor, so the returns kept there are biased
// towards the sensor (a floor seen higher, elevations and height pulled off). So a return also
// needs its ray, as the model fires it, to meet its nearest polygon from the side it faces,
// inside it and `margin_m` from every edge: where the ray meets a surface does not depend on the
// measured range. (Giving a return the first polygon its ray meets among those near its point
// instead was measured worse on simulated captures, elevations 0.105 and 0.234° RMS against
// 0.067 and 0.085° in two seeds: docs/results/calibration-range-noise.md.)
//
// The nearest polygon still lets the noise choose behind a wall of two faces: a return measured
// long by more than half the wall's thickness is nearer the next room's face, which its ray meets
// from behind, so it is dropped (FJK-Haus, 3 cm of range noise: 1.1–1.4% of two walls' returns
// near normal incidence, every one above +6 cm; the walls' kept returns 0.8–1.0 mm shorter than
// all of theirs).
// Letting only the polygons that face the ray's origin compete keeps them, and was measured
// worse: the elevations took a common slope of 1.6–2.6 mdeg per degree of elevation (both
// halves of a capture alike), example building at 12 s 0.0117 → 0.0236° and 0.0170 → 0.0241°
// RMS (seeds 1, 2), FJK-Haus at 36 s 0.0487 → 0.0423° (seed 1, exact map) and 0.0664 → 0.0751°
// (seed 2). Not understood; not kept.

#include <Eigen/Core>

#include "maps/plane_index.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::calib {

/// Index of the polygon of `map` nearest to `point_map` (distance to the bounded polygon, holes
/// excluded), or −1 when none is within `gate_m`.
int nearest_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                    const Eigen::Vector3d& point_map, double gate_m);

/// A ray grazing a surface, beyond 84° from its normal, is not used: its range residual (the
/// point-to-plane one over the cosine, calibration_model.hpp) would turn a millimetre of
/// survey error into a centimetre.
constexpr double kMinIncidenceCosine = 0.1;

/// True when the ray origin + s·direction (s > 0) meets `polygon`'s plane from the side it faces
/// (either side of a two-sided one), within kMinIncidenceCosine of grazing, inside the polygon
/// and at least `margin_m` from its outer ring and holes.
bool ray_meets_inside(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction, double margin_m);

/// The polygon a return lies on: nearest_polygon(point_map), kept only when the ray from
/// `origin` through the point meets it as ray_meets_inside() requires (−1 otherwise).
int associated_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                       const Eigen::Vector3d& origin, const Eigen::Vector3d& point_map,
                       double gate_m, double margin_m);

}  // namespace conicloc::calib
