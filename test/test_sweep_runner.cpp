// A whole evaluation sweep through the run library (run/sweep_runner.hpp): its runs returned in
// the order runs.csv holds them, its progress told through the callbacks, its folder written.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "eval/sweep_report.hpp"
#include "run/sweep_runner.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace cr = conicloc::run;
namespace fs = std::filesystem;

TEST(SweepRunner, RunsEverySettingAndTellsEachRun) {
  if (!fs::exists(CONICLOC_EXAMPLE_MAP)) GTEST_SKIP() << "no example building";
  const fs::path dir = conicloc::test::unique_temp_path("sweep_runner");
  cr::SweepOptions options;
  options.map_path = CONICLOC_EXAMPLE_MAP;
  options.out_dir = dir.string();
  options.command = "test";
  options.spec.name = "tiny";
  options.spec.models = {"conic-beam", "point-to-plane"};
  options.spec.particles = {100};
  options.spec.beams = {200};
  options.spec.seeds = {1};
  options.spec.scenarios = {"robot"};
  options.spec.duration_s = 2.0;
  options.spec.threads = 1;

  std::vector<cr::SweepOutline> outlines;
  std::vector<std::string> told;  // building, scenario, model of each run, in order
  std::vector<std::size_t> done;
  cr::SweepProgress progress;
  progress.started = [&](const cr::SweepOutline& outline) { outlines.push_back(outline); };
  progress.run_done = [&](const cr::SweepRunDone& run) {
    told.push_back(run.building + " " + run.scenario->name + " " + run.setting.model);
    done.push_back(run.done);
    EXPECT_EQ(run.share, 2u);
    EXPECT_EQ(run.record->model, run.setting.model);
  };
  progress.error = [](const std::string& message) { ADD_FAILURE() << message; };
  const cr::SweepResult result = cr::run_sweep(options, progress);

  EXPECT_EQ(result.failed, 0);
  ASSERT_EQ(outlines.size(), 1u);
  EXPECT_EQ(outlines[0].runs, 2u);
  EXPECT_EQ(outlines[0].recordings, 1u);
  EXPECT_EQ(outlines[0].settings, 2u);
  EXPECT_EQ(outlines[0].to_make, 2u);
  EXPECT_EQ(told, (std::vector<std::string>{"example_building robot conic-beam",
                                            "example_building robot point-to-plane"}));
  EXPECT_EQ(done, (std::vector<std::size_t>{1, 2}));
  ASSERT_EQ(result.runs.size(), 2u);
  for (const auto& run : result.runs) {
    EXPECT_FALSE(run.failed) << run.error;
    EXPECT_GT(run.scans, 10u);
    EXPECT_TRUE(fs::exists(dir / run.estimate_file)) << run.estimate_file;
  }
  // The table returned is the one written.
  EXPECT_EQ(conicloc::test::slurp(dir / "runs.csv"), conicloc::eval::runs_csv(result.runs));
  for (const char* file : {"summary.md", "robustness.md", "sweep.txt", "shard.txt"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
  fs::remove_all(dir);
}
