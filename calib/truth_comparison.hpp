#pragma once
// Scores estimated corrections against the calibration a sensor really has (a simulation's
// truth). Vertical and azimuth offsets are known only up to the gauge the solver fixes (a common
// shift is height or yaw), so their errors are taken about their mean over the lasers compared;
// elevations and range offsets are compared as they are. Unobservable corrections are skipped
// and counted.

#include "calib/calibration_solver.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::calib {

struct TruthErrors {
  double elevation_rms_rad = 0.0;
  double vertical_offset_rms_m = 0.0;  ///< about the mean (gauge)
  double azimuth_rms_rad = 0.0;        ///< about the mean (gauge)
  double range_offset_rms_m = 0.0;
  std::array<int, 4> compared{};      ///< lasers compared per correction (Δφ, Δo, Δψ, Δd)
  std::array<int, 4> unobservable{};  ///< lasers skipped per correction
};

/// `decode` + the estimated corrections against `truth` (same lasers, channel order). Throws
/// std::invalid_argument when the laser counts differ.
TruthErrors compare_to_truth(const CalibrationResult& result,
                             const sensor::LaserCalibration& decode,
                             const sensor::LaserCalibration& truth);

}  // namespace conicloc::calib
