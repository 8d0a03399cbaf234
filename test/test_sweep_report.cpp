// Evaluation sweeps: the sweep file format, the Pareto front, the per-configuration means and the
// runs.csv columns people script against.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "eval/svg_plot.hpp"
#include "eval/sweep_report.hpp"
#include "eval/sweep_scenario.hpp"
#include "eval/sweep_spec.hpp"
#include "io/input_error.hpp"
#include "sim/building_generator.hpp"
#include "temp_path.hpp"

namespace ce = conicloc::eval;
namespace fs = std::filesystem;

namespace {

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path path = conicloc::test::unique_temp_path(name);
  std::ofstream(path) << text;
  return path;
}

std::string error_of(const fs::path& path) {
  try {
    ce::read_sweep_file(path.string());
  } catch (const conicloc::io::InputError& e) {
    return e.what();
  }
  return "";
}

ce::RunRecord run(const std::string& model, int particles, int beams, double ate, double ms,
                  const std::string& scenario = "robot", bool converged = true) {
  ce::RunRecord r;
  r.building = "b";
  r.scenario = scenario;
  r.seed = 1;
  r.model = model;
  r.particles = particles;
  r.beams = beams;
  r.metrics.ate_xy_m.rmse = ate;
  r.metrics.heading_deg.rmse = 10.0 * ate;
  r.time_per_scan_ms = ms;
  r.time_p95_ms = 1.5 * ms;
  r.realtime_factor = 100.0 / ms;
  r.converged = converged;
  return r;
}

}  // namespace

TEST(SweepSpec, FileOverridesTheQuickSweepAndResolvesMapPaths) {
  const fs::path path = write_file("sweep.txt",
                                   "# a comment line\n"
                                   "models = conic-beam, point-to-plane   # trailing comment\n"
                                   "particles = 100, 2000\n"
                                   "seeds = 3\n"
                                   "scenarios = clutter, kidnap\n"
                                   "duration_s = 7.5\n"
                                   "maps = other.gml, /abs/b.gml\n");
  const auto spec = ce::read_sweep_file(path.string());
  EXPECT_EQ(spec.models, (std::vector<std::string>{"conic-beam", "point-to-plane"}));
  EXPECT_EQ(spec.particles, (std::vector<int>{100, 2000}));
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{3}));
  EXPECT_EQ(spec.scenarios, (std::vector<std::string>{"clutter", "kidnap"}));
  EXPECT_DOUBLE_EQ(spec.duration_s, 7.5);
  EXPECT_EQ(spec.beams, ce::quick_sweep().beams);  // not in the file: the quick sweep's
  ASSERT_EQ(spec.maps.size(), 2u);
  EXPECT_EQ(spec.maps[0], (path.parent_path() / "other.gml").string());
  EXPECT_EQ(spec.maps[1], "/abs/b.gml");
  fs::remove(path);
}

TEST(SweepSpec, ErrorsNameTheFileAndLine) {
  const fs::path unknown_key = write_file("bad1.txt", "models = conic-beam\n\nwidgets = 3\n");
  EXPECT_NE(error_of(unknown_key).find("line 3"), std::string::npos) << error_of(unknown_key);
  EXPECT_NE(error_of(unknown_key).find(unknown_key.string()), std::string::npos);
  const fs::path bad_model = write_file("bad2.txt", "models = conic-beam, laser-magic\n");
  EXPECT_NE(error_of(bad_model).find("laser-magic"), std::string::npos);
  const fs::path bad_number = write_file("bad3.txt", "particles = 100, ten\n");
  EXPECT_NE(error_of(bad_number).find("line 1"), std::string::npos);
  const fs::path fraction = write_file("bad4.txt", "particles = 10.5\n");
  EXPECT_NE(error_of(fraction).find("whole number"), std::string::npos);
  const fs::path empty = write_file("bad5.txt", "seeds = ,\n");
  EXPECT_NE(error_of(empty).find("no values"), std::string::npos);
  const fs::path no_equals = write_file("bad6.txt", "models conic-beam\n");
  EXPECT_NE(error_of(no_equals).find("key = value"), std::string::npos);
  const fs::path scenario = write_file("bad7.txt", "scenarios = robot, moon\n");
  EXPECT_NE(error_of(scenario).find("moon"), std::string::npos);
  EXPECT_THROW(ce::resolve_sweep("/nonexistent/sweep.txt"), conicloc::io::InputError);
  for (const auto& p : {unknown_key, bad_model, bad_number, fraction, empty, no_equals, scenario})
    fs::remove(p);
}

