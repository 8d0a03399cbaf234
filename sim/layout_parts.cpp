#include "sim/layout_parts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sim/seeded_draw.hpp"

namespace conicloc::sim {

void add_room_row(const RoomRow& row, std::mt19937_64& rng, PrismBuilding& building) {
  // Widths in proportion to weights in [0.7, 1.3], measured where the end wall is nearest, so a
  // slanted end only ever widens the last room.
  const double length = std::min(row.end_x_lo, row.end_x_hi) - row.x_start;
  std::vector<double> weights;
  double sum = 0.0;
  for (int i = 0; i < row.rooms; ++i) {
    weights.push_back(draw_uniform(rng, 0.7, 1.3));
    sum += weights.back();
  }
  std::vector<double> splits = {row.x_start};
  for (int i = 0; i + 1 < row.rooms; ++i)
    splits.push_back(std::round((splits.back() + length * weights[i] / sum) * 100.0) / 100.0);

  const double door_y = row.corridor_north ? row.y_hi : row.y_lo;
  for (int i = 0; i < row.rooms; ++i) {
    const bool last = i + 1 == row.rooms;
    const double x0 = splits[i];
    PrismCell room;
    room.id = row.id_prefix + "-Room" + std::to_string(i + 1);
    room.name = row.label + " room " + std::to_string(i + 1);
    room.description = "room off " + row.corridor_id;
    room.floor_z = row.floor_z;
    room.ceiling = {row.floor_z + row.height_m, 0.0, 0.0};
    double wall_end = 0.0;  // where the room's corridor wall ends
    if (last) {
      room.footprint = {
          {x0, row.y_lo}, {row.end_x_lo, row.y_lo}, {row.end_x_hi, row.y_hi}, {x0, row.y_hi}};
      wall_end = row.corridor_north ? row.end_x_hi : row.end_x_lo;
    } else {
      wall_end = splits[i + 1];
      room.footprint = {{x0, row.y_lo}, {wall_end, row.y_lo}, {wall_end, row.y_hi}, {x0, row.y_hi}};
    }
    DoorOpening door;
    door.id = row.id_prefix + "-Door" + std::to_string(i + 1);
    door.name = "door " + room.name + " - " + row.corridor_id;
    const double width = draw_length(rng, 0.9, 1.1);
    const double start = draw_length(rng, x0 + 0.3, wall_end - 0.3 - width);
    door.p0 = {start, door_y};
    door.p1 = {start + width, door_y};
    door.z0 = row.floor_z;
    door.z1 = row.floor_z + kDoorHeight_m;
    door.cells = {room.id, row.corridor_id};
    building.cells.push_back(std::move(room));
    building.doors.push_back(std::move(door));
  }
}

PrismCell corridor_cell(const std::string& id, const std::string& name, maps::Ring2 footprint,
                        double floor_z, double height_m) {
  PrismCell corridor;
  corridor.id = id;
  corridor.class_name = "navi:TransitionSpace";
  corridor.name = name;
  corridor.description = "corridor";
  corridor.footprint = std::move(footprint);
  corridor.floor_z = floor_z;
  corridor.ceiling = {floor_z + height_m, 0.0, 0.0};
  return corridor;
}

void slope_ceiling(PrismCell& room, double y_wall, double angle_rad) {
  double y_lo = room.footprint.front().y();
  double y_hi = y_lo;
  for (const auto& p : room.footprint) y_lo = std::min(y_lo, p.y()), y_hi = std::max(y_hi, p.y());
  const double top = room.ceiling.x();
  const double slope = std::min(std::tan(angle_rad), (top - room.floor_z - 1.6) / (y_hi - y_lo));
  // z = top − slope · (distance from the wall), the distance growing away from y_wall.
  const double toward = room.centroid().y() < y_wall ? 1.0 : -1.0;
  room.ceiling = {top - slope * toward * y_wall, 0.0, slope * toward};
  room.description += ", under a ceiling sloping down away from it";
}

std::string fixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace conicloc::sim
