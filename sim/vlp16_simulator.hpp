#pragma once
// The VLP-16 firing pattern cast into a World: 16 lasers fired 2.304 µs apart, one sequence every
// 55.296 µs, while the head turns clockwise at `rpm` and the sensor moves (the caller gives the
// pose of each sequence, so motion distortion is real). The world is not the map: range noise,
// 2 mm quantisation, dropouts, elevation calibration errors and a maximum range are applied here.

#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "io/packet_encoder.hpp"
#include "sensor/laser_calibration.hpp"
#include "sim/world.hpp"

namespace conicloc::sim {

struct SensorEffects {
  double range_noise_m = 0.03;       ///< σ of Gaussian range noise
  double quantisation_m = 0.002;     ///< range resolution (0: none; the packet has 2 mm anyway)
  double dropout_rate = 0.002;       ///< probability that a return is lost (range 0)
  double elevation_error_deg = 0.1;  ///< per-laser elevation error, uniform in ±this
  double offset_error_m = 0.0;       ///< σ of per-laser vertical and range offset errors
  double azimuth_error_deg = 0.0;    ///< σ of per-laser azimuth offset errors
  double max_range_m = 100.0;        ///< farther surfaces return nothing
  double min_range_m = 0.3;          ///< nearer surfaces block the beam and return nothing
};

struct SensorConfig {
  double rpm = 600.0;                 ///< 300..1200
  bool dual_return = false;           ///< last + strongest echoes (12 sequences per packet)
  double beam_divergence_rad = 3e-3;  ///< footprint of a beam: mixed echoes at edges (dual)
  double start_azimuth_rad = 0.0;     ///< θ of the first firing, REP-103
};

/// What happened to every simulated ray (for tests and the sidecar).
struct SensorStats {
  std::uint64_t rays = 0;
  std::uint64_t map_hits = 0;        ///< returns from map surfaces
  std::uint64_t furniture_hits = 0;  ///< returns from clutter boxes
  std::uint64_t person_hits = 0;
  std::uint64_t dropouts = 0;       ///< a surface was there but the return was dropped
  std::uint64_t no_surface = 0;     ///< nothing within range (openings, glass, sky)
  std::uint64_t blind_zone = 0;     ///< a surface nearer than min_range_m stopped the beam
  std::uint64_t second_echoes = 0;  ///< dual: last echo distinct from the strongest

  SensorStats& operator+=(const SensorStats& other);
};

class Vlp16Simulator {
 public:
  /// `calibration` is the sensor's nominal table; per-laser errors (elevation, then vertical
  /// offset, azimuth offset and range offset) are drawn once from `rng` and added to it, giving
  /// what the sensor really is (so a decoder using the nominal table sees them as calibration
  /// errors). The range offset d_k is the sensor's: it reports r_raw = r_true − d_k.
  Vlp16Simulator(const World& world, sensor::LaserCalibration calibration, SensorConfig config,
                 SensorEffects effects, std::mt19937_64& rng);

  /// Angular rate of the head, rad/s (positive; θ decreases with time, the head turns clockwise).
  double angular_rate() const;

  /// θ of the head at `time_s` after the capture start.
  double azimuth_at(double time_s) const;

  /// Fires one sequence at `time_s` (seconds after the capture start) from `T_map_sensor`. The
  /// returned sequence's time_s is `time_s + device_time_offset_s`. `hints` (one per channel)
  /// carry the last polygon each laser hit between calls, for speed only.
  io::FiringSequence fire(double time_s, double device_time_offset_s,
                          const Eigen::Isometry3d& T_map_sensor, std::mt19937_64& rng,
                          std::array<int, 16>& hints, SensorStats& stats) const;

  /// Elevation error applied to each channel, radians.
  const std::vector<double>& elevation_errors_rad() const { return elevation_errors_rad_; }
  /// The nominal table and what the sensor really is (nominal + the drawn errors), per channel.
  const sensor::LaserCalibration& nominal_calibration() const { return nominal_; }
  const sensor::LaserCalibration& true_calibration() const { return calibration_; }
  const SensorConfig& config() const { return config_; }
  const SensorEffects& effects() const { return effects_; }

 private:
  struct Echo {
    double range_m = 0.0;  ///< 0: none
    double intensity = 0.0;
    SurfaceOrigin origin = SurfaceOrigin::Map;
  };
  // Laser k fires at θ_seq − ω·k·2.304 µs + its azimuth offset: a constant angle δ_k from the
  // sequence's θ, so its direction follows from cos/sin θ_seq by one rotation (no sincos per ray).
  struct LaserDirection {
    double cos_elevation = 1.0;  ///< of the true elevation (calibration error included)
    double sin_elevation = 0.0;
    double cos_delta = 1.0;
    double sin_delta = 0.0;
  };
  /// Laser `channel`'s ray at azimuth θ (given as cos θ, sin θ), map frame.
  Ray beam_ray(const Eigen::Isometry3d& T_map_sensor, int channel, double cos_azimuth,
               double sin_azimuth) const;
  /// The map surface each ray of a firing's fan meets (rays[k] tried first against hints[k]), and
  /// the people the fan may meet before them.
  struct FanCast {
    std::array<std::optional<WorldHit>, 16> surfaces;
    PeopleSnapshot people;
  };
  FanCast cast_fan(std::span<const Ray> rays, double time_s, double max_cast_m,
                   const std::array<int, 16>& hints) const;
  /// What the sensor makes of the surface or person a ray met.
  static Echo echo_of(const std::optional<WorldHit>& hit);

  const World& world_;
  sensor::LaserCalibration nominal_;
  sensor::LaserCalibration calibration_;
  SensorConfig config_;
  SensorEffects effects_;
  std::vector<double> elevation_errors_rad_;
  std::vector<LaserDirection> directions_;
  double cos_half_divergence_ = 1.0;  ///< dual: the beam edge, half the divergence behind
  double sin_half_divergence_ = 0.0;
};

}  // namespace conicloc::sim
