#pragma once
// Where in the building a scan fits, searched over the whole floor plan at once: the proposal of
// a global start and a recovery. The scan's near-horizontal returns, seen from above, are matched
// against the walls cut at the sensor's height on every storey (plan_field.hpp) by branch and
// bound over translations, for each heading the scan proposes (heading_proposal.hpp) — exact at
// the field's resolution, so the cost follows how much of the building fits the scan (the
// branches that cannot be pruned), not its floor area. The score of a pose is the mean field
// value over the returns,
//   s(x, y, ψ) = (1/n) Σ_p f(R(ψ) p + (x, y)) / 255 ∈ [0, 1],
// the fraction of the returns that lie on a wall. The candidates, a few dozen distinct poses on
// free floor, then seed particles that the observation model judges in 3D (Localizer).

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/plan_field.hpp"
#include "maps/plane_map.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct PlanSearchConfig {
  /// Share of a global start's particles, and of every restart's share over the whole building,
  /// drawn about the candidates; the rest stay uniform over the free space, as all do when the
  /// search finds no candidate; 0 switches the search off. All by default: 0.5 cost a global
  /// start's first scans 2–20× the time and found no more places over 162 corpus runs (global
  /// starts and kidnaps, with and without odometry, among crowds, in maps 5 cm off; session 40,
  /// docs/results/scale.md): a uniform particle in a building of thousands of m² almost never
  /// lands in the truth's peak, and where the plan search misses the truth a restart searches
  /// again.
  double fraction = 1.0;
  double resolution_m = 0.2;    ///< cell of the field: the search's translation step
  double field_sigma_m = 0.15;  ///< σ of the field: range noise plus the cell's own size
  int coarsest_level = 6;       ///< root nodes of 2^6 cells (12.8 m) a side
  /// Candidates closer than 2^distinct_level cells (0.8 m) and distinct_yaw_rad are one: the
  /// cells of one likelihood peak are one pose.
  int distinct_level = 2;
  /// Rings used: the near-horizontal ones, whose returns on walls lie near the section height.
  double max_elevation_rad = 3.5 * M_PI / 180.0;
  double min_range_m = 0.5;
  /// Walls as far as a large hall's: a hall 40 m across has its walls 20–30 m from the sensor,
  /// and within 15 m of it the search saw only clutter and the floor (PNU, seed 4: no pose put
  /// more than 14 % of those returns on a wall; out to 30 m the truth scored 0.54 and was the best
  /// candidate). Farther, the heading step that moves the farthest return by one cell gets finer
  /// and the yaws searched more.
  double max_range_m = 30.0;
  /// The floor and the ceiling are no wall of the plan. A return whose height above the floor,
  /// the sensor taken as level at its height (as the search takes it), is under this clearance,
  /// or that comes this close to the ceiling over most of the map's navigable floor area, is
  /// left out (at most half the way to either: a sensor 0.2 m up keeps its level rings).
  /// The −3° ring of a sensor 0.8 m up meets the floor 15.3 m off, a circle of returns that fits
  /// no wall; in a hall that circle was most of the returns matched (PNU, seed 4: 425 of 679).
  double surface_clearance_m = 0.25;
  /// ... widened by d·tan(tilt_allowance_rad) at horizontal distance d: the tilt a sensor taken
  /// as level may have (a robot's pitch on braking; a hand-held sensor sways more, and then
  /// some floor returns stay in, as before).
  double tilt_allowance_rad = 1.0 * M_PI / 180.0;
  double point_spacing_m = 0.2;  ///< returns thinned to one per cell of this size
  std::size_t max_points = 400;
  double heading_window_rad = 2.0 * M_PI / 180.0;  ///< searched about each proposed heading
  double min_score = 0.25;                         ///< s below this is no candidate ...
  /// ... nor s below this share of the best one's: a pose that puts a fifth fewer of the returns
  /// on walls than the best is a worse fit, not the same place seen past clutter (which costs
  /// every pose alike).
  double min_relative_score = 0.8;
  std::size_t max_candidates = 64;
  /// Nodes of the search expanded at once, their children bounded on the threads; the candidates
  /// are the same for any value (PlanSearch::search). Each batch starts its threads: in KU, 64 a
  /// batch made 2 threads slower than one (75 against 39 ms), 1,024 a batch 34 ms.
  std::size_t expand_batch = 1024;
  double distinct_yaw_rad = 5.0 * M_PI / 180.0;
  double sigma_xy_m = 0.1;  ///< spread of the particles drawn about a candidate
  double sigma_yaw_rad = 1.0 * M_PI / 180.0;
};

/// A pose on free floor where the scan fits the plan.
struct PlanCandidate {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
  int cell = -1;         ///< the navigable cell under it
  double floor_z = 0.0;  ///< its floor there
  double score = 0.0;    ///< s above
};

class PlanSearch {
 public:
  /// Builds the fields of every storey (each wall cut `height_above_floor_m` over the floor of
  /// the cell it bounds); keeps references to `map` and `free_space` (both must outlive this).
  PlanSearch(const maps::PlaneMap& map, const FreeSpace& free_space, double height_above_floor_m,
             const PlanSearchConfig& config);

  /// The best distinct candidates for `scan` (sensor frame, taken as level), best first, at most
  /// max_candidates; `headings` are the proposed yaws (each searched ± heading_window_rad), all
  /// yaws when empty. Deterministic for any `threads`.
  std::vector<PlanCandidate> search(const sensor::Scan& scan, const std::vector<double>& headings,
                                    int threads) const;

  /// The scan's returns the search matches: near-horizontal, thinned (sensor frame, xy).
  std::vector<Eigen::Vector2d> search_points(const sensor::Scan& scan) const;

  std::size_t memory_bytes() const;

 private:
  struct StoreyPlan {
    double floor_z = 0.0;      ///< the storey's floor (PlaneMap::storeys), its walls' fallback
    double top_floor_z = 0.0;  ///< and highest
    int storey = -1;
    PlanField field;
    /// Translations searched (cells of the field): the storey's navigable cells' extent.
    Eigen::Vector2i t_min = Eigen::Vector2i::Zero();
    Eigen::Vector2i t_max = Eigen::Vector2i::Zero();
  };

  const maps::PlaneMap& map_;
  const FreeSpace& free_space_;
  PlanSearchConfig config_;
  std::vector<StoreyPlan> storeys_;
  /// How far the floor lies below a level sensor, and the ceiling over most of the navigable
  /// floor area above it (m; the ceiling infinite when the map gives none).
  double floor_below_m_ = 0.0;
  double ceiling_above_m_ = std::numeric_limits<double>::infinity();
};

}  // namespace conicloc::localizer
