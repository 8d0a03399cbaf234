#pragma once
// Parts the generated layouts share: a row of rooms along one side of a corridor (or hall), each
// with a door into it, widths and door positions drawn from the generator's seed; corridors;
// sloped ceilings.

#include <random>
#include <string>

#include "sim/prism_building.hpp"

namespace conicloc::sim {

constexpr double kDoorHeight_m = 2.1;

/// The band y ∈ [y_lo, y_hi] from x = x_start to the band's end wall, which runs from
/// (end_x_lo, y_lo) to (end_x_hi, y_hi): a slanted wall when they differ.
struct RoomRow {
  std::string id_prefix;       ///< room ids are "<prefix>-Room<i>", door ids "<prefix>-Door<i>"
  std::string label;           ///< names: "<label> room <i>"
  std::string corridor_id;     ///< the cell every room opens into
  bool corridor_north = true;  ///< the corridor lies at y_hi (else at y_lo)
  int rooms = 2;
  double x_start = 0.0;
  double end_x_lo = 0.0;
  double end_x_hi = 0.0;
  double y_lo = 0.0;
  double y_hi = 0.0;
  double floor_z = 0.0;
  double height_m = 3.0;  ///< clear height of the rooms
};

/// Appends the rooms (GeneralSpace cells, level floor and ceiling) and their doors (0.9–1.1 m
/// wide, kDoorHeight_m high, at least 0.3 m from the room's corners) to `building`. Precondition:
/// every room is at least 1.8 m wide along the corridor.
void add_room_row(const RoomRow& row, std::mt19937_64& rng, PrismBuilding& building);

/// A corridor: a TransitionSpace with a level floor and ceiling.
PrismCell corridor_cell(const std::string& id, const std::string& name, maps::Ring2 footprint,
                        double floor_z, double height_m);

/// Lets the ceiling of `room` slope down away from the wall at y = y_wall (the corridor side,
/// where it keeps its height) at `angle_rad`, but no lower than 1.6 m above the floor.
void slope_ceiling(PrismCell& room, double y_wall, double angle_rad);

/// `value` with `decimals` decimals, for the summary lines.
std::string fixed(double value, int decimals = 2);

}  // namespace conicloc::sim
