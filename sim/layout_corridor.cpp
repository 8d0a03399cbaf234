// corridor_layout() and wings_layout(): one storey of rooms off corridors.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "sim/building_layouts.hpp"
#include "sim/layout_parts.hpp"
#include "sim/seeded_draw.hpp"

namespace conicloc::sim {
namespace {

constexpr double kDegree = M_PI / 180.0;

// "East" -> "West" and "east" -> "west" in ids and names of the mirrored wing.
std::string mirrored(std::string text) {
  for (const auto& [from, to] : {std::pair{"East", "West"}, std::pair{"east", "west"}}) {
    for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at))
      text.replace(at, 4, to);
  }
  return text;
}

// The mirror image x -> −x of a cell; the footprint is reversed to stay counter-clockwise.
PrismCell mirrored(const PrismCell& cell) {
  PrismCell out = cell;
  out.id = mirrored(cell.id);
  out.name = mirrored(cell.name);
  out.description = mirrored(cell.description);
  out.footprint.clear();
  for (auto it = cell.footprint.rbegin(); it != cell.footprint.rend(); ++it)
    out.footprint.emplace_back(-it->x(), it->y());
  out.ceiling.y() = -cell.ceiling.y();
  return out;
}

DoorOpening mirrored(const DoorOpening& door) {
  DoorOpening out = door;
  out.id = mirrored(door.id);
  out.name = mirrored(door.name);
  out.p0.x() = -door.p0.x();
  out.p1.x() = -door.p1.x();
  out.cells = {mirrored(door.cells[0]), mirrored(door.cells[1])};
  return out;
}

}  // namespace

PrismBuilding corridor_layout(std::mt19937_64& rng) {
  const double length = draw_length(rng, 20.0, 40.0);
  const double width = draw_length(rng, 2.0, 3.0);
  const double south = draw_length(rng, 4.0, 6.0);  // room depths
  const double north = draw_length(rng, 4.0, 6.0);
  const double height = draw_length(rng, 2.8, 3.4);
  const double facade_deg = std::round(draw_uniform(rng, 10.0, 35.0) * 10.0) / 10.0;
  const double lean = draw_int(rng, 0, 1) == 0 ? 1.0 : -1.0;
  const int rooms = draw_int(rng, 4, 8);
  const int south_rooms = rooms / 2 + (rooms % 2 == 1 ? draw_int(rng, 0, 1) : 0);
  const double depth = south + width + north;
  // The east facade, slanted off the y axis: x = length at mid-depth.
  auto facade_x = [&](double y) {
    return length + lean * std::tan(facade_deg * kDegree) * (y - 0.5 * depth);
  };

  PrismBuilding b;
  b.cells.push_back(corridor_cell("Corridor", "Corridor",
                                  {{0.0, south},
                                   {facade_x(south), south},
                                   {facade_x(south + width), south + width},
                                   {0.0, south + width}},
                                  0.0, height));
  RoomRow row;
  row.corridor_id = "Corridor";
  row.height_m = height;
  row.id_prefix = "South";
  row.label = "south";
  row.rooms = south_rooms;
  row.end_x_lo = facade_x(0.0);
  row.end_x_hi = facade_x(south);
  row.y_hi = south;
  add_room_row(row, rng, b);
  row.id_prefix = "North";
  row.label = "north";
  row.rooms = rooms - south_rooms;
  row.corridor_north = false;
  row.end_x_lo = facade_x(south + width);
  row.end_x_hi = facade_x(depth);
  row.y_lo = south + width;
  row.y_hi = depth;
  add_room_row(row, rng, b);

  PrismCell& sloped = b.cells[draw_int(rng, 1, rooms)];
  const bool south_side = sloped.centroid().y() < south;
  slope_ceiling(sloped, south_side ? south : south + width,
                draw_uniform(rng, 12.0, 20.0) * kDegree);

  b.name = "conicloc generated corridor building";
  b.summary = {"One storey, " + fixed(length) + " m x " + fixed(depth) + " m, clear height " +
                   fixed(height) + " m: a corridor " + fixed(width) + " m wide with " +
                   std::to_string(south_rooms) + " rooms south and " +
                   std::to_string(rooms - south_rooms) + " north of it,",
               "each through a door; " + sloped.name +
                   " has a sloped ceiling; the east facade is slanted " + fixed(facade_deg, 1) +
                   " deg off the y axis (a non-Manhattan wall)."};
  return b;
}