TEST(SweepSpec, BuiltInSweepsUseKnownScenarios) {
  for (const auto& spec : {ce::quick_sweep(), ce::full_sweep()}) {
    for (const auto& name : spec.scenarios) EXPECT_NE(ce::find_scenario(name), nullptr) << name;
    EXPECT_FALSE(spec.models.empty());
  }
  EXPECT_EQ(ce::find_scenario("nope"), nullptr);
  EXPECT_EQ(ce::find_scenario("global")->start, ce::FilterStartMode::Global);
}

TEST(ParetoFront, KeepsOnlyUndominatedPointsOrderedByCost) {
  //            0     1     2     3     4     5
  const std::vector<double> cost{10.0, 5.0, 20.0, 5.0, 40.0, 30.0};
  const std::vector<double> error{0.5, 0.9, 0.2, 1.2, 0.2, 0.1};
  // 3 is dominated by 1 (same cost, more error); 4 by 2 (same error, more cost).
  EXPECT_EQ(ce::pareto_front(cost, error), (std::vector<std::size_t>{1, 0, 2, 5}));
  EXPECT_TRUE(ce::pareto_front({}, {}).empty());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ce::pareto_front({1.0, nan, 3.0}, {1.0, 0.1, 0.5}), (std::vector<std::size_t>{0, 2}));
}

TEST(SweepReport, ConfigurationsAverageTrackingRunsAndMarkTheFront) {
  std::vector<ce::RunRecord> runs{
      run("conic-beam", 100, 500, 0.04, 10.0), run("conic-beam", 100, 500, 0.06, 14.0),
      run("conic-beam", 1000, 500, 0.02, 60.0), run("point-to-plane", 100, 500, 0.08, 30.0),
      // A global start is summarised apart: its error must not enter the tracking means.
      run("conic-beam", 100, 500, 7.0, 12.0, "global", false)};
  runs.push_back(run("point-to-plane", 100, 500, 0.0, 0.0));
  runs.back().failed = true;
  const auto configs = ce::summarize_configs(runs);
  ASSERT_EQ(configs.size(), 3u);
  EXPECT_EQ(configs[0].runs, 2);
  EXPECT_EQ(configs[0].succeeded, 2);
  EXPECT_NEAR(configs[0].ate_xy_rmse_m, 0.05, 1e-12);
  EXPECT_NEAR(configs[0].time_per_scan_ms, 12.0, 1e-12);
  EXPECT_NEAR(configs[0].time_p95_ms, 21.0, 1e-12);  // the worse run's p95
  EXPECT_TRUE(configs[0].pareto);
  EXPECT_TRUE(configs[1].pareto);   // slower but more accurate
  EXPECT_FALSE(configs[2].pareto);  // slower and less accurate than conic-beam 100
  EXPECT_EQ(configs[2].model, "point-to-plane");
  EXPECT_EQ(configs[2].runs, 2);       // the failed run counts as a run ...
  EXPECT_EQ(configs[2].completed, 1);  // ... but not in the means
  EXPECT_NEAR(configs[2].ate_xy_rmse_m, 0.08, 1e-12);

  const std::string md = ce::summary_markdown(runs, "conicloc evaluate --sweep quick", {"p.svg"});
  EXPECT_NE(md.find("conicloc evaluate --sweep quick"), std::string::npos);
  EXPECT_NE(md.find("## Global localization"), std::string::npos);
  EXPECT_NE(md.find("| conic-beam | 100 | 500 | 1 | 0/1 | — |"), std::string::npos) << md;
  EXPECT_NE(md.find("failed"), std::string::npos);
  EXPECT_NE(md.find("![p.svg](p.svg)"), std::string::npos);
}

