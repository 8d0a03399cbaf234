#include "maps/space_layers.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <tuple>
#include <unordered_map>

namespace conicloc::maps {
namespace {

std::string upper_trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  text = text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

// 1.0's classes and 2.0's themes.
bool declared_not_space(const std::string& layer_class) {
  return layer_class == "SENSOR" || layer_class == "LOGICAL" || layer_class == "TAGS" ||
         layer_class == "VIRTUAL";
}
bool declared_space(const std::string& layer_class) {
  return layer_class == "TOPOGRAPHIC" || layer_class == "PHYSICAL";
}

// The layer of each raw cell: the one it is written in (2.0), else that of the state it is dual
// to (either side of the duality may be written), empty when it has none.
std::vector<std::string> layers_of_cells(const RawBuilding& raw) {
  std::unordered_map<std::string, const RawState*> state_by_id;
  std::unordered_map<std::string, const RawState*> state_by_cell;
  for (const auto& state : raw.states) {
    state_by_id.emplace(state.id, &state);
    if (!state.cell_id.empty()) state_by_cell.emplace(state.cell_id, &state);
  }
  std::vector<std::string> layers(raw.cells.size());
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    const auto by_id = state_by_id.find(raw.cells[r].state_id);
    const auto by_cell = state_by_cell.find(raw.cells[r].id);
    if (!raw.cells[r].layer.empty()) {
      layers[r] = raw.cells[r].layer;
    } else if (by_id != state_by_id.end()) {
      layers[r] = by_id->second->layer;
    } else if (by_cell != state_by_cell.end()) {
      layers[r] = by_cell->second->layer;
    }
  }
  return layers;
}

// The two cells share more than half of the lower one's height.
bool share_heights(const CellExtent& a, const CellExtent& b) {
  const double shared = std::min(a.ceiling_z, b.ceiling_z) - std::max(a.floor_z, b.floor_z);
  const double lower = std::min(a.ceiling_z - a.floor_z, b.ceiling_z - b.floor_z);
  return shared > 0.5 * lower;
}

// How a cell lies over the topographic cells: of a 32 × 32 grid over its bounding box, the points
// inside it (its area in grid points), those inside any of `rooms`, and per room those inside it.
struct Overlap {
  int inside = 0;
  int covered = 0;
  std::vector<int> per_room;
};

Overlap overlap_with(const CellExtent& cell, const std::vector<const CellExtent*>& rooms) {
  Eigen::AlignedBox2d box;
  for (const auto& p : cell.footprint) box.extend(p);
  constexpr int kGrid = 32;
  Overlap overlap;
  overlap.per_room.assign(rooms.size(), 0);
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const Eigen::Vector2d p = box.min() + Eigen::Vector2d((i + 0.5) / kGrid * box.sizes().x(),
                                                            (j + 0.5) / kGrid * box.sizes().y());
      if (!ring_contains(cell.footprint, p)) continue;
      ++overlap.inside;
      bool covered = false;
      for (std::size_t k = 0; k < rooms.size(); ++k) {
        if (share_heights(cell, *rooms[k]) && ring_contains(rooms[k]->footprint, p)) {
          ++overlap.per_room[k];
          covered = true;
        }
      }
      overlap.covered += covered ? 1 : 0;
    }
  }
  return overlap;
}

// A layer of zones drawn over the rooms: most of its (navigable) cells' area lies in rooms, and
// one of its cells crosses a wall between two rooms side by side (each holds a tenth of it) —
// which no room, corridor or obstacle does.
bool zones_over_rooms(const std::vector<const CellExtent*>& cells,
                      const std::vector<const CellExtent*>& rooms) {
  double area = 0.0, covered = 0.0;
  bool crosses = false;
  for (const CellExtent* cell : cells) {
    const Overlap overlap = overlap_with(*cell, rooms);
    if (overlap.inside == 0) continue;
    Eigen::AlignedBox2d box;
    for (const auto& p : cell->footprint) box.extend(p);
    const double point_area = box.volume() / (32.0 * 32.0);
    area += point_area * overlap.inside;
    covered += point_area * overlap.covered;
    std::vector<std::size_t> holding;
    for (std::size_t k = 0; k < rooms.size(); ++k) {
      if (overlap.per_room[k] > overlap.inside / 10) holding.push_back(k);
    }
    for (std::size_t a = 0; a < holding.size() && !crosses; ++a) {
      for (std::size_t b = a + 1; b < holding.size() && !crosses; ++b)
        crosses = share_heights(*rooms[holding[a]], *rooms[holding[b]]);
    }
  }
  return crosses && covered > 0.5 * area;
}

}  // namespace

