// Sharded sweeps: run keys and the sweep's order, the split into shards, resuming a shard, and
// merging the shards back into the sweep's order with missing and duplicated runs named.
#include <gtest/gtest.h>

#include <algorithm>

#include "eval/sweep_plan.hpp"
#include "eval/sweep_shard.hpp"

namespace ce = conicloc::eval;

namespace {

ce::SweepSpec tiny_spec() {
  ce::SweepSpec spec;
  spec.models = {"conic-beam", "conic-segment"};
  spec.particles = {100, ce::kDefaultSetting};
  spec.beams = {300, 0};
  spec.seeds = {1, 2};
  spec.scenarios = {"robot", "kidnap"};
  return spec;
}

const std::vector<ce::PlannedBuilding> kBuildings{{"house", false}, {"corridor", true}};

ce::RunRecord record_of(const ce::RunKey& key) {
  ce::RunRecord r;
  r.building = key.building;
  r.scenario = key.scenario;
  r.seed = key.seed;
  r.model = key.model;
  r.particles = key.particles;
  r.beams = key.beams;
  return r;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ce::ShardError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SweepPlan, RunsInTheSweepsOrderWithReadableKeys) {
  const auto plan = ce::plan_runs(kBuildings, tiny_spec());
  // conic-beam: 2 particles x 2 beams; conic-segment: 2 particles, all returns.
  ASSERT_EQ(ce::localizer_settings(tiny_spec()).size(), 6u);
  ASSERT_EQ(plan.size(), 2u * 2u * 2u * 6u);
  EXPECT_EQ(plan.front().text(), "house/robot/s1/conic-beam/p100/b300");
  EXPECT_EQ(plan[1].text(), "house/robot/s1/conic-beam/p100/b0");
  EXPECT_EQ(plan[3].text(), "house/robot/s1/conic-beam/pdefault/b0");
  EXPECT_EQ(plan[4].text(), "house/robot/s1/conic-segment/p100/b0");
  EXPECT_EQ(plan[6].text(), "house/kidnap/s1/conic-beam/p100/b300");
  EXPECT_EQ(plan[12].text(), "house/robot/s2/conic-beam/p100/b300");
  EXPECT_EQ(plan[24].text(), "corridor-s1/robot/s1/conic-beam/p100/b300");
  EXPECT_EQ(plan.back().text(), "corridor-s2/kidnap/s2/conic-segment/pdefault/b0");
  std::vector<ce::RunKey> sorted = plan;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "keys are unique";
}

TEST(Shard, ParsesOneBasedIOfN) {
  EXPECT_EQ(ce::parse_shard("1/4").index, 1);
  EXPECT_EQ(ce::parse_shard("4/4").index, 4);
  EXPECT_EQ(ce::parse_shard("4/4").count, 4);
  EXPECT_EQ(ce::parse_shard("1/1").count, 1);
  EXPECT_EQ(ce::parse_shard("3/12").text(), "3/12");
  for (const char* bad : {"0/4", "5/4", "1/0", "0/0", "1", "1/", "/4", "a/4", "1/4x", " 1/4",
                          "-1/4", "1/-4", "1.0/4", "1/4/5", "", "1/99999999"}) {
    EXPECT_THROW(ce::parse_shard(bad), std::invalid_argument) << bad;
  }
  try {
    ce::parse_shard("0/4");
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'0/4'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1/4"), std::string::npos) << e.what();
  }
}

TEST(Shard, EveryRunInExactlyOneShardAndSharesDifferByAtMostOne) {
  for (int count = 1; count <= 7; ++count) {
    std::vector<int> holders(23, 0);
    std::vector<int> share(static_cast<std::size_t>(count), 0);
    for (int index = 1; index <= count; ++index) {
      for (std::size_t run = 0; run < holders.size(); ++run) {
        if (!ce::Shard{index, count}.holds(run)) continue;
        ++holders[run];
        ++share[static_cast<std::size_t>(index - 1)];
      }
    }
    EXPECT_TRUE(std::all_of(holders.begin(), holders.end(), [](int h) { return h == 1; }));
    const auto [lo, hi] = std::minmax_element(share.begin(), share.end());
    EXPECT_LE(*hi - *lo, 1) << count << " shards";
  }
  const ce::Shard second{2, 4};
  EXPECT_FALSE(second.holds(0));
  EXPECT_TRUE(second.holds(1));
  EXPECT_TRUE(second.holds(5));
  EXPECT_FALSE(second.holds(6));
}

TEST(Shard, ResumeSkipsTheHeldRunsOnly) {
  const auto plan = ce::plan_runs(kBuildings, tiny_spec());
  const ce::Shard shard{2, 4};
  const auto all = ce::pending_runs(plan, shard, {});
  ASSERT_EQ(all.size(), plan.size() / 4);
  EXPECT_EQ(all.front(), 1u);
  EXPECT_EQ(all[1], 5u);
  const auto rest = ce::pending_runs(plan, shard, {record_of(plan[5]), record_of(plan[1])});
  ASSERT_EQ(rest.size(), all.size() - 2);
  EXPECT_EQ(rest.front(), 9u);
  EXPECT_TRUE(ce::pending_runs(plan, shard,
                               [&] {
                                 std::vector<ce::RunRecord> held;
                                 for (const auto i : all) held.push_back(record_of(plan[i]));
                                 return held;
                               }())
                  .empty());
}

TEST(Shard, ResumeRefusesRunsOfAnotherShardOrTwice) {
  const auto plan = ce::plan_runs(kBuildings, tiny_spec());
  const std::string other = message_of([&] {
    ce::pending_runs(plan, {2, 4}, {record_of(plan[2])});
  });
  EXPECT_NE(other.find(plan[2].text()), std::string::npos) << other;
  EXPECT_NE(other.find("2/4"), std::string::npos) << other;
  const std::string twice = message_of([&] {
    ce::pending_runs(plan, {2, 4}, {record_of(plan[1]), record_of(plan[1])});
  });
  EXPECT_NE(twice.find(plan[1].text()), std::string::npos) << twice;
}

TEST(Shard, MergeRestoresTheSweepsOrder) {
  const auto plan = ce::plan_runs(kBuildings, tiny_spec());
  std::vector<ce::ShardRuns> shards{{"d3", {}}, {"d1", {}}, {"d2", {}}};
  // Shard 3's folder first, and each shard's runs backwards.
  for (std::size_t i = plan.size(); i-- > 0;) {
    ce::RunRecord r = record_of(plan[i]);
    r.metrics.ate_xy_m.rmse = static_cast<double>(i);
    shards[(i % 3 + 1) % 3].runs.push_back(r);
  }
  const auto merged = ce::merge_shards(plan, shards);
  ASSERT_EQ(merged.size(), plan.size());
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(ce::key_of(merged[i]), plan[i]);
    EXPECT_EQ(merged[i].metrics.ate_xy_m.rmse, static_cast<double>(i));
  }
}

