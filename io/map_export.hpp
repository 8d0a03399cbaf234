#pragma once
// Exports of a PlaneMap for looking at it: a Wavefront OBJ mesh (any 3D viewer) and an SVG
// floor plan per storey (any browser).

#include <iosfwd>
#include <string>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::io {

struct ObjStats {
  int vertices = 0;
  int normals = 0;  ///< one per polygon written
  int faces = 0;    ///< triangles
  int objects = 0;  ///< `o` blocks: one per cell, plus one for polygons without a cell
  int groups = 0;   ///< `g` blocks: one per (cell, surface kind)
};

/// Writes every polygon, triangulated (holes kept open), in map-frame metres: one `o` per cell
/// (named by its gml:id), inside it one `g` and `usemtl` per surface kind (wall, floor, ceiling,
/// slope), one `vn` per polygon. `mtl_file` (may be empty) is named in an `mtllib` line.
ObjStats write_obj(const maps::PlaneMap& map, std::ostream& out, const std::string& mtl_file = "");

/// Writes `path` and, beside it, the materials `<path without .obj>.mtl` (a colour per kind).
/// Throws InputError naming the file if it cannot be written.
ObjStats write_obj_file(const maps::PlaneMap& map, const std::string& path);

/// A path drawn over the plan (a trajectory): each point on the storey whose height band holds it.
struct PlanPath {
  std::string label;                    ///< legend entry
  std::string colour = "#d62728";       ///< any SVG colour
  double width_px = 1.6;
  bool dashed = false;
  std::vector<Eigen::Vector3d> points;  ///< map frame, in order
};

struct FloorPlanOptions {
  double section_height_m = 1.0;  ///< cut above each storey's floor (doors open, windows cut)
  double pixels_per_m = 0.0;      ///< 0: fit the building into about `target_width_px`
  double target_width_px = 900.0;
  bool show_navigation = true;  ///< navigation graph: nodes, edges, doors
  bool show_labels = true;      ///< cell names
  std::vector<PlanPath> paths;  ///< drawn over everything else, listed in the legend
};

/// A standalone SVG document: one <g class="storey"> per storey (in a grid, highest storey
/// first), each with cell footprints coloured by class, walls and sloped surfaces cut
/// `section_height_m` above each cell's floor, openings in walls (windows), doors and the
/// navigation graph; a scale bar, a legend and a north arrow. y is flipped so that north (+y of
/// the map frame) is up.
std::string render_floor_plan_svg(const maps::PlaneMap& map, const FloorPlanOptions& options = {});

/// Writes render_floor_plan_svg() to `path`; throws InputError if it cannot be written.
void write_floor_plan_svg(const maps::PlaneMap& map, const std::string& path,
                          const FloorPlanOptions& options = {});

}  // namespace conicloc::io
