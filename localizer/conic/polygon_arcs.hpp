#pragma once
// Clipping a ring's conic to a bounded polygon with holes: the azimuth arcs where the ring's beams
// hit the plane inside the polygon. Exact: the hit point crosses the line of an edge P0P1 exactly
// when the beam lies in the plane through the apex and the edge, m·d(θ) = 0 with
// m = (P0 − apex) × (P1 − apex), i.e. m_x cos φ cos θ + m_y cos φ sin θ + m_z sin φ = 0, solved in
// closed form (θ = ψ ± acos(γ/R)); a crossing counts when d lies in the edge's forward wedge.
// Between consecutive crossings (and the plane's visible-interval ends) the inside/outside state
// is constant, so one midpoint test per interval classifies it. Crossings accepted with a small
// tolerance at vertices only add harmless split points, so no crossing is lost to rounding.
// Faster and equal: the hit point is inside a vertex ring (even-odd) on one interval, and that
// state flips at each crossing of one of the ring's edges; the polygon is its outer ring minus
// its holes. So one test per vertex ring suffices, where every crossing is a clean transversal
// one: inside its edge by more than the tolerance, apart from its ring's other crossings, not
// tangent, and an even number per ring (the azimuth circle is closed). Where any of that fails
// (a beam through or near a vertex, a conic tangent to an edge) it falls back to one midpoint
// test per interval. So the arcs are those of the midpoint tests, but for a sliver (of rounding
// width) where two vertex rings are crossed at one azimuth, classified by the walk there.

#include <vector>

#include "localizer/conic/pose.hpp"
#include "localizer/conic/predicted_scan.hpp"
#include "localizer/conic/ring_conic.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "maps/planar_polygon.hpp"

namespace conicloc::localizer {

/// Appends `polygon` (index `index` in its map), transformed into the sensor frame of
/// T_map_sensor, to the workspace's polygons and vertex arrays.
void add_sensor_polygon(const maps::PlanarPolygon& polygon, int index, const Pose3& T_map_sensor,
                        PredictionWorkspace& workspace);

/// The plane of a workspace polygon.
inline SensorPlane sensor_plane(const PredictionWorkspace::SensorPolygon& polygon) {
  return {{polygon.normal[0], polygon.normal[1], polygon.normal[2]}, polygon.offset};
}

/// How append_polygon_arcs() decides which intervals between crossings are inside the polygon.
enum class ArcClassification {
  kCrossingParity,  ///< one inside test per vertex ring, then toggles (falls back when unsafe)
  kMidpointTests,   ///< one inside test per interval
};

/// Appends the arcs (within [0, 2π], ascending, disjoint, each with the polygon's 1/r
/// coefficients) where `ring` hits `polygon` at a positive range. `map_polygon` is the same
/// polygon in the map (its uv rings are used for the inside test). Uses workspace.edge_crossings
/// and the per-ring scratch. Returns the classification it used (kMidpointTests where the parity
/// walk is unsafe, or when asked for).
ArcClassification append_polygon_arcs(
    const RingGeometry& ring, const PredictionWorkspace::SensorPolygon& polygon,
    const maps::PlanarPolygon& map_polygon, PredictionWorkspace& workspace,
    std::vector<PredictionWorkspace::Arc>& arcs,
    ArcClassification classification = ArcClassification::kCrossingParity);

}  // namespace conicloc::localizer
