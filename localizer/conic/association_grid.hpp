#pragma once
// The coarse grid of pose space in which measurement-to-polygon associations are shared: cells of
// `cell_m` in x, y, z and `angle_rad` in roll, pitch, yaw, centred on 0 (so the mounting pose's
// roll = pitch = 0 is a cell centre). A model predicts the scan once at a cell's centre — a
// deterministic pose, whichever particle reaches the cell first — and every particle in the cell
// reuses the association (conic-segment, conic-beam).

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "localizer/conic/pose.hpp"

namespace conicloc::localizer {

/// Cell indices (x, y, z, roll, pitch, yaw).
using AssociationCellKey = std::array<std::int64_t, 6>;

/// The cell holding T_map_sensor.
AssociationCellKey association_cell_of(const Pose3& T_map_sensor, double cell_m, double angle_rad);

/// The cell's centre pose.
Pose3 association_cell_centre(const AssociationCellKey& key, double cell_m, double angle_rad);

/// One thread's associations for the current scan, by grid cell. A new scan (another
/// `scan_generation`) forgets the cells but keeps the storage.
template <typename Association>
class AssociationCache {
 public:
  /// The association of the cell holding T_map_sensor; the first time a cell is met in a scan,
  /// `fill(cell_centre_pose, association)` computes it.
  template <typename Fill>
  const Association& get(const Pose3& T_map_sensor, std::uint64_t scan_generation, double cell_m,
                         double angle_rad, Fill&& fill) {
    if (generation_ != scan_generation) {
      generation_ = scan_generation;
      cells_.clear();
      used_ = 0;
    }
    const AssociationCellKey key = association_cell_of(T_map_sensor, cell_m, angle_rad);
    const auto found = cells_.find(key);
    if (found != cells_.end()) return associations_[found->second];
    if (used_ == associations_.size()) associations_.emplace_back();
    fill(association_cell_centre(key, cell_m, angle_rad), associations_[used_]);
    cells_.emplace(key, used_);
    return associations_[used_++];
  }

 private:
  std::uint64_t generation_ = 0;
  std::map<AssociationCellKey, std::size_t> cells_;  ///< grid cell → index into associations_
  std::vector<Association> associations_;
  std::size_t used_ = 0;  ///< associations_[0, used_) belong to the current scan
};

}  // namespace conicloc::localizer