TEST(Shard, MergeNamesMissingDuplicatedAndForeignRuns) {
  const auto plan = ce::plan_runs(kBuildings, tiny_spec());
  std::vector<ce::ShardRuns> shards{{"out/shard-1", {}}, {"out/shard-2", {}}};
  for (std::size_t i = 0; i < plan.size(); ++i) shards[i % 2].runs.push_back(record_of(plan[i]));
  ASSERT_EQ(ce::merge_shards(plan, shards).size(), plan.size());

  auto missing = shards;
  missing[1].runs.erase(missing[1].runs.begin() + 3);  // plan[7]
  const std::string gone = message_of([&] { ce::merge_shards(plan, missing); });
  EXPECT_NE(gone.find(plan[7].text()), std::string::npos) << gone;
  EXPECT_NE(gone.find("missing"), std::string::npos) << gone;
  EXPECT_NE(gone.find("out/shard-1, out/shard-2"), std::string::npos) << gone;

  auto duplicated = shards;
  duplicated[1].runs.push_back(record_of(plan[4]));
  const std::string twice = message_of([&] { ce::merge_shards(plan, duplicated); });
  EXPECT_NE(twice.find(plan[4].text()), std::string::npos) << twice;
  EXPECT_NE(twice.find("in out/shard-1 and in out/shard-2"), std::string::npos) << twice;

  auto foreign = shards;
  ce::RunRecord stranger = record_of(plan[0]);
  stranger.seed = 3;
  foreign[0].runs.push_back(stranger);
  const std::string unknown = message_of([&] { ce::merge_shards(plan, foreign); });
  EXPECT_NE(unknown.find("house/robot/s3/conic-beam/p100/b300"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("out/shard-1"), std::string::npos) << unknown;
}
