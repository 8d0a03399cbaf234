#pragma once
// `localize --record run.mcap`: a localization run as an MCAP recording that Foxglove, Lichtblick
// and other MCAP viewers open. Topics (JSON messages, Foxglove schemas; log time = scan UTC):
//   /map        foxglove.SceneUpdate     the map's polygons as triangles, coloured by surface kind
//                                        (frame "map"; once, at the first scan)
//   /scan       foxglove.PointCloud      the measured returns: x, y, z, intensity (float32), ring
//                                        (uint16), frame "sensor"
//   /particles  foxglove.PosesInFrame    the particle cloud after the update (every k-th particle,
//                                        at most max_particles), frame "map"
//   /estimate   foxglove.PoseInFrame     T_map_sensor, frame "map"
//   /conics     foxglove.SceneUpdate     the scan lines the conic model predicts at the estimate,
//                                        a LINE_STRIP per ring and polygon, frame "sensor"
//   /tf         foxglove.FrameTransform  map -> sensor at the estimate
//
// JSON rather than ROS 2 CDR: it needs no message definitions of its own (the schema names are
// enough for Foxglove and Lichtblick), any MCAP tool prints it, and a test can check every field
// with JSON.parse.

#include <cstdint>
#include <numbers>
#include <string>

#include "io/mcap_writer.hpp"
#include "localizer/conic/conic_scan_predictor.hpp"
#include "localizer/conic/plane_culling.hpp"
#include "localizer/filter/localizer.hpp"
#include "maps/plane_index.hpp"
#include "maps/plane_map.hpp"
#include "sensor/scan.hpp"

namespace conicloc::tools {

struct RecordingOptions {
  std::size_t max_particles = 500;  ///< /particles holds every k-th particle, at most this many
  /// Azimuth spacing of the /conics points: 1°, a 17 cm chord at 10 m (writing numbers as JSON
  /// is most of a recording's cost: 0.5° doubles it).
  double conic_step_rad = std::numbers::pi / 180.0;
  bool cull_back_faces = true;  ///< false when the map serves both sides of a wall with one face
};

class RunRecording {
 public:
  /// Creates the recording (throws io::InputError naming `path` when it cannot be written).
  /// Keeps a reference to `map`, which must outlive the recording.
  RunRecording(const std::string& path, const maps::PlaneMap& map,
               const sensor::LaserCalibration& calibration, RecordingOptions options = {});

  /// One localized scan: its returns, the particles and the estimate at `utc_s`.
  void add(double utc_s, const localizer::UpdateResult& result, const sensor::Scan& scan,
           const localizer::ParticleSet& particles);

  /// Writes the summary and closes the file; throws io::InputError when that fails.
  void close() { writer_.close(); }
  std::uint64_t messages() const { return writer_.message_count(); }

 private:
  std::string map_update(std::uint64_t time_ns) const;
  std::string conics_update(std::uint64_t time_ns, const localizer::Pose3& T_map_sensor);

  const maps::PlaneMap& map_;
  RecordingOptions options_;
  io::McapWriter writer_;
  std::uint16_t map_channel_ = 0, scan_channel_ = 0, particles_channel_ = 0, estimate_channel_ = 0,
                conics_channel_ = 0, tf_channel_ = 0;
  bool map_written_ = false;
  maps::PlaneIndex index_;
  localizer::PlaneCuller culler_;
  localizer::ConicScanPredictor predictor_;
  localizer::PredictedScan predicted_;
};

}  // namespace conicloc::tools
