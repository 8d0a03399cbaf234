#include "maps/build_plane_map.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <unordered_map>

#include "maps/cell_surfaces.hpp"
#include "maps/floorless_cells.hpp"
#include "maps/map_frame.hpp"
#include "maps/navigation_builder.hpp"
#include "maps/space_layers.hpp"
#include "maps/storeys.hpp"
#include "maps/surface_merge.hpp"
#include "maps/unit_plausibility.hpp"

namespace conicloc::maps {
namespace {

std::vector<Eigen::Vector3d> all_points(const RawBuilding& raw) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& cell : raw.cells) {
    for (const auto& shell : cell.shells) {
      for (const auto& polygon : shell.polygons)
        points.insert(points.end(), polygon.outer.begin(), polygon.outer.end());
    }
    for (const auto& polygon : cell.footprints_2d)
      points.insert(points.end(), polygon.outer.begin(), polygon.outer.end());
  }
  return points;
}

bool name_says_door(const std::string& class_name) {
  std::string lower = class_name;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.find("door") != std::string::npos;
}

// Boundary centres and door flags. A door: a boundary dual to a transition, between two navigable
// cells (known from the cells that list it and the states its transition connects); or a
// door-classed boundary (e.g. PublicSafetyDoor) of navigable cells only.
std::map<std::string, BoundaryInfo> classify_boundaries(const RawBuilding& raw, const PlaneMap& map,
                                                        const std::vector<int>& cell_of_raw,
                                                        const MapFrame& frame) {
  std::unordered_map<std::string, int> cell_by_id;
  for (std::size_t c = 0; c < map.cells.size(); ++c)
    cell_by_id.emplace(map.cells[c].id, static_cast<int>(c));
  std::unordered_map<std::string, int> cell_by_state;
  for (const auto& state : raw.states) {
    if (const auto it = cell_by_id.find(state.cell_id); it != cell_by_id.end())
      cell_by_state.emplace(state.id, it->second);
  }
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (cell_of_raw[r] >= 0 && !raw.cells[r].state_id.empty())
      cell_by_state.emplace(raw.cells[r].state_id, cell_of_raw[r]);
  }
  std::unordered_map<std::string, std::set<int>> adjacent;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (cell_of_raw[r] < 0) continue;
    for (const auto& id : raw.cells[r].boundary_ids) adjacent[id].insert(cell_of_raw[r]);
  }
  std::unordered_map<std::string, const RawTransition*> transition_by_id;
  for (const auto& transition : raw.transitions)
    transition_by_id.emplace(transition.id, &transition);
  for (const auto& transition : raw.transitions) {
    if (transition.boundary_id.empty()) continue;
    for (const auto& state : transition.state_ids) {
      if (const auto it = cell_by_state.find(state); it != cell_by_state.end())
        adjacent[transition.boundary_id].insert(it->second);
    }
  }
  std::map<std::string, BoundaryInfo> out;
  for (const auto& boundary : raw.boundaries) {
    BoundaryInfo info;
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    double area = 0.0;
    for (const auto& raw_polygon : boundary.polygons) {  // area centroid of the surfaces
      PlanarPolygon polygon;
      std::map<std::string, int> ignored;
      if (!fit_polygon(raw_polygon, frame, false, polygon, ignored)) continue;
      sum += polygon.area * polygon.centroid;
      area += polygon.area;
    }
    if (area > 0.0) {
      info.centre = sum / area;
    } else {
      for (const auto& line : boundary.lines) {  // mid-point of the curves' end points
        if (line.empty()) continue;
        sum += frame.to_map(line.front()) + frame.to_map(line.back());
        count += 2;
      }
      if (count > 0) info.centre = sum / count;
    }
    if (const auto it = transition_by_id.find(boundary.transition_id);
        it != transition_by_id.end()) {
      for (const auto& state : it->second->state_ids) {
        if (const auto c = cell_by_state.find(state); c != cell_by_state.end())
          adjacent[boundary.id].insert(c->second);
      }
    }
    const bool has_transition =
        transition_by_id.count(boundary.transition_id) > 0 ||
        std::any_of(raw.transitions.begin(), raw.transitions.end(),
                    [&](const RawTransition& t) { return t.boundary_id == boundary.id; });
    const std::set<int>& cells = adjacent[boundary.id];
    const bool all_navigable =
        std::all_of(cells.begin(), cells.end(), [&](int c) { return map.cells[c].navigable; });
    info.door = all_navigable && ((has_transition && cells.size() >= 2) ||
                                  (name_says_door(boundary.class_name) && !cells.empty()));
    out.emplace(boundary.id, info);
  }
  return out;
}

