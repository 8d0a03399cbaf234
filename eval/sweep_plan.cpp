#include "eval/sweep_plan.hpp"

#include <fmt/format.h>

#include "eval/sweep_report.hpp"
#include "localizer/models/observation_factory.hpp"

namespace conicloc::eval {

std::vector<LocalizerSetting> localizer_settings(const SweepSpec& spec) {
  std::vector<LocalizerSetting> settings;
  for (const auto& model : spec.models) {
    for (const int particles : spec.particles) {
      const auto* entry = localizer::find_observation_model(model);
      if (entry && !entry->max_beams) {  // it scores every segment: `beams` does not apply
        settings.push_back({model, particles, 0});
        continue;
      }
      for (const int beams : spec.beams) settings.push_back({model, particles, beams});
    }
  }
  return settings;
}

std::string RunKey::text() const {
  return fmt::format("{}/{}/s{}/{}/p{}/b{}", building, scenario, seed, model,
                     setting_text(particles), setting_text(beams));
}

RunKey key_of(const RunRecord& run) {
  return {run.building, run.scenario, run.seed, run.model, run.particles, run.beams};
}

std::string building_name(const PlannedBuilding& building, std::uint64_t seed) {
  return building.per_seed ? building.name + "-s" + std::to_string(seed) : building.name;
}

std::string recording_name(const std::string& building, const std::string& scenario,
                           std::uint64_t seed) {
  return building + "-" + scenario + "-s" + std::to_string(seed);
}

std::vector<RunKey> plan_runs(const std::vector<PlannedBuilding>& buildings,
                              const SweepSpec& spec) {
  const auto settings = localizer_settings(spec);
  std::vector<RunKey> runs;
  for (const auto& building : buildings) {
    for (const auto seed : spec.seeds) {
      for (const auto& scenario : spec.scenarios) {
        for (const auto& s : settings) {
          runs.push_back(
              {building_name(building, seed), scenario, seed, s.model, s.particles, s.beams});
        }
      }
    }
  }
  return runs;
}

}  // namespace conicloc::eval
