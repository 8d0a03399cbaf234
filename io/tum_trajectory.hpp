#pragma once
// TUM trajectory files: one pose per line, "timestamp tx ty tz qx qy qz qw" (seconds, metres,
// unit quaternion of R_map_sensor), '#' starts a comment. Used for ground truth, odometry and
// the localizer's output.

#include <Eigen/Geometry>
#include <iosfwd>
#include <string>
#include <vector>

namespace conicloc::io {

struct StampedPose {
  double time_s = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

/// Reads a TUM file. Throws InputError naming the file and line for a malformed line, a
/// non-finite value or a quaternion far from unit norm; timestamps must not decrease.
std::vector<StampedPose> read_tum(const std::string& path);

/// Parses TUM text from a stream; `name` is used in error messages.
std::vector<StampedPose> read_tum(std::istream& in, const std::string& name);

/// Writes one TUM line (microsecond time, sub-millimetre position, 1e-9 quaternion).
void write_tum_line(std::ostream& out, const StampedPose& pose);

/// Writes a whole TUM file. Throws InputError if the file cannot be written.
void write_tum(const std::string& path, const std::vector<StampedPose>& poses);

}  // namespace conicloc::io
