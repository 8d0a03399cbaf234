// hall_layout(): a large open hall with a grid of pillars and rooms along one wall.
#include <algorithm>
#include <cmath>

#include "sim/building_layouts.hpp"
#include "sim/layout_parts.hpp"
#include "sim/seeded_draw.hpp"

namespace conicloc::sim {

PrismBuilding hall_layout(std::mt19937_64& rng) {
  const double width = draw_length(rng, 15.0, 30.0);  // x
  const double depth = draw_length(rng, 15.0, 30.0);  // y
  const double hall_height = draw_length(rng, 4.0, 6.0);
  const double room_depth = draw_length(rng, 4.0, 6.0);
  const double room_height = draw_length(rng, 2.8, 3.2);
  const double spacing = draw_length(rng, 4.5, 6.5);
  const double pillar = draw_length(rng, 0.4, 0.8);  // side of the square section
  const double aisle = draw_length(rng, 3.0, 4.0);   // pillar-free band along the south wall
  const double y0 = room_depth;                      // the hall's south wall

  PrismBuilding b;
  PrismCell hall;
  hall.id = "Hall";
  hall.name = "Hall";
  hall.description = "open hall with pillars";
  hall.footprint = {{0.0, y0}, {width, y0}, {width, y0 + depth}, {0.0, y0 + depth}};
  hall.ceiling = {hall_height, 0.0, 0.0};
  // Routes cross a cell in straight lines between its State and its doors (sim/navigation_route),
  // and all doors are in the south wall: with the State in the aisle, no route meets a pillar.
  hall.state_xy = Eigen::Vector2d(std::round(50.0 * width) / 100.0, y0 + 1.2);
  const int columns = std::max(2, static_cast<int>(std::lround(width / spacing)));
  int rows = 0;
  for (double y = y0 + aisle; y <= y0 + depth - 2.0; y += spacing, ++rows) {
    for (int i = 0; i < columns; ++i) {
      const double x = std::round(100.0 * (i + 0.5) * width / columns) / 100.0;
      const double h = 0.5 * pillar;
      hall.pillars.push_back({{x - h, y - h}, {x + h, y - h}, {x + h, y + h}, {x - h, y + h}});
    }
  }
  b.cells.push_back(std::move(hall));

  RoomRow row;
  row.id_prefix = "South";
  row.label = "south";
  row.corridor_id = "Hall";
  row.rooms = draw_int(rng, 2, 4);
  row.end_x_lo = row.end_x_hi = width;
  row.y_hi = y0;
  row.height_m = room_height;
  add_room_row(row, rng, b);

  b.name = "conicloc generated hall building";
  b.summary = {"One storey: an open hall " + fixed(width) + " m x " + fixed(depth) + " m, " +
                   fixed(hall_height) + " m high, with " + std::to_string(columns) + " x " +
                   std::to_string(rows) + " square pillars (" + fixed(pillar) + " m, " +
                   fixed(spacing) + " m apart;",
               "interior shells of the hall's solid), and " + std::to_string(row.rooms) +
                   " rooms along its south wall (" + fixed(room_depth) + " m deep, " +
                   fixed(room_height) + " m high), each through a door."};
  return b;
}

}  // namespace conicloc::sim
