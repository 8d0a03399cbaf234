#pragma once
// The tracked pose's copies on the other storeys, kept as hypotheses once a (re)start settles.
//
// Why: on identical storeys one place stands at one x, y on every storey, and a scan there scores
// the same on each (test_identical_storeys.cpp). A global start's cloud over them settles on one
// all the same: while it searches, a storey's share of the weight follows how well its particles
// happen to sit on their likelihood peak, not what the scans tell apart, and once the other
// storeys hold under ~1 % the cloud collapses onto the one it drifted to. Nothing of the others
// is left to weigh the next scans' evidence against it (generated storeys, 3 identical ones, 20 s,
// localizer seed 1 of building seed 4: a wrong storey tracked as certain for 151 scans, though
// from the truth the later scans score 100–1,000 nats better than from there).
//
// So from the scan a (re)start's cloud converges, the estimate's twin on each other storey — the
// same x, y, tilt, yaw and height above the floor, on that storey's floor — is scored with the
// scan at every update, as the estimate is, and holds log-odds against the estimate:
//   L_d ← L_d + τ · (log p(z | twin_d) − log p(z | estimate)),
// τ what the scan is worth as independent evidence (τ_max), from even odds: the weights the cloud
// held between storeys when it converged were drift, not evidence. A storey's share is
//   p_d = e^{L_d} / (1 + Σ_k e^{L_k})   (the estimate's: 1 / (1 + Σ_k e^{L_k})),
// and the shares enter the status and the covariance (the storeys' mixture in z). A twin whose
// share falls under min_share is dropped (a storey that differs where the sensor looks is gone
// within a scan or two); one whose share reaches switch_share takes the cloud, which moves to its
// storey. A twin with no floor of its storey under it (a stair that storey lacks, a hole) for
// more than max_missing_scans scans in a row is dropped too: the sensor cannot stand there.

#include <functional>
#include <optional>
#include <vector>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/particle.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::localizer {

struct StoreyTwinsConfig {
  bool enabled = true;
  double min_share = 1e-4;     ///< a twin whose share falls under this is dropped
  double switch_share = 0.8;   ///< a twin holding this share takes the cloud
  int max_missing_scans = 10;  ///< dropped after more scans in a row without its storey's floor
  /// The twin's floor must lie this close to the estimate's floor moved by the storeys' spacing
  /// (a stair of that storey at the same height), else it has no floor this scan.
  double floor_tolerance_m = 0.5;
};

/// One other storey's copy of the estimate.
struct StoreyTwin {
  int offset = 0;         ///< storeys above (+) or below (−) the estimate's
  double log_odds = 0.0;  ///< L_d, against the estimate
  int missing_scans = 0;  ///< consecutive scans without a floor of its storey under it
};

/// What one scan's twins say.
struct StoreyTwinsUpdate {
  double estimate_share = 1.0;  ///< the estimate's storey's share
  double z_variance_m2 = 0.0;   ///< of the mixture over the storeys (heights of their floors)
  /// Where a twin took the cloud: the height every particle moves by (m).
  std::optional<double> move_z_m;
};

class StoreyTwins {
 public:
  /// Keeps references to `map` and `free_space` (must outlive this).
  StoreyTwins(const maps::PlaneMap& map, const FreeSpace& free_space,
              const StoreyTwinsConfig& config)
      : map_(map), free_space_(free_space), config_(config) {}

  /// Even odds for every other storey there is from the storey of `estimate` (every other
  /// storey of the map where it stands on no navigable floor; none on a map of one storey or
  /// when disabled).
  void start(const PoseState& estimate, double mounting_height_m);
  void clear() { twins_.clear(); }
  bool empty() const { return twins_.empty(); }
  const std::vector<StoreyTwin>& twins() const { return twins_; }

  /// `estimate` moved `offset` storeys: same x, y, roll, pitch, yaw and height above its floor,
  /// on the floor of that storey under x, y. `mounting_height_m` (the sensor's height above the
  /// floor) finds the estimate's floor. None where the estimate or that storey has no navigable
  /// floor under x, y (within floor_tolerance_m of the storeys' spacing).
  std::optional<PoseState> twin_pose(const PoseState& estimate, double mounting_height_m,
                                     int offset) const;

  /// The twins' shares and z variance at `estimate`, without a scan's evidence (a scan not
  /// observed, or weighed on a few rings). Off every navigable floor, the storey it last stood on
  /// gives the heights.
  StoreyTwinsUpdate current(const PoseState& estimate, double mounting_height_m) const;

  /// Scores of poses, the same scan for each: log p(z | pose), un-tempered.
  using ScorePoses = std::function<std::vector<double>(const std::vector<PoseState>& poses)>;

  /// One scan: scores the estimate and its twins with `score` (one call, the estimate first),
  /// adds τ = `tempering` times each twin's log-likelihood over the estimate's to its odds, drops
  /// and moves as the header says. After a move the odds are counted from the new storey (the old
  /// estimate is a twin of it).
  StoreyTwinsUpdate update(const PoseState& estimate, double mounting_height_m, double tempering,
                           const ScorePoses& score);

 private:
  /// The estimate's storey and floor height under it; none off every navigable cell.
  struct Footing {
    int storey = -1;
    double floor_z = 0.0;
  };
  std::optional<Footing> footing(const PoseState& estimate, double mounting_height_m) const;
  /// twin_pose() from the estimate's footing.
  std::optional<PoseState> twin_at(const PoseState& estimate, const Footing& own, int offset) const;
  bool storey_exists(int storey) const;
  /// log(1 + Σ_k e^{L_k}): twin d's share is e^{L_d − log_total()}, the estimate's
  /// e^{−log_total()}.
  double log_total() const;
  /// Drops the twins whose share is under min_share.
  void drop_refuted();
  /// Shares and z variance of the twins, the estimate on `storey` (−1: unknown, no variance).
  StoreyTwinsUpdate summarise(int storey) const;
  /// The floor-to-floor height from `storey` to `storey + offset`; 0 where there is none.
  double storey_rise_m(int storey, int offset) const;

  const maps::PlaneMap& map_;
  const FreeSpace& free_space_;
  StoreyTwinsConfig config_;
  std::vector<StoreyTwin> twins_;
  int last_storey_ = -1;  ///< the estimate's storey at the last update with a footing
};

}  // namespace conicloc::localizer
