#pragma once
// Which scans of a capture a calibration may use: those the carrier drove on a level floor.
//
// Why: the model moves the carrier in the plane through a scan (x, y, yaw and their rates,
// calibration_model.hpp) above a floor held per scan. A scan on a stair or a ramp breaks that: the
// sensor rises through it, by v_z·τ at the firing τ before the scan's end, which the fit can only
// put into the lasers and the mounting. The example building's stair climbed at 0.65 m/s is 6.5 cm
// in one revolution: a 36 s capture that climbs it from 23 to 29 s (seed 4, range noise only) gave
// elevations 4–5 σ off their sigmas, 0.027° RMS; its level scans alone give 0.012°.
// So a scan is used only when the floor under the sensor (the map's, at the localized position:
// what the fit holds it above) changes, from the scan before it and to the scan after it, by no
// more than max_climb_mps times their interval: at 0.02 m/s the rise through a revolution of
// 0.1 s is 2 mm, the packet's range resolution. On a level floor it is the same from scan to scan
// exactly; a stair's sloped or stepped floor, or a step between rooms, changes it. (Not the
// localized height itself: the filter estimates it, a few millimetres apart from scan to scan.)

#include <cstddef>
#include <span>
#include <vector>

namespace conicloc::calib {

struct LevelScanChoice {
  std::vector<std::size_t> chosen;  ///< indices into the scans, ascending
  std::size_t climbing = 0;  ///< scans from `first` on left out: climbing, or the floor unknown
};

/// Up to `count` scans spread evenly over the level ones at index `first` (≥ 1: a scan needs the
/// one before it) and after; the last scan is judged against the one before it alone. `times_s` and
/// `floor_z_m` are the scans' times and the heights of the floor under them, one each. Throws
/// std::invalid_argument when they differ in length or `first` is 0.
LevelScanChoice choose_level_scans(std::span<const double> times_s,
                                   std::span<const double> floor_z_m, std::size_t first,
                                   std::size_t count, double max_climb_mps);

}  // namespace conicloc::calib
