#pragma once
// Triangulation of a plane polygon with holes (ear clipping after bridging holes to the outer
// ring).

#include <array>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::maps {

/// A triangle as three indices into the polygon's vertices, numbered outer ring first, then each
/// hole in order (so they index PlanarPolygon::outer followed by PlanarPolygon::holes).
using Triangle = std::array<int, 3>;

/// Triangles covering the region inside `outer` and outside every hole, counter-clockwise (each
/// triangle's orientation is that of a counter-clockwise outer ring). Accepts either ring
/// orientation; rings are open (no repeated closing vertex). A ring that revisits a vertex (a
/// "keyhole" ring holding a window, as real files write them) is cut there into loops: loops
/// turning against the largest one are holes. Holes are bridged to their outline (Eberly,
/// "Triangulation by Ear Clipping", 2002) and the merged ring is clipped ear by ear.
/// For a valid polygon (simple loops, holes inside and disjoint) the triangle areas sum to the
/// polygon's area; for invalid input the result is some covering without crashing. A hole
/// outside the outer ring is ignored. Fewer than 3 outer vertices give no triangles.
std::vector<Triangle> triangulate(const Ring2& outer, const std::vector<Ring2>& holes);

/// Same for a PlanarPolygon (uses its uv rings); indices refer to `outer` then `holes`.
std::vector<Triangle> triangulate(const PlanarPolygon& polygon);

}  // namespace conicloc::maps