PrismBuilding wings_layout(std::mt19937_64& rng) {
  const double lobby_width = draw_length(rng, 6.0, 10.0);
  const double lobby_height = draw_length(rng, 3.5, 6.0);
  const double width = draw_length(rng, 2.0, 3.0);  // wing corridors
  const double south = draw_length(rng, 4.0, 6.0);  // room depths
  const double north = draw_length(rng, 4.0, 6.0);
  const double wing_length = draw_length(rng, 12.0, 24.0);
  const double height = draw_length(rng, 2.8, 3.4);
  const double lobby_south = -0.5 * width - south - draw_length(rng, 0.0, 2.0);
  const double lobby_north = 0.5 * width + north + draw_length(rng, 0.0, 2.0);
  const double door_width = draw_length(rng, 1.2, std::min(1.8, width - 0.4));
  const double x0 = 0.5 * lobby_width;  // where the east wing begins
  const double x1 = x0 + wing_length;

  PrismBuilding b;
  PrismCell lobby;
  lobby.id = "Lobby";
  lobby.name = "Lobby";
  lobby.description = "central lobby between the two wings";
  lobby.footprint = {{-x0, lobby_south}, {x0, lobby_south}, {x0, lobby_north}, {-x0, lobby_north}};
  lobby.ceiling = {lobby_height, 0.0, 0.0};
  b.cells.push_back(std::move(lobby));

  // The east wing, then its mirror image as the west wing.
  const std::size_t first_east = b.cells.size();
  b.cells.push_back(corridor_cell(
      "East-Corridor", "east wing corridor",
      {{x0, -0.5 * width}, {x1, -0.5 * width}, {x1, 0.5 * width}, {x0, 0.5 * width}}, 0.0, height));
  DoorOpening entry;
  entry.id = "East-Door";
  entry.name = "door Lobby - east wing corridor";
  entry.p0 = {x0, -0.5 * door_width};
  entry.p1 = {x0, 0.5 * door_width};
  entry.z1 = kDoorHeight_m;
  entry.cells = {"Lobby", "East-Corridor"};
  b.doors.push_back(entry);
  RoomRow row;
  row.corridor_id = "East-Corridor";
  row.height_m = height;
  row.x_start = x0;
  row.end_x_lo = row.end_x_hi = x1;
  row.id_prefix = "East-South";
  row.label = "east wing south";
  row.rooms = draw_int(rng, 2, 4);
  row.y_lo = -0.5 * width - south;
  row.y_hi = -0.5 * width;
  add_room_row(row, rng, b);
  const int south_rooms = row.rooms;
  row.id_prefix = "East-North";
  row.label = "east wing north";
  row.rooms = draw_int(rng, 2, 4);
  row.corridor_north = false;
  row.y_lo = 0.5 * width;
  row.y_hi = 0.5 * width + north;
  add_room_row(row, rng, b);
  const std::size_t east_cells = b.cells.size();
  const std::size_t east_doors = b.doors.size();
  for (std::size_t c = first_east; c < east_cells; ++c) b.cells.push_back(mirrored(b.cells[c]));
  for (std::size_t d = 0; d < east_doors; ++d) b.doors.push_back(mirrored(b.doors[d]));

  // One asymmetry, as real buildings have: a sloped ceiling in one east room.
  PrismCell& sloped =
      b.cells[draw_int(rng, static_cast<int>(first_east) + 1, static_cast<int>(east_cells) - 1)];
  const bool south_side = sloped.centroid().y() < 0.0;
  slope_ceiling(sloped, (south_side ? -0.5 : 0.5) * width, draw_uniform(rng, 12.0, 20.0) * kDegree);

  b.name = "conicloc generated wings building";
  b.summary = {
      "One storey: a lobby " + fixed(lobby_width) + " m x " + fixed(lobby_north - lobby_south) +
          " m (" + fixed(lobby_height) + " m high) between two mirror-image wings,",
      "each a corridor " + fixed(wing_length) + " m x " + fixed(width) + " m with " +
          std::to_string(south_rooms) + " rooms south and " + std::to_string(row.rooms) +
          " north of it (clear height " + fixed(height) + " m);",
      "deliberately ambiguous: only " + sloped.name + " (sloped ceiling) breaks the symmetry."};
  return b;
}

}  // namespace conicloc::sim
