#pragma once
// Reads a VeloView / Velodyne XML calibration (boost-serialisation "db.xml" format) to override a
// model's built-in table. Per laser (<points_><item><px>): id_, vertCorrection_ (elevation, deg),
// rotCorrection_ (azimuth correction, deg: Velodyne's corrected azimuth is α − rotCorrection, so
// ours is θ = −α + rotCorrection), vertOffsetCorrection_ (cm), distCorrection_ (cm, added to every
// distance). VeloView files list 64 lasers; the first `channels` of the model are used.
// Corrections this decoder does not model (horizOffsetCorrection_, the two-point
// distCorrectionX_/Y_ and focal terms) are reported as warnings.
//
// Example:
//   auto loaded = io::read_veloview_calibration("VLP-16.xml", sensor::SensorModel::VLP16);
//   for (const auto& w : loaded.warnings) spdlog::warn("{}", w);
//   io::VelodyneDecoder decoder(loaded.calibration);

#include <string>
#include <vector>

#include "sensor/laser_calibration.hpp"

namespace conicloc::io {

struct LoadedCalibration {
  sensor::LaserCalibration calibration;
  double distance_unit_m = 0.002;  ///< distLSB_ (given in cm)
  std::vector<std::string> warnings;
};

/// Throws InputError naming the file and element for a missing file, malformed XML, a missing or
/// non-numeric field, a laser id out of range or missing.
LoadedCalibration read_veloview_calibration(const std::string& path, sensor::SensorModel model);

/// Writes `calibration` in the same format (17 significant digits of degrees and centimetres, so
/// it reads back to within a unit conversion's rounding), one <item> per laser in channel order,
/// with `distance_unit_m` as distLSB_. Throws InputError naming `path` when it cannot be written.
void write_veloview_calibration(const std::string& path,
                                const sensor::LaserCalibration& calibration,
                                double distance_unit_m);

}  // namespace conicloc::io
