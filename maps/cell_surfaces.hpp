#pragma once
// The bounding surfaces of one cell as PlanarPolygons in the map frame, normals into the cell:
// 3D shells oriented by their signed volume, 2D footprints extruded to walls, floor and ceiling.

#include <map>
#include <string>
#include <vector>

#include "maps/map_frame.hpp"
#include "maps/planar_polygon.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::maps {

struct SurfaceStats {
  std::map<std::string, int> dropped;  ///< reason -> count
  int shells_flipped = 0;              ///< shells whose rings ran the wrong way (outward normals)
  int open_shells = 0;                 ///< shells not closed: oriented per polygon instead
};

/// Fits every polygon of the cell's shells; reorients each shell so its normals point into the
/// cell's free space. Appends to `out` with `cell` set.
void add_cell_surfaces_3d(const RawCell& cell, int cell_index, const MapFrame& frame,
                          std::vector<PlanarPolygon>& out, SurfaceStats& stats);

/// Extrudes the cell's 2D footprint polygons by `height_m`: one wall per footprint edge (holes
/// too), a floor and a ceiling, all facing into the cell.
void add_cell_surfaces_2d(const RawCell& cell, int cell_index, const MapFrame& frame,
                          double height_m, std::vector<PlanarPolygon>& out, SurfaceStats& stats);

/// Fits a raw polygon in the map frame, counting a drop reason on failure.
bool fit_polygon(const RawPolygon& raw, const MapFrame& frame, bool reverse, PlanarPolygon& out,
                 std::map<std::string, int>& dropped);

/// xy outline of a cell: the outer ring of its largest upward-facing surface, counter-clockwise;
/// the convex hull of all its vertices when it has none.
Ring2 cell_footprint(const std::vector<const PlanarPolygon*>& surfaces);

/// A point strictly inside `ring` (the centroid when inside, else the middle of the widest
/// chord through the centroid's height).
Eigen::Vector2d point_inside(const Ring2& ring);

}  // namespace conicloc::maps
