// RolloutPool: the results of a run are a function of its cases alone: not of
// the number of threads, not of whether a World is reused or built afresh; and
// ending an episode at rest changes a landing by far less than the jumps' error.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "pronk/report.h"
#include "pronk/rollout.h"

namespace pronk {
namespace {

const std::string kMix = std::string(PRONK_SOURCE_DIR) + "/tests/cli/scenarios/go1_rollout_mix.xml";

class Rollout : public ::testing::Test {
 protected:
  void SetUp() override {
    registry_.load(PRONK_GUIDED_JUMP_PLUGIN);
    scenario_ = loadScenario(kMix);
  }
  RolloutSetup setup() const { return environmentSetup(scenario_, registry_, {}, "ballistic"); }
  std::vector<EpisodeRecord> run(const RolloutOptions& options, const std::string& sweep) {
    RolloutPool pool(setup(), options);
    std::vector<EpisodeRecord> records;
    pool.run(sweepCases(scenario_, sweep), [&](EpisodeRecord& r) { records.push_back(std::move(r)); });
    return records;
  }

  PluginRegistry registry_;
  Scenario scenario_;
};

// Every number a sink sees, compared exactly (NaN equals NaN).
void expectSameRecords(const std::vector<EpisodeRecord>& a, const std::vector<EpisodeRecord>& b) {
  ASSERT_EQ(a.size(), b.size());
  auto same = [](double x, double y) { return x == y || (std::isnan(x) && std::isnan(y)); };
  for (size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const EnvironmentEpisodeResult &x = a[i].result, &y = b[i].result;
    EXPECT_EQ(a[i].index, b[i].index);
    EXPECT_EQ(x.observation, y.observation);
    EXPECT_EQ(x.action, y.action);
    EXPECT_TRUE(same(x.reward, y.reward)) << x.reward << " " << y.reward;
    EXPECT_EQ(x.rejected, y.rejected);
    EXPECT_EQ(x.episode.failure.has_value(), y.episode.failure.has_value());
    ASSERT_EQ(x.episode.trace.metrics.size(), y.episode.trace.metrics.size());
    for (size_t m = 0; m < x.episode.trace.metrics.size(); ++m) {
      EXPECT_EQ(x.episode.trace.metrics[m].name, y.episode.trace.metrics[m].name);
      EXPECT_TRUE(same(x.episode.trace.metrics[m].value, y.episode.trace.metrics[m].value))
          << x.episode.trace.metrics[m].name;
    }
    ASSERT_EQ(x.episode.trace.events.size(), y.episode.trace.events.size());
    for (size_t e = 0; e < x.episode.trace.events.size(); ++e) {
      EXPECT_EQ(x.episode.trace.events[e].name, y.episode.trace.events[e].name);
      EXPECT_EQ(x.episode.trace.events[e].time, y.episode.trace.events[e].time);
    }
    ASSERT_EQ(x.episode.trace.samples.size(), y.episode.trace.samples.size());
    if (!x.episode.trace.samples.empty()) {
      const TraceSample &p = x.episode.trace.samples.back(), &q = y.episode.trace.samples.back();
      EXPECT_EQ(p.time, q.time);
      EXPECT_EQ(p.base_position, q.base_position);
      EXPECT_EQ(p.base_quaternion, q.base_quaternion);
      EXPECT_EQ(p.q, q.q);
      EXPECT_EQ(p.qd, q.qd);
    }
  }
}

TEST_F(Rollout, ReusedWorldsOnTwoThreadsEqualAFreshWorldPerCaseOnOne) {
  // `mix` swaps step platforms between cases (a reused World's terrain
  // changes); `mass` changes the trunk mass between cases (a new World).
  for (const char* sweep : {"mix", "mass"}) {
    SCOPED_TRACE(sweep);
    RolloutOptions fresh;
    fresh.threads = 1;
    fresh.reuse_worlds = false;
    RolloutOptions reused;
    reused.threads = 2;
    expectSameRecords(run(fresh, sweep), run(reused, sweep));
  }
}

TEST_F(Rollout, ThreadCountsChangeNoRecordAndWorldsAreReused) {
  RolloutOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const std::vector<EpisodeCase> cases = sweepCases(scenario_, "mix");
  RolloutPool a(setup(), one), b(setup(), two);
  std::vector<EpisodeRecord> ra, rb;
  a.run(cases, [&](EpisodeRecord& r) { ra.push_back(std::move(r)); });
  b.run(cases, [&](EpisodeRecord& r) { rb.push_back(std::move(r)); });
  expectSameRecords(ra, rb);
  EXPECT_EQ(a.worldsBuilt(), 1u);  // six cases, one World
  EXPECT_LE(b.worldsBuilt(), 2u);
  // The mix has landed, refused and failed jumps, so each path was compared.
  int landed = 0, rejected = 0, failed = 0;
  for (const EpisodeRecord& r : ra) {
    const std::string status = judgeJump(r).status;
    landed += status == "ok" || status == "missed";
    rejected += status == "rejected";
    failed += status == "failed";
  }
  EXPECT_GT(landed, 0);
  EXPECT_GT(rejected, 0);
  EXPECT_GT(failed, 0);
}

TEST_F(Rollout, ChosenCasesGetWhatAWholeRunGivesThemInTheOrderAsked) {
  // What a resumed evaluation relies on: case k of a partial run is case k of
  // the whole run (its index, its seed), whatever else runs beside it.
  RolloutOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const std::vector<EpisodeCase> cases = sweepCases(scenario_, "mix");
  ASSERT_GE(cases.size(), 5u);
  RolloutPool a(setup(), one), b(setup(), two);
  std::vector<EpisodeRecord> whole, part;
  a.run(cases, [&](EpisodeRecord& r) { whole.push_back(std::move(r)); });
  const std::vector<size_t> which = {4, 1, 3};
  EXPECT_EQ(b.run(cases, which, [&](EpisodeRecord& r) { part.push_back(std::move(r)); }), 3u);
  std::vector<EpisodeRecord> expected;
  for (size_t i : which) expected.push_back(whole[i]);
  expectSameRecords(expected, part);
  EXPECT_EQ(part[0].index, 4u);
  EXPECT_THROW(b.run(cases, {cases.size()}, [](EpisodeRecord&) {}), Error);
}

TEST_F(Rollout, EndingAtRestMovesNoLandingByMoreThanTwoMillimetres) {
  // The flat region's first eight targets, run to the environment's end and
  // stopped 0.2 s after coming to rest.
  Scenario flat = loadScenario(std::string(PRONK_SOURCE_DIR) + "/scenarios/go1/region.xml");
  std::vector<EpisodeCase> cases = sweepCases(flat, "region");
  cases.resize(8);
  RolloutOptions full, at_rest;
  full.threads = at_rest.threads = 2;
  full.end_at_rest = 0;
  std::vector<EpisodeRecord> a, b;
  RolloutPool(environmentSetup(flat, registry_, {}, "ballistic"), full).run(cases, [&](EpisodeRecord& r) {
    a.push_back(std::move(r));
  });
  RolloutPool(environmentSetup(flat, registry_, {}, "ballistic"), at_rest).run(cases, [&](EpisodeRecord& r) {
    b.push_back(std::move(r));
  });
  ASSERT_EQ(a.size(), b.size());
  int stopped_early = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const JumpOutcome x = judgeJump(a[i]), y = judgeJump(b[i]);
    EXPECT_EQ(x.status, y.status) << i;
    if (x.status != "ok") continue;
    EXPECT_NEAR(x.landing.error_xy, y.landing.error_xy, 2e-3) << i;
    stopped_early += b[i].result.episode.trace.findEvent("at_rest") != nullptr;
  }
  EXPECT_GT(stopped_early, 0);  // the lever acted, so the comparison means something
}

TEST_F(Rollout, RecordsArriveInCaseOrderAndASinkErrorStopsTheRun) {
  RolloutOptions two;
  two.threads = 2;
  RolloutPool pool(setup(), two);
  const std::vector<EpisodeCase> cases = sweepCases(scenario_, "mix");
  std::vector<size_t> order;
  EXPECT_THROW(pool.run(cases,
                        [&](EpisodeRecord& r) {
                          order.push_back(r.index);
                          if (r.index == 2) throw std::runtime_error("sink failed");
                        }),
               std::runtime_error);
  EXPECT_EQ(order, (std::vector<size_t>{0, 1, 2}));
  // The pool runs again afterwards, from the first case.
  order.clear();
  EXPECT_EQ(pool.run(cases, [&](EpisodeRecord& r) { order.push_back(r.index); }), cases.size());
  EXPECT_EQ(order.size(), cases.size());
  for (size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
}

TEST_F(Rollout, ACaseWhosePolicyThrowsFailsAloneWithItsReason) {
  RolloutSetup s = setup();
  const Policy planner = s.policy;
  s.policy = [planner](const std::vector<double>& observation, EnvironmentInstance& env, uint64_t seed) {
    if (seed == 1) throw Error("this policy has no action for case 1");
    return planner(observation, env, seed);
  };
  const std::vector<EpisodeCase> cases = sweepCases(scenario_, "mass");  // "ahead" three times
  ASSERT_EQ(cases.size(), 3u);
  RolloutOptions options;
  options.threads = 2;
  RolloutPool pool(std::move(s), options);
  std::vector<JumpOutcome> outcomes;
  EXPECT_EQ(pool.run(cases, [&](EpisodeRecord& r) { outcomes.push_back(judgeJump(r)); }), cases.size());
  ASSERT_EQ(outcomes.size(), cases.size());
  EXPECT_EQ(outcomes[1].status, "failed");
  EXPECT_NE(outcomes[1].reason.find("this policy has no action for case 1"), std::string::npos) << outcomes[1].reason;
  EXPECT_EQ(outcomes[0].status, "ok") << outcomes[0].reason;
  EXPECT_EQ(outcomes[2].status, "ok") << outcomes[2].reason;
}

TEST_F(Rollout, ACaseWithNoRoomForItsEdgeIsRefusedAloneWithItsReason) {
  // A height target straight above the start has no room for a platform edge.
  std::vector<EpisodeCase> cases = targetCases(scenario_);
  EpisodeCase above = cases.front();
  above.label = "straight up";
  above.target.x = 0.01;
  above.target.z = 0.2;
  cases.insert(cases.begin(), above);
  RolloutPool pool(setup(), RolloutOptions{});
  std::vector<JumpOutcome> outcomes;
  pool.run(cases, [&](EpisodeRecord& r) { outcomes.push_back(judgeJump(r)); });
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_EQ(outcomes[0].status, "rejected");
  EXPECT_EQ(outcomes[0].reason.rfind("terrain: ", 0), 0u) << outcomes[0].reason;
  EXPECT_NE(outcomes[0].reason.find("needs a platform edge"), std::string::npos) << outcomes[0].reason;
  EXPECT_EQ(outcomes[1].status, "ok") << outcomes[1].reason;
}

}  // namespace
}  // namespace pronk
