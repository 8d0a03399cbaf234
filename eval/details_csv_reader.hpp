#pragma once
// Reads back what a report needs of `localize --details` (tools/details_csv.hpp): per scan the
// time, the estimate, the particle count, the update's wall time, the status and whether the set
// was refilled. Columns are found by their header names, so older files with fewer diagnostics
// still read.

#include <string>
#include <vector>

#include "localizer/conic/pose.hpp"

namespace conicloc::eval {

struct DetailsRow {
  double time_s = 0.0;
  localizer::Pose3 T_map_sensor = localizer::Pose3::Identity();
  double particles = 0.0;
  double time_ms = 0.0;
  bool recovered = false;
  std::string status;  ///< "tracking", "uncertain", "lost", "relocalizing"
};

/// Parses details CSV text; `file` names it in errors. Throws io::InputError naming the file and
/// line for a missing column (time_s, x, y, z, qx, qy, qz, qw, particles, time_ms, recovered,
/// status), a line with the wrong number of fields or a bad number.
std::vector<DetailsRow> read_details_csv(const std::string& text, const std::string& file);

}  // namespace conicloc::eval