bool cells_in_several_layers(const RawBuilding& raw) {
  const auto layers = layers_of_cells(raw);
  const auto first = std::find_if(layers.begin(), layers.end(),
                                  [](const std::string& layer) { return !layer.empty(); });
  return first != layers.end() && std::any_of(first, layers.end(), [&](const std::string& layer) {
           return !layer.empty() && layer != *first;
         });
}

LayerSelection select_topographic_cells(const RawBuilding& raw,
                                        const std::vector<CellExtent>& extents) {
  LayerSelection selection;
  selection.left_out.assign(raw.cells.size(), false);
  const std::vector<std::string> layer_of = layers_of_cells(raw);
  std::map<std::string, std::string> class_of;  // layer id -> declared class, upper case
  std::vector<std::string> order;               // layers as listed
  for (const auto& layer : raw.layers) {
    class_of.emplace(layer.id, upper_trimmed(layer.layer_class));
    order.push_back(layer.id);
  }
  // Layers that hold cells with geometry, and the doors each one's transitions pass through.
  std::map<std::string, int> doors;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (!layer_of[r].empty() && !extents[r].footprint.empty()) doors.emplace(layer_of[r], 0);
  }
  if (doors.size() < 2) return selection;
  std::unordered_map<std::string, std::string> layer_of_state;
  for (const auto& state : raw.states) layer_of_state.emplace(state.id, state.layer);
  for (const auto& transition : raw.transitions) {
    if (transition.boundary_id.empty() || transition.state_ids.empty()) continue;
    const auto it = layer_of_state.find(transition.state_ids.front());
    if (it != layer_of_state.end() && doors.count(it->second)) ++doors[it->second];
  }
  // The topographic layer: declared so, else not declared otherwise, then the most doors. When
  // that leaves a tie, the file does not say which layer is the building: nothing is left out.
  const auto key = [&](const std::string& id) {
    return std::make_tuple(declared_space(class_of[id]), !declared_not_space(class_of[id]),
                           doors[id]);
  };
  std::string topographic = doors.begin()->first;
  for (const auto& entry : doors) {
    if (key(entry.first) > key(topographic)) topographic = entry.first;
  }
  for (const auto& entry : doors) {
    if (entry.first != topographic && key(entry.first) == key(topographic)) {
      selection.notes.push_back("space layers \"" + topographic + "\" and \"" + entry.first +
                                "\" both could be the building's rooms (no class, " +
                                std::to_string(doors[topographic]) +
                                " doors each): every cell kept");
      return selection;
    }
  }
  const std::string why =
      declared_space(class_of[topographic])
          ? "declared " + class_of[topographic]
          : "its transitions pass " + std::to_string(doors[topographic]) + " doors";

  std::vector<const CellExtent*> rooms;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (layer_of[r] == topographic && !extents[r].footprint.empty()) rooms.push_back(&extents[r]);
  }
  for (const std::string& layer : order) {
    if (layer == topographic || !doors.count(layer)) continue;
    const std::string& declared = class_of[layer];
    if (declared_space(declared)) continue;
    // Its navigable cells; a non-navigable one (NonNavigableSpace: a column, a shaft) is an
    // obstacle in the rooms, whatever layer holds it.
    std::vector<std::size_t> cells;
    std::vector<const CellExtent*> cell_extents;
    for (std::size_t r = 0; r < raw.cells.size(); ++r) {
      if (layer_of[r] != layer || extents[r].footprint.empty() || !raw.cells[r].navigable) continue;
      cells.push_back(r);
      cell_extents.push_back(&extents[r]);
    }
    if (cells.empty()) continue;
    std::string reason;
    if (declared_not_space(declared)) {
      reason = "its class is " + declared + " (not rooms)";
    } else if (zones_over_rooms(cell_extents, rooms)) {
      reason = "its cells lie over the rooms of the topographic layer \"" + topographic + "\" (" +
               why + ") and cross their walls: zones, not walls";
    } else {
      continue;
    }
    for (const std::size_t r : cells) selection.left_out[r] = true;
    selection.notes.push_back("space layer \"" + layer + "\": " + std::to_string(cells.size()) +
                              " cell" + (cells.size() == 1 ? "" : "s") + " left out (\"" +
                              raw.cells[cells.front()].id + "\"" +
                              (cells.size() > 1 ? ", ..." : "") + "), " + reason);
  }
  return selection;
}

}  // namespace conicloc::maps
