#pragma once
// A tiny building made in code, for tests and benchmarks that need a map with known geometry:
// two rooms side by side, each `room_x_m` × `room_y_m` × `height_m`, the shared wall at
// x = room_x_m with a door (a hole 0.9 m wide, 0.05..2.1 m high, centred at y = room_y_m / 2),
// a window hole (glass: returns nothing) in the far east wall, cells with footprints and a
// navigation graph of two nodes joined through the door. Room A: x ∈ [0, room_x], room B:
// x ∈ [room_x, 2 room_x]; y ∈ [0, room_y]; floor z = 0. Normals point into the rooms.

#include "maps/plane_map.hpp"

namespace conicloc::sim {

struct BoxBuildingSize {
  double room_x_m = 5.0;
  double room_y_m = 4.0;
  double height_m = 3.0;
};

maps::PlaneMap make_box_building(const BoxBuildingSize& size = {});

}  // namespace conicloc::sim
