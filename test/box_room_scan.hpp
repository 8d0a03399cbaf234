#pragma once
// An observation model scoring one synthetic scan of the box room (synthetic_room.hpp): what the
// tests of a model's likelihood around a known pose start from.

#include <memory>
#include <random>
#include <string>

#include "localizer/models/observation_factory.hpp"
#include "synthetic_room.hpp"

namespace conicloc::test {

/// Model `name` of `map`, prepared with a scan of it taken from `truth` (1 cm range noise, drawn
/// by generator `seed`) for poses within 1 m in x, y of the room's left half-centre (3, 2.5).
inline std::unique_ptr<localizer::ObservationModel> model_with_scan(const std::string& name,
                                                                    const maps::PlaneMap& map,
                                                                    const localizer::Pose3& truth,
                                                                    std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  const auto scan = make_scan(map, truth, options, rng);
  localizer::ObservationConfig config;
  config.model = name;
  auto model = localizer::make_observation_model(config, map, vlp16());
  model->prepare(
      scan, Eigen::AlignedBox3d(Eigen::Vector3d(2.0, 1.5, 0.5), Eigen::Vector3d(4.0, 3.5, 2.0)));
  return model;
}

}  // namespace conicloc::test