TEST(SweepReport, RunsCsvStartsWithTheDocumentedColumns) {
  auto r = run("conic-segment", 300, 0, 0.0312345, 42.5);
  r.error = "a, b\nc";
  const std::string csv = ce::runs_csv({r});
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.rfind("model,particles,beams,seed,scenario,ate_xy_rmse_m,heading_rmse_deg,"
                         "time_per_scan_ms,realtime_factor,converged,",
                         0),
            0u)
      << header;
  const std::string row = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(row.rfind("conic-segment,300,0,1,robot,0.03123,0.3123,42.500,2.353,1,", 0), 0u) << row;
  // Every row has as many fields as the header: commas inside the error text are replaced.
  const auto fields = [](const std::string& line) {
    return std::count(line.begin(), line.end(), ',');
  };
  EXPECT_EQ(fields(header), fields(row.substr(0, row.find('\n'))));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 2);
}

TEST(SweepReport, ParetoPlotDrawsEachModelsFrontInItsColour) {
  const std::vector<ce::RunRecord> runs{run("conic-beam", 100, 500, 0.04, 10.0),
                                        run("conic-beam", 1000, 500, 0.02, 50.0),
                                        run("point-to-plane", 100, 500, 0.08, 30.0)};
  const std::string svg = ce::pareto_svg(runs);
  const std::string beam = ce::palette_colour(0);
  const std::string plane = ce::palette_colour(1);
  EXPECT_NE(svg.find("<polyline fill=\"none\" stroke=\"" + beam + "\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("<circle"), std::string::npos);
  EXPECT_NE(svg.find("fill=\"" + plane + "\""), std::string::npos);
  // One point: no front line for point-to-plane; the legend lists models, not fronts.
  EXPECT_EQ(svg.find("stroke=\"" + plane + "\" stroke-width"), std::string::npos);
  EXPECT_EQ(svg.find(">conic-beam front<"), std::string::npos);
  EXPECT_NE(svg.find(">point-to-plane</text>"), std::string::npos);
}

TEST(SweepScenario, RobustnessScenariosKeepTheOldOnes) {
  for (const char* name :
       {"robot", "handheld", "clean", "clutter", "map-error", "global", "kidnap"})
    EXPECT_NE(ce::find_scenario(name), nullptr) << name;
  EXPECT_TRUE(ce::find_scenario("robot")->odometry);
  EXPECT_TRUE(ce::find_scenario("kidnap")->odometry);
  const auto* robot = ce::find_scenario("robot-no-odom");
  ASSERT_NE(robot, nullptr);
  EXPECT_FALSE(robot->odometry);
  EXPECT_FALSE(robot->handheld);
  const auto* handheld = ce::find_scenario("handheld-no-odom");
  ASSERT_NE(handheld, nullptr);
  EXPECT_FALSE(handheld->odometry);
  EXPECT_TRUE(handheld->handheld);
  EXPECT_EQ(ce::find_scenario("crowd")->clutter_level, 3);
  EXPECT_TRUE(ce::find_scenario("crowd")->odometry);
  EXPECT_DOUBLE_EQ(ce::find_scenario("map-error-5cm")->map_error_m, 0.05);
  EXPECT_EQ(ce::find_scenario("global-no-odom")->start, ce::FilterStartMode::Global);
  EXPECT_FALSE(ce::find_scenario("global-no-odom")->odometry);
  EXPECT_EQ(ce::find_scenario("kidnap-no-odom")->start, ce::FilterStartMode::Kidnap);
  EXPECT_FALSE(ce::find_scenario("kidnap-no-odom")->odometry);
  const auto* crowd = ce::find_scenario("global-crowd");
  ASSERT_NE(crowd, nullptr);
  EXPECT_EQ(crowd->start, ce::FilterStartMode::Global);
  EXPECT_EQ(crowd->clutter_level, 3);
  EXPECT_TRUE(crowd->odometry);
  const auto* map_error = ce::find_scenario("global-map-error");
  ASSERT_NE(map_error, nullptr);
  EXPECT_EQ(map_error->start, ce::FilterStartMode::Global);
  EXPECT_DOUBLE_EQ(map_error->map_error_m, 0.05);
  EXPECT_EQ(map_error->clutter_level, 1);
}

TEST(SweepSpec, RobustnessSweepListsThePublicModelsAndTheGeneratedKinds) {
  const fs::path dir = conicloc::test::unique_temp_path("public_models");
  fs::create_directories(dir);
  for (const char* name : {"b.gml", "a.gml", "notes.txt"}) std::ofstream(dir / name) << "x";
  const auto spec = ce::robustness_sweep(dir.string());
  EXPECT_EQ(spec.name, "robustness");
  EXPECT_EQ(spec.maps, (std::vector<std::string>{(dir / "a.gml").string(), (dir / "b.gml").string(),
                                                 "generated:corridor", "generated:wings",
                                                 "generated:hall", "generated:storeys"}));
  EXPECT_TRUE(spec.warnings.empty());
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(spec.models.size(), 3u);
  EXPECT_EQ(spec.particles, (std::vector<int>{ce::kDefaultSetting}));
  EXPECT_EQ(spec.beams, (std::vector<int>{ce::kDefaultSetting}));
  EXPECT_DOUBLE_EQ(spec.duration_s, 30.0);
  for (const char* name : {"robot", "robot-no-odom", "handheld-no-odom", "crowd", "map-error-5cm",
                           "global", "kidnap"}) {
    EXPECT_NE(std::find(spec.scenarios.begin(), spec.scenarios.end(), name), spec.scenarios.end())
        << name;
  }
  for (const auto& name : spec.scenarios) EXPECT_NE(ce::find_scenario(name), nullptr) << name;
  EXPECT_EQ(ce::resolve_sweep("robustness", dir.string()).maps, spec.maps);
  fs::remove_all(dir);

  const auto without = ce::robustness_sweep((dir / "absent").string());
  EXPECT_EQ(without.maps.size(), 4u);
  ASSERT_EQ(without.warnings.size(), 1u);
  EXPECT_NE(without.warnings[0].find("absent"), std::string::npos);
}

TEST(SweepSpec, ScaleSweepGrowsAStoreysBuildingInStoreysAndFloorPlates) {
  const auto spec = ce::resolve_sweep("scale");
  EXPECT_EQ(spec.name, "scale");
  ASSERT_EQ(spec.maps.size(), 7u);
  int most_storeys = 0, most_plates = 0;
  for (const auto& map : spec.maps) {
    const auto generated = conicloc::sim::parse_generated_building_spec(map);
    ASSERT_TRUE(generated.has_value()) << map;
    EXPECT_EQ(generated->kind, "storeys");
    most_storeys = std::max(most_storeys, generated->scale.storeys);
    most_plates = std::max(most_plates, generated->scale.plate_tiles);
  }
  EXPECT_EQ(most_storeys, 10);  // issue 15: up to 10 storeys, up to 4 floor plates
  EXPECT_EQ(most_plates, 4);
  EXPECT_EQ(spec.scenarios, (std::vector<std::string>{"robot", "global"}));
  const fs::path path = write_file("scale.sweep", "base = scale\nseeds = 1\n");
  EXPECT_EQ(ce::read_sweep_file(path.string()).maps, spec.maps);
  fs::remove(path);
}

TEST(SweepSpec, BaseChoosesTheSweepTheFileModifies) {
  // `base` applies first wherever it stands; `maps =` alone leaves only --map.
  const fs::path path = write_file("reduced.sweep",
                                   "seeds = 1\n"
                                   "base = robustness\n"
                                   "models = conic-beam\n"
                                   "beams = default, 500\n"
                                   "maps =\n");
  const auto spec = ce::read_sweep_file(path.string(), "/nonexistent");
  EXPECT_EQ(spec.name, path.string());
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{1}));
  EXPECT_EQ(spec.models, (std::vector<std::string>{"conic-beam"}));
  EXPECT_EQ(spec.beams, (std::vector<int>{ce::kDefaultSetting, 500}));
  EXPECT_EQ(spec.particles, (std::vector<int>{ce::kDefaultSetting}));
  EXPECT_EQ(spec.scenarios, ce::robustness_sweep("").scenarios);
  EXPECT_DOUBLE_EQ(spec.duration_s, 30.0);
  EXPECT_TRUE(spec.maps.empty());
  EXPECT_TRUE(spec.warnings.empty());  // the public models were not wanted
  // Generated buildings are not paths relative to the file.
  const fs::path generated = write_file(
      "generated.sweep", "base = full\nmaps = generated:hall, generated:wings:7, x.gml\n");
  const auto full = ce::read_sweep_file(generated.string());
  EXPECT_EQ(full.maps, (std::vector<std::string>{"generated:hall", "generated:wings:7",
                                                 (generated.parent_path() / "x.gml").string()}));
  EXPECT_EQ(full.particles, ce::full_sweep().particles);

  const fs::path bad = write_file("bad_base.sweep", "models = conic-beam\nbase = huge\n");
  EXPECT_NE(error_of(bad).find("line 2"), std::string::npos) << error_of(bad);
  EXPECT_NE(error_of(bad).find("huge"), std::string::npos);
  const fs::path two = write_file("two_bases.sweep", "base = quick, full\n");
  EXPECT_NE(error_of(two).find("one value"), std::string::npos) << error_of(two);
  EXPECT_EQ(ce::setting_text(ce::kDefaultSetting), "default");
  EXPECT_EQ(ce::beams_text(0), "all");
  EXPECT_EQ(ce::beams_text(300), "300");
  for (const auto& p : {path, generated, bad, two}) fs::remove(p);
}

