// storeys_layout(): identical storeys stacked, joined by straight stairs; the floor plate repeated
// along the corridor when the scale asks for it.
#include <algorithm>
#include <cmath>

#include "sim/building_layouts.hpp"
#include "sim/layout_parts.hpp"
#include "sim/seeded_draw.hpp"

namespace conicloc::sim {

PrismBuilding storeys_layout(std::mt19937_64& rng, const BuildingScale& scale) {
  // The count is drawn even when the scale fixes it, so every other dimension stays the seed's.
  const int drawn_storeys = draw_int(rng, 2, 4);
  const int storeys = scale.storeys > 0 ? scale.storeys : drawn_storeys;
  const int tiles = scale.plate_tiles;
  const double height = draw_length(rng, 2.7, 3.2);
  const double rise = height + draw_length(rng, 0.2, 0.3);  // storey to storey, over the slab
  const double stair_deg = std::round(draw_uniform(rng, 32.0, 38.0) * 10.0) / 10.0;
  const double flight = std::round(100.0 * rise / std::tan(stair_deg * M_PI / 180.0)) / 100.0;
  const double landing = draw_length(rng, 1.2, 1.5);
  const double lane = 2.0 * landing + flight;  // length of one stair
  const double stair_width = draw_length(rng, 1.8, 2.4);
  const double width = draw_length(rng, 2.0, 3.0);  // corridor
  const double south = draw_length(rng, 4.0, 6.0);  // room depths
  const double north = draw_length(rng, 4.0, 6.0);
  // Stairwell lanes, side by side north of it. A scaled building always keeps room for both, so
  // its floor plate is the same whatever the storey count.
  const int lanes = scale.storeys > 0 ? 2 : std::min(2, storeys - 1);
  const double north_start = lanes * lane;
  const double plate = north_start + draw_length(rng, 8.0, 16.0);  // one floor plate along x
  const double length = tiles * plate;                             // the corridor
  const int south_rooms = draw_int(rng, 2, 4);
  const int north_rooms = draw_int(rng, 1, 3);
  const double y_north = south + width;  // the corridor's north wall

  PrismBuilding b;
  // Every storey draws its rooms from a copy of the same generator state: identical floor plans.
  const std::mt19937_64 plan = rng;
  for (int k = 0; k < storeys; ++k) {
    const std::string tag = "F" + std::to_string(k);
    const std::string corridor = tag + "-Corridor";
    const double z = k * rise;
    b.cells.push_back(corridor_cell(
        corridor, "Corridor, floor " + std::to_string(k),
        {{0.0, south}, {length, south}, {length, y_north}, {0.0, y_north}}, z, height));
    std::mt19937_64 storey_rng = plan;
    // Plate j spans x ∈ [j·plate, (j + 1)·plate]; its rooms are drawn after plate j − 1's, so the
    // plates differ from each other while the storeys stay identical. Plate 0 keeps the stairwell
    // lanes north of the corridor and the ids of an untiled building.
    for (int j = 0; j < tiles; ++j) {
      const std::string plate_tag = j == 0 ? tag : tag + "-P" + std::to_string(j);
      const std::string plate_label =
          j == 0 ? "floor " + std::to_string(k)
                 : "floor " + std::to_string(k) + " plate " + std::to_string(j);
      const double x0 = j * plate;
      RoomRow row;
      row.corridor_id = corridor;
      row.floor_z = z;
      row.height_m = height;
      row.x_start = x0;
      row.end_x_lo = row.end_x_hi = x0 + plate;
      row.id_prefix = plate_tag + "-South";
      row.label = plate_label + " south";
      row.rooms = south_rooms;
      row.y_hi = south;
      add_room_row(row, storey_rng, b);
      row.id_prefix = plate_tag + "-North";
      row.label = plate_label + " north";
      row.rooms = north_rooms;
      row.corridor_north = false;
      row.x_start = j == 0 ? north_start : x0;
      row.y_lo = y_north;
      row.y_hi = y_north + north;
      add_room_row(row, storey_rng, b);
    }
  }

  // Stair k joins floors k and k + 1 in lane k % 2: bottom landing, flight, top landing (east).
  for (int k = 0; k + 1 < storeys; ++k) {
    const double x0 = (k % 2) * lane;
    const double z0 = k * rise;
    const double z1 = z0 + rise;
    PrismCell stair;
    stair.id = "Stair" + std::to_string(k);
    stair.class_name = "navi:TransitionSpace";
    stair.name = "Staircase, floor " + std::to_string(k) + " to " + std::to_string(k + 1);
    stair.description = "stair, " + fixed(stair_deg, 1) + " deg flight";
    stair.footprint = {{x0, y_north},
                       {x0 + lane, y_north},
                       {x0 + lane, y_north + stair_width},
                       {x0, y_north + stair_width}};
    stair.floor_z = z0;
    stair.floor_profile = {
        {x0, z0}, {x0 + landing, z0}, {x0 + landing + flight, z1}, {x0 + lane, z1}};
    stair.ceiling = {z1 + height, 0.0, 0.0};
    const double door_width = 0.9;
    const double inset = 0.5 * (landing - door_width);  // door centred on the landing
    for (const bool top : {false, true}) {
      const int floor = top ? k + 1 : k;
      const double start = top ? x0 + lane - landing + inset : x0 + inset;
      DoorOpening door;
      door.id = "F" + std::to_string(floor) + "-Door-" + stair.id;
      door.name = "door corridor floor " + std::to_string(floor) + " - " + stair.name;
      door.p0 = {start, y_north};
      door.p1 = {start + door_width, y_north};
      door.z0 = top ? z1 : z0;
      door.z1 = door.z0 + kDoorHeight_m;
      door.cells = {"F" + std::to_string(floor) + "-Corridor", stair.id};
      b.doors.push_back(std::move(door));
    }
    b.cells.push_back(std::move(stair));
  }

  b.name = "conicloc generated storeys building";
  b.summary = {
      std::to_string(storeys) + " identical storeys " + fixed(rise) + " m apart (clear height " +
          fixed(height) + " m), each a corridor " + fixed(length) + " m x " + fixed(width) +
          " m with " + std::to_string(tiles * south_rooms) + " rooms south",
      "and " + std::to_string(tiles * north_rooms) + " north of it" +
          (tiles > 1 ? " (" + std::to_string(tiles) + " floor plates of " + fixed(plate) + " m)"
                     : std::string()) +
          "; " + std::to_string(storeys - 1) + " straight stairs (" + fixed(stair_deg, 1) +
          " deg, " + fixed(stair_width) +
          " m wide, TransitionSpace cells with a sloped floor) join them,",
      "alternating between two lanes north of the corridor; doors from each corridor to the "
      "stair landings."};
  return b;
}

}  // namespace conicloc::sim
