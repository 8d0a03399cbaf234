#pragma once
// Which map plane a measured point lies on. The ray decides, not the measured range: of the
// polygons within a gate of the point, the first the ray (as the model fires it) meets from the
// side it faces, kept only when it meets that one inside and a margin from every edge, and passes
// every other of them, before it, clear of their edges and not through their backs. The gate
// shrinks over the calibration's rounds as the model improves (coarse poses first, then tight).
//
// Why the ray: wherever the measured range chose the polygon, the noise chose which returns a
// surface keeps. The nearest polygon to the point did: a return on the floor by a wall's foot
// measured long lies nearer the wall; one measured long by more than half a wall's thickness
// lies nearer the next room's face, which its ray meets from behind. Either is dropped, so the
// kept returns were biased short (FJK-Haus, 3 cm of range noise: 1.1–1.4% of two walls' returns,
// every one above +6 cm; those walls' kept returns 0.8–1.0 mm short). A 15° laser's range on a
// wall 2 m off moves 0.9 mm per 0.1° (dr/dφ = r·tan φ): FJK-Haus seed 1's elevations came out
// 4–6 σ off, alike in every noise draw, and with the ray deciding at their noise (z 1.25;
// docs/results/calibration-association.md).
//
// Why the edges of the others: by an edge, which of two surfaces a return came from turns on the
// few millimetres between the modelled ray and the true one, not on the noise; taking the first
// polygon met without that test handed returns by a wall's end to the wall behind it (FJK-Haus:
// 1.2 of 4.2 M returns left, elevations 0.36° off). Earlier variants measured worse: the first
// polygon met among those near the point, without the edge test (0.105 and 0.234° against 0.067
// and 0.085°: docs/results/calibration-range-noise.md), and only polygons facing the ray competing
// for the nearest (a common elevation slope, example building 0.0117 → 0.0236°, session 44).

#include <Eigen/Core>

#include "maps/plane_index.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::calib {

/// A ray grazing a surface, beyond 84° from its normal, is not used: its range residual (the
/// point-to-plane one over the cosine, calibration_model.hpp) would turn a millimetre of
/// survey error into a centimetre.
constexpr double kMinIncidenceCosine = 0.1;

/// True when the ray origin + s·direction (s > 0) meets `polygon`'s plane from the side it faces
/// (either side of a two-sided one), within kMinIncidenceCosine of grazing, inside the polygon
/// and at least `margin_m` from its outer ring and holes.
bool ray_meets_inside(const maps::PlanarPolygon& polygon, const Eigen::Vector3d& origin,
                      const Eigen::Vector3d& direction, double margin_m);

/// The polygon a return lies on (module comment): of the polygons within `gate_m` of
/// `point_map` (distance to the bounded polygon, holes excluded), the first the ray from `origin`
/// through the point meets from the side it faces, kept when ray_meets_inside() holds for it and
/// the ray crosses every other one's plane before it at least `margin_m` from its rings and not
/// through its back (−1 otherwise).
int associated_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                       const Eigen::Vector3d& origin, const Eigen::Vector3d& point_map,
                       double gate_m, double margin_m);

}  // namespace conicloc::calib