// Bounds, heights, footprint and representative point of every cell from its surfaces.
void describe_cells(PlaneMap& map, const RawBuilding& raw, const std::vector<int>& cell_of_raw,
                    const MapFrame& frame) {
  std::vector<std::vector<const PlanarPolygon*>> surfaces(map.cells.size());
  for (std::size_t i = 0; i < map.polygons.size(); ++i) {
    const PlanarPolygon& polygon = map.polygons[i];
    for (const int c : {polygon.cell, polygon.back_cell}) {
      if (c < 0) continue;
      map.cells[c].polygons.push_back(static_cast<int>(i));
      surfaces[c].push_back(&polygon);
    }
  }
  std::unordered_map<std::string, Eigen::Vector3d> state_point_of_cell;
  for (const auto& state : raw.states) {
    if (state.point) state_point_of_cell.emplace(state.cell_id, frame.to_map(*state.point));
  }
  (void)cell_of_raw;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    Cell& cell = map.cells[c];
    for (const PlanarPolygon* polygon : surfaces[c]) cell.bounds.extend(polygon->bounds);
    if (cell.bounds.isEmpty()) cell.bounds.extend(Eigen::Vector3d::Zero());
    cell.floor_z = cell.bounds.min().z();
    cell.ceiling_z = cell.bounds.max().z();
    cell.footprint = cell_footprint(surfaces[c]);
    const auto state = state_point_of_cell.find(cell.id);
    if (state != state_point_of_cell.end() &&
        ring_contains(cell.footprint, state->second.head<2>())) {
      cell.representative_point = {state->second.x(), state->second.y(), cell.floor_z};
    } else {
      const Eigen::Vector2d xy = point_inside(cell.footprint);
      cell.representative_point = {xy.x(), xy.y(), cell.floor_z};
    }
  }
}

// A cell's surfaces: its 3D shells, else its 2D footprint extruded (then true).
bool add_cell_surfaces(const RawCell& cell, int index, const MapFrame& frame,
                       double storey_height_m, std::vector<PlanarPolygon>& out,
                       SurfaceStats& stats) {
  if (!cell.shells.empty()) {
    add_cell_surfaces_3d(cell, index, frame, out, stats);
    return false;
  }
  add_cell_surfaces_2d(cell, index, frame, storey_height_m, out, stats);
  return true;
}

// Each raw cell's xy outline and heights, from its surfaces as the map will hold them.
std::vector<CellExtent> cell_extents(const RawBuilding& raw, const MapFrame& frame,
                                     double storey_height_m) {
  std::vector<CellExtent> extents(raw.cells.size());
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    std::vector<PlanarPolygon> surfaces;
    SurfaceStats ignored;
    add_cell_surfaces(raw.cells[r], 0, frame, storey_height_m, surfaces, ignored);
    if (surfaces.empty()) continue;
    std::vector<const PlanarPolygon*> pointers;
    Eigen::AlignedBox3d bounds;
    for (const auto& surface : surfaces) {
      pointers.push_back(&surface);
      bounds.extend(surface.bounds);
    }
    extents[r] = {cell_footprint(pointers), bounds.min().z(), bounds.max().z()};
  }
  return extents;
}

}  // namespace

