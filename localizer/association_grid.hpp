#pragma once
// The coarse grid of pose space in which measurement-to-polygon associations are shared: cells of
// `cell_m` in x, y, z and `angle_rad` in roll, pitch, yaw, centred on 0 (so the mounting pose's
// roll = pitch = 0 is a cell centre). A model predicts the scan once at a cell's centre — a
// deterministic pose, whichever particle reaches the cell first — and every particle in the cell
// reuses the association (conic-segment, conic-beam).

#include <array>
#include <cstdint>

#include "localizer/pose.hpp"

namespace conicloc::localizer {

/// Cell indices (x, y, z, roll, pitch, yaw).
using AssociationCellKey = std::array<std::int64_t, 6>;

/// The cell holding T_map_sensor.
AssociationCellKey association_cell_of(const Pose3& T_map_sensor, double cell_m, double angle_rad);

/// The cell's centre pose.
Pose3 association_cell_centre(const AssociationCellKey& key, double cell_m, double angle_rad);

}  // namespace conicloc::localizer