TEST(SweepSpec, SweepFileTextReadsBackToTheSameSpec) {
  ce::SweepSpec custom = ce::quick_sweep();
  custom.maps = {"/abs/a.gml", "generated:corridor", "generated:hall:7"};
  custom.particles = {ce::kDefaultSetting, 250};
  custom.beams = {0, ce::kDefaultSetting};
  custom.seeds = {0, 9000000000000000ull};
  custom.duration_s = 1.1 + 2.2;  // not a short decimal
  custom.threads = 3;
  custom.keep_captures = true;
  for (const auto& spec : {ce::quick_sweep(), ce::full_sweep(), custom}) {
    const fs::path path = write_file("roundtrip.sweep", ce::sweep_file_text(spec));
    const auto back = ce::read_sweep_file(path.string());
    fs::remove(path);
    EXPECT_EQ(back.maps, spec.maps);
    EXPECT_EQ(back.models, spec.models);
    EXPECT_EQ(back.particles, spec.particles);
    EXPECT_EQ(back.beams, spec.beams);
    EXPECT_EQ(back.seeds, spec.seeds);
    EXPECT_EQ(back.scenarios, spec.scenarios);
    EXPECT_EQ(back.duration_s, spec.duration_s);
    EXPECT_EQ(back.threads, spec.threads);
    EXPECT_EQ(back.keep_captures, spec.keep_captures);
    EXPECT_EQ(ce::sweep_file_text(back), ce::sweep_file_text(spec));
  }
}
