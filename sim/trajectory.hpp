#pragma once
// A timed sensor trajectory T_map_sensor(t): a smooth path walked with a trapezoidal speed
// profile (limited acceleration, lateral acceleration and yaw rate), the sensor carried by a
// mobile robot (fixed height, level) or by hand (bob, sway, roll and pitch of a walking person).

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <random>
#include <vector>

namespace conicloc::sim {

enum class MotionStyle { Robot, Handheld };

struct TrajectoryConfig {
  MotionStyle style = MotionStyle::Robot;
  double speed_mps = 1.0;                  ///< cruise speed
  double acceleration_mps2 = 0.5;          ///< along the path, speeding up and slowing down
  double lateral_acceleration_mps2 = 0.6;  ///< v²κ in turns
  double yaw_rate_max_radps = 0.8;         ///< also used to turn in place
  /// How fast the yaw rate may change (turning in place, and v·κ along the path): a wheeled base's
  /// controller limits it (ROS's base_local_planner: acc_lim_theta 3.2 rad/s²), and a carrier
  /// slows where its path bends one way and then the other. Positive and finite (Trajectory
  /// throws std::invalid_argument otherwise).
  double yaw_acceleration_max_radps2 = 3.0;
  double sensor_height_m = -1.0;           ///< above the floor; <0: 0.8 (robot) or 1.4 (handheld)
  double mount_roll_deg = 0.0;  ///< the sensor's fixed tilt on its carrier (ZYX, after yaw)
  double mount_pitch_deg = 0.0;
  double step_length_m = 0.7;  ///< handheld: one step
  double bob_m = 0.015;        ///< handheld: vertical bob amplitude, once per step
  double sway_m = 0.02;        ///< handheld: lateral sway amplitude, once per stride
  double hand_tilt_deg = 2.0;  ///< handheld: roll/pitch amplitude (gait + slow wander)
};

/// A point to pass, at floor level (z of the floor under it). With a yaw, the sensor stops
/// there and turns in place to that heading before going on.
struct Waypoint {
  Eigen::Vector3d floor_point = Eigen::Vector3d::Zero();
  std::optional<double> yaw_rad;
};

/// The height of the ground under a point of the planned path (z interpolated between
/// waypoints), e.g. FloorSurface::height_under: on a stair the floor is not linear between the
/// waypoints. nullopt where there is no ground under the point.
using GroundHeightFunction =
    std::function<std::optional<double>(const Eigen::Vector3d& floor_point)>;

class Trajectory {
 public:
  /// Plans the motion through `waypoints`, starting at rest heading along the path (or the first
  /// waypoint's yaw) and ending at rest. Random parts of the hand motion come from `rng`. With
  /// `ground_height`, every path sample's floor point is moved onto the ground it finds; over a
  /// gap in that ground the carrier keeps the height it stood at.
  Trajectory(const std::vector<Waypoint>& waypoints, const TrajectoryConfig& config,
             std::mt19937_64& rng, const GroundHeightFunction& ground_height = {});

  /// Sensor pose at `time_s` (clamped to [0, duration]: standing still after the end).
  Eigen::Isometry3d T_map_sensor(double time_s) const;

  /// Floor point under the sensor's path (no hand motion) and the speed at `time_s`.
  Eigen::Vector3d floor_point(double time_s) const;
  double speed(double time_s) const;
  double yaw(double time_s) const;  ///< heading of the carrier (before hand motion)

  double duration_s() const { return samples_.empty() ? 0.0 : samples_.back().time_s; }
  double length_m() const { return samples_.empty() ? 0.0 : samples_.back().s_m; }
  /// The configuration, with a negative sensor height resolved to the style's default.
  const TrajectoryConfig& config() const { return config_; }

 private:
  struct TimedSample {
    double time_s = 0.0;
    double s_m = 0.0;
    double speed_mps = 0.0;
    double yaw_rad = 0.0;  ///< unwrapped
    Eigen::Vector3d floor_point = Eigen::Vector3d::Zero();
  };
  TimedSample sample_at(double time_s) const;
  void append_leg(const std::vector<Eigen::Vector3d>& points,
                  const GroundHeightFunction& ground_height);
  /// `nominal` on the ground `ground_height` finds under it; where there is none, at the last
  /// sample's height: a gap in the modelled floor is crossed level, not at the route's nominal
  /// height (interpolated from the cells' lowest points, it can lie well below the floor).
  Eigen::Vector3d on_ground(const Eigen::Vector3d& nominal,
                            const GroundHeightFunction& ground_height) const;
  void turn_to(double yaw_rad);
  /// Fills yaw_track_: the carrier's yaw following the samples' within the yaw acceleration limit.
  void track_yaw();
  /// The carrier's yaw (unwrapped) at `time_s`, clamped to [0, duration].
  double tracked_yaw(double time_s) const;

  TrajectoryConfig config_;
  std::vector<TimedSample> samples_;
  std::vector<double> yaw_track_;  ///< carrier yaw every kYawTrackStep_s from time 0
  std::array<double, 6> wander_frequency_hz_{};  ///< roll, pitch, yaw × 2 slow components
  std::array<double, 6> wander_phase_rad_{};
};

}  // namespace conicloc::sim
