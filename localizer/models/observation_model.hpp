#pragma once
// The observation model interface: how well does a measured scan fit the map seen from a pose?
// One interface, three models chosen by name (DESIGN.md "Observation models"):
//   "conic-beam"     per beam, range residual against the predicted piecewise-conic scan line;
//   "conic-segment"  per measured conic segment, against the predicted conic of its plane;
//   "point-to-plane" per point, distance to the nearest map polygon (the MCL baseline).

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "maps/plane_map.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// The score of one pose: the log-likelihood log p(scan | pose) (a sum over the model's terms,
/// each a robust mixture, so it is finite for any pose) and the fraction of terms explained by
/// the map within the model's inlier gate (used to detect a collapsed filter).
struct ObservationScore {
  double log_likelihood = 0.0;
  double inlier_fraction = 0.0;
};

class ObservationModel {
 public:
  /// Per-thread working memory of score(); models that need none return nullptr.
  struct Scratch {
    virtual ~Scratch() = default;
  };

  virtual ~ObservationModel() = default;

  /// The model's name as accepted by make_observation_model().
  virtual std::string name() const = 0;

  /// Once per scan, serially, before any score(): takes the (de-skewed) scan, selects and
  /// preprocesses its beams, and culls the map to what a sensor anywhere in `cloud_box` (the
  /// particles' positions, map frame) can see.
  virtual void prepare(const sensor::Scan& scan, const Eigen::AlignedBox3d& cloud_box) = 0;

  /// Number of likelihood terms (beams, points or segments) of the prepared scan; 0 when the
  /// scan holds nothing to score.
  virtual std::size_t term_count() const = 0;

  /// How many independent terms the prepared scan is worth, seen from `T_map_sensor` (the
  /// cloud's estimate): its terms grouped by the map surface they fall on there, each group of n
  /// counted as n / (1 + (n − 1)ρ) (correlated_terms.hpp). The filter tempers the scan's
  /// likelihood to this count. term_count() for a model that does not group its terms.
  /// `scratch` (may be null; not in use by another thread) lends its caches (a conic model's
  /// associations kept by cell).
  virtual double effective_terms(const Pose3& T_map_sensor, Scratch* scratch) const {
    (void)T_map_sensor;
    (void)scratch;
    return static_cast<double>(term_count());
  }

  virtual std::unique_ptr<Scratch> make_scratch() const { return nullptr; }

  /// Raises the prepared scan's terms on surfaces that face a direction the scan's equal
  /// exponents shortchange, to what the surfaces seen at `reference` are worth there
  /// (direction_term_weights(), correlated_terms.hpp), for the following score() calls until the
  /// next prepare(), which restores equal weights. Serially, after set_pose_blur() and prepare().
  /// A model that does not group its terms (point-to-plane) keeps them equal.
  virtual void weigh_terms(const Pose3& reference, Scratch* scratch) {
    (void)reference;
    (void)scratch;
  }

  /// Whether score() costs less for a scan that holds fewer rings (a model that predicts ring by
  /// ring): the Localizer then gives a cloud searching the building a few rings only
  /// (localizer/filter/search_rings.hpp). False where the cost follows the terms alone.
  virtual bool cost_follows_rings() const { return false; }

  /// Widens every term's residual spread to σ_eff = √(σ² + b²), and the part of it shared by the
  /// terms of one surface alike, for a cloud that samples the poses only to within a range error
  /// `blur_m` = b (localizer/pose_blur.hpp); b ≤ σ leaves (restores) the configured model. Call
  /// before score() and effective_terms(), serially.
  virtual void set_pose_blur(double blur_m) = 0;

  /// Scores one pose against the prepared scan. Thread-safe for distinct `scratch` objects.
  virtual ObservationScore score(const Pose3& T_map_sensor, Scratch* scratch) const = 0;

 protected:
  /// The caller's scratch as the model's own kind, or, without one, a scratch made for this call
  /// and held by `local`. On the heap, not in a std::optional on the stack: a model's scratch is
  /// large (conic-beam's 73 KB: predicted rings held in place), and GCC 12 zeroes an optional's
  /// whole storage on every call, given a scratch or not — a 73 KB memset, through the L1 cache,
  /// per particle scored (~2 % of a tracking run's time).
  template <typename Own>
  static Own& own_scratch(Scratch* scratch, std::unique_ptr<Own>& local) {
    if (scratch != nullptr) return static_cast<Own&>(*scratch);
    local = std::make_unique<Own>();
    return *local;
  }
};

/// The names make_observation_model() accepts, the default first.
std::vector<std::string> observation_model_names();

}  // namespace conicloc::localizer
