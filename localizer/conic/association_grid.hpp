#pragma once
// The coarse grid of pose space in which measurement-to-polygon associations are shared: cells of
// AssociationCellSize, centred on 0 (so the mounting pose's roll = pitch = 0 is a cell centre), in
// z on each storey's floor. A model predicts the scan once at a cell's centre — a
// deterministic pose, whichever particle reaches the cell first — and every particle in the cell
// reuses the association (conic-segment, conic-beam).

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::localizer {

/// The grid's cell.
struct AssociationCellSize {
  double xy_m = 0.25;            ///< in x and y
  double z_m = 0.25;             ///< in z, counted from the storey's floor (AssociationGrid)
  double angle_rad = 0.0349066;  ///< 2°, in roll, pitch and yaw
  /// The largest distance of a pose in a cell from its centre: half the cell's diagonal.
  double half_diagonal_m() const;
  /// How much nearer than the cell's centre a pose of the cell can meet a surface with a ring's
  /// rays, to first order, for a surface the centre's ray meets at `range_m`: the position's
  /// half_diagonal_m(), plus range × the tilt of the spin axis (half a cell in roll and in pitch:
  /// at most angle_rad together; yaw turns a ring's cone into itself) for a ray meeting the
  /// surface at up to 45° from its normal. Beams that graze a surface change range faster.
  double range_margin_m(double range_m) const;
};

/// Cell indices (x, y, storey, z, roll, pitch, yaw).
using AssociationCellKey = std::array<std::int64_t, 7>;

/// The grid over pose space. Its z cells are counted from the floor of the storey a pose stands
/// on (the highest of the storeys' floors at or below it; from z = 0 without storeys), so every
/// storey meets the grid at one phase. Counted from z = 0, each storey's particles — which share
/// one height, the floor's plus the mounting height — were predicted from a height a different
/// offset off theirs: a sensor at 7.62 m from 7.50 m, one storey down at 4.21 m from 4.25 m. A
/// down-looking ring's floor/wall boundary moves by Δz / tan(elevation), 3.7 Δz at −15°, and a
/// global start in a building of identical storeys settled on the storey whose phase fitted
/// (generated storeys, seed 2: the scans scored ~150 nats higher each one storey below the
/// truth).
class AssociationGrid {
 public:
  /// `storey_floors_m` ascending (PlaneMap::storeys' floor_z).
  explicit AssociationGrid(const AssociationCellSize& size = {},
                           std::vector<double> storey_floors_m = {});

  /// The cell holding T_map_sensor.
  AssociationCellKey cell_of(const Pose3& T_map_sensor) const;
  /// The cell's centre pose.
  Pose3 centre(const AssociationCellKey& key) const;
  const AssociationCellSize& size() const { return size_; }

 private:
  AssociationCellSize size_;
  std::vector<double> storey_floors_m_;
};

/// The grid of `size` over the storeys of `map`.
AssociationGrid association_grid(const maps::PlaneMap& map, const AssociationCellSize& size);

/// One thread's associations for the current scan, by grid cell. A new scan (another
/// `scan_generation`) forgets the cells but keeps the storage.
template <typename Association>
class AssociationCache {
 public:
  /// The association of the cell holding T_map_sensor; the first time a cell is met in a scan,
  /// `fill(cell_key, cell_centre_pose, association)` computes it.
  template <typename Fill>
  const Association& get(const Pose3& T_map_sensor, std::uint64_t scan_generation,
                         const AssociationGrid& grid, Fill&& fill) {
    if (generation_ != scan_generation) {
      generation_ = scan_generation;
      cells_.clear();
      used_ = 0;
    }
    const AssociationCellKey key = grid.cell_of(T_map_sensor);
    const auto found = cells_.find(key);
    if (found != cells_.end()) return associations_[found->second];
    if (used_ == associations_.size()) associations_.emplace_back();
    fill(key, grid.centre(key), associations_[used_]);
    cells_.emplace(key, used_);
    return associations_[used_++];
  }

 private:
  std::uint64_t generation_ = 0;
  std::map<AssociationCellKey, std::size_t> cells_;  ///< grid cell → index into associations_
  std::vector<Association> associations_;
  std::size_t used_ = 0;  ///< associations_[0, used_) belong to the current scan
};

/// Values by grid cell kept from one scan to the next: a robot's cloud moves a fraction of a
/// cell per scan, so most of the cells a scan meets were met by the scan before. A cell met in
/// the current scan or the one before is kept; when a new scan starts (another
/// `scan_generation`), the cells the ending scan did not meet are forgotten and their storage
/// reused, so what is kept is at most two scans' cells.
template <typename Value>
class RecentCellCache {
 public:
  /// The value of cell `key`; when the cell is not kept, `fill(value)` computes it.
  template <typename Fill>
  const Value& get(const AssociationCellKey& key, std::uint64_t scan_generation, Fill&& fill) {
    if (generation_ != scan_generation) start_scan(scan_generation);
    const auto found = cells_.find(key);
    if (found != cells_.end()) {
      Slot& slot = slots_[found->second];
      slot.met = generation_;
      return slot.value;
    }
    std::size_t index = slots_.size();
    if (free_.empty()) {
      slots_.emplace_back();
    } else {
      index = free_.back();
      free_.pop_back();
    }
    fill(slots_[index].value);
    slots_[index].met = generation_;
    cells_.emplace(key, index);
    return slots_[index].value;
  }

  /// Forgets every cell (their storage is kept).
  void clear() {
    for (const auto& [key, index] : cells_) free_.push_back(index);
    cells_.clear();
  }

 private:
  struct Slot {
    Value value;
    std::uint64_t met = 0;  ///< the last scan that met the cell
  };
  void start_scan(std::uint64_t scan_generation) {
    for (auto it = cells_.begin(); it != cells_.end();) {
      if (slots_[it->second].met == generation_) {
        ++it;
      } else {
        free_.push_back(it->second);
        it = cells_.erase(it);
      }
    }
    generation_ = scan_generation;
  }

  std::uint64_t generation_ = 0;
  std::map<AssociationCellKey, std::size_t> cells_;  ///< grid cell → index into slots_
  std::vector<Slot> slots_;
  std::vector<std::size_t> free_;  ///< slots no cell holds
};

}  // namespace conicloc::localizer
