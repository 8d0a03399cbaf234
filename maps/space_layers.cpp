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

bool declared_not_space(const std::string& layer_class) {
  return layer_class == "SENSOR" || layer_class == "LOGICAL" || layer_class == "TAGS";
}

// The layer of each raw cell: that of the state it is dual to (either side of the duality may
// be written), empty when it has none.
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
    if (by_id != state_by_id.end()) {
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

// The share of `cell`'s footprint inside one of `others`: of a 32 × 32 grid over its bounding
// box, the points inside it that also lie inside another.
double covered_fraction(const CellExtent& cell, const std::vector<const CellExtent*>& others) {
  Eigen::AlignedBox2d box;
  for (const auto& p : cell.footprint) box.extend(p);
  constexpr int kGrid = 32;
  int inside = 0, covered = 0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const Eigen::Vector2d p = box.min() + Eigen::Vector2d((i + 0.5) / kGrid * box.sizes().x(),
                                                            (j + 0.5) / kGrid * box.sizes().y());
      if (!ring_contains(cell.footprint, p)) continue;
      ++inside;
      covered += std::any_of(others.begin(), others.end(), [&](const CellExtent* other) {
        return ring_contains(other->footprint, p);
      });
    }
  }
  return inside > 0 ? static_cast<double>(covered) / inside : 0.0;
}

}  // namespace

bool cells_in_several_layers(const RawBuilding& raw) {
  const auto layers = layers_of_cells(raw);
  for (std::size_t r = 0; r < layers.size(); ++r) {
    if (!layers[r].empty() && layers[r] != layers.front()) return true;
  }
  return false;
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
  const auto rank = [&](const std::string& id) {
    return std::find(order.begin(), order.end(), id) - order.begin();
  };
  // Declared topographic first, then the most doors, then the first listed.
  const auto key = [&](const std::string& id) {
    return std::make_tuple(class_of[id] == "TOPOGRAPHIC", doors[id], -rank(id));
  };
  std::string topographic = doors.begin()->first;
  for (const auto& entry : doors) {
    if (key(entry.first) > key(topographic)) topographic = entry.first;
  }

  std::vector<const CellExtent*> rooms;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (layer_of[r] == topographic && !extents[r].footprint.empty()) rooms.push_back(&extents[r]);
  }
  std::map<std::string, int> left_out_count;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    const std::string& layer = layer_of[r];
    // A non-navigable cell (NonNavigableSpace: a column, a shaft, a block of furniture) is an
    // obstacle in the rooms, whatever layer holds it.
    if (layer.empty() || layer == topographic || extents[r].footprint.empty() ||
        !raw.cells[r].navigable)
      continue;
    const std::string& declared = class_of[layer];
    if (declared == "TOPOGRAPHIC") continue;
    bool leave = declared_not_space(declared);
    if (!leave && declared.empty()) {
      std::vector<const CellExtent*> level;
      for (const CellExtent* room : rooms) {
        if (share_heights(extents[r], *room)) level.push_back(room);
      }
      leave = covered_fraction(extents[r], level) > 0.5;
    }
    if (leave) {
      selection.left_out[r] = true;
      ++left_out_count[layer];
    }
  }
  for (const auto& [layer, count] : left_out_count) {
    const std::string& declared = class_of[layer];
    selection.notes.push_back(
        "space layer \"" + layer + "\": " + std::to_string(count) + " cell" +
        (count == 1 ? "" : "s") + " left out, " +
        (declared_not_space(declared)
             ? "its class is " + declared + " (not rooms)"
             : "each lies mostly inside cells of the topographic layer \"" + topographic +
                   "\" (zones drawn over the rooms, not walls)"));
  }
  return selection;
}

}  // namespace conicloc::maps