BuildResult build_plane_map(const RawBuilding& raw, const BuildOptions& options) {
  BuildResult result;
  PlaneMap& map = result.map;
  BuildReport& report = result.report;
  report.warnings = raw.warnings;
  report.polygons_dropped = raw.polygons_dropped;

  const MapFrame frame =
      make_map_frame(raw.crs, all_points(raw), options.unit_scale, report.warnings);
  map.origin = frame.origin();
  map.crs = raw.crs;
  report.crs_handling = frame.description();

  // Cells of the topographic layer only: other layers' zones drawn over the rooms are no walls.
  LayerSelection layers;
  layers.left_out.assign(raw.cells.size(), false);
  if (cells_in_several_layers(raw)) {
    layers = select_topographic_cells(raw, cell_extents(raw, frame, options.storey_height_m));
    report.space_layer_notes = layers.notes;
    report.warnings.insert(report.warnings.end(), layers.notes.begin(), layers.notes.end());
  }

  // Cells with geometry, their surfaces facing into them.
  SurfaceStats stats;
  std::vector<int> cell_of_raw(raw.cells.size(), -1);
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    const RawCell& source = raw.cells[r];
    ++report.cells_by_class[source.class_name];
    if (layers.left_out[r]) {
      ++report.cells_left_out;
      continue;
    }
    if (source.shells.empty() && source.footprints_2d.empty()) {
      report.warnings.push_back("cell \"" + source.id + "\" (" + describe(source.place) +
                                ") has no geometry");
      continue;
    }
    const int index = static_cast<int>(map.cells.size());
    cell_of_raw[r] = index;
    Cell cell;
    cell.id = source.id;
    cell.name = source.name;
    cell.class_name = source.class_name;
    cell.navigable = source.navigable;
    map.cells.push_back(std::move(cell));
    if (add_cell_surfaces(source, index, frame, options.storey_height_m, map.polygons, stats))
      report.extruded_2d = true;
  }
  for (const auto& [reason, count] : stats.dropped) report.polygons_dropped[reason] += count;
  report.shells_flipped = stats.shells_flipped;
  report.open_shells = stats.open_shells;
  for (const auto& polygon : map.polygons) {
    report.max_flatness_m = std::max(report.max_flatness_m, polygon.flatness_m);
    if (polygon.flatness_m > 0.01) ++report.nonplanar_polygons;
  }

  // Doors between navigable cells become openings.
  const auto boundaries = classify_boundaries(raw, map, cell_of_raw, frame);
  MergeStats merge;
  std::vector<PlanarPolygon> doors;
  for (const auto& boundary : raw.boundaries) {
    if (!boundaries.at(boundary.id).door) continue;
    ++report.doors;
    for (const auto& polygon : boundary.polygons) {
      PlanarPolygon door;
      std::map<std::string, int> ignored;
      if (fit_polygon(polygon, frame, false, door, ignored)) doors.push_back(std::move(door));
    }
  }
  if (!options.close_doors) cut_door_openings(map.polygons, doors, merge);
  merge_coplanar_faces(map.polygons, merge);
  report.door_holes_cut = merge.door_holes_cut;
  report.door_surfaces_removed = merge.door_surfaces_removed;
  report.faces_merged = merge.faces_merged;
  report.two_sided_faces = merge.two_sided;
  report.partial_overlaps = merge.partial_overlaps;
  report.planes_after_merge = static_cast<int>(map.polygons.size());

  describe_cells(map, raw, cell_of_raw, frame);
  map.navigation =
      build_navigation_graph(raw, cell_of_raw, map, frame, boundaries, report.warnings);
  // The graph finds the floorless cells' thresholds; built again, its edges measure from the
  // floors found (its warnings were given the first time).
  if (assign_floors_to_floorless_cells(map, report.warnings) > 0) {
    std::vector<std::string> repeated;
    map.navigation = build_navigation_graph(raw, cell_of_raw, map, frame, boundaries, repeated);
  }
  assign_storeys(map);
  for (const auto& polygon : map.polygons) map.bounds.extend(polygon.bounds);

  // Sizes a wrong unit gives away: rooms lower than 1.8 m or higher than 12 m, kilometre halls.
  if (!map.cells.empty()) {
    const UnitCheck units = check_units(map, options.unit_scale, !report.extruded_2d);
    if (!units.plausible) {
      std::ostringstream warning;
      warning << "implausible sizes: " << units.problem << "; is the model in other units";
      if (units.suggested_unit_scale)
        warning << " (try --unit-scale " << *units.suggested_unit_scale << ")";
      warning << "?";
      report.warnings.push_back(warning.str());
    }
  }
  return result;
}

}  // namespace conicloc::maps
