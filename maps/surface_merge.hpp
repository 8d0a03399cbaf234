#pragma once
// Load-time clean-up of a building's surfaces: door openings cut into walls, and coplanar faces
// of adjacent cells (thin-wall models hold every wall twice, once from each side) kept once.

#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::maps {

struct MergeStats {
  int door_holes_cut = 0;         ///< door outlines added as holes to walls
  int door_surfaces_removed = 0;  ///< shell faces that were the door itself
  int faces_merged = 0;           ///< faces removed because a coplanar face covers them
  int two_sided = 0;              ///< kept faces that now bound free space on both sides
  int partial_overlaps = 0;       ///< coplanar overlapping pairs kept (neither covers the other)
};

/// Coplanar within 2° and 2 cm (each centroid within 2 cm of the other's plane).
bool coplanar(const PlanarPolygon& a, const PlanarPolygon& b, double angle_deg = 2.0,
              double distance_m = 0.02);

/// True when every outer vertex of `inner` lies inside `outer`'s outline (or within `tolerance_m`
/// of it) and no hole of `outer` opens into `inner`. Precondition: coplanar(outer, inner).
bool covers(const PlanarPolygon& outer, const PlanarPolygon& inner, double tolerance_m = 0.02);

/// Door boundaries become openings: a face the door covers is removed (it is the door surface),
/// a wall the door lies in gets the door outline as a hole. Polygons removed are erased.
void cut_door_openings(std::vector<PlanarPolygon>& polygons,
                       const std::vector<PlanarPolygon>& doors, MergeStats& stats);

/// Keeps each physical surface once: a face covered by a coplanar face of another cell is removed;
/// when their normals are opposite the kept face becomes two-sided (back_cell = the other cell).
/// Returns, for every input index, the index in the merged vector of the face that now holds it.
std::vector<int> merge_coplanar_faces(std::vector<PlanarPolygon>& polygons, MergeStats& stats);

}  // namespace conicloc::maps
