// The targets training draws: inside the region, heights away from the start,
// the same for a seed, and a validation set apart from the training draws.
#include <gtest/gtest.h>

#include <cmath>

#include "pronk/error.h"
#include "pronk/training.h"

namespace {

pronk::TrainingSpec omniRegion() {
  pronk::TrainingSpec t;
  t.x = {-0.6, 1.2};
  t.y = {-0.6, 0.6};
  t.z = {-0.4, 0.4};
  t.yaw = {-1.5707963267948966, 1.5707963267948966};
  return t;
}

TEST(TargetSampler, DrawsInsideTheRegionAndKeepsHeightsAwayFromTheStart) {
  const pronk::TrainingSpec t = omniRegion();
  pronk::Rng rng(4);
  const std::vector<pronk::EpisodeCase> cases = pronk::TargetSampler(t).cases(rng, 2000, "c");
  ASSERT_EQ(cases.size(), 2000u);
  double min_x = 1e9, max_x = -1e9;
  for (const pronk::EpisodeCase& c : cases) {
    const pronk::TargetSpec& g = c.target;
    EXPECT_GE(g.x, t.x.min);
    EXPECT_LE(g.x, t.x.max);
    EXPECT_GE(g.y, t.y.min);
    EXPECT_LE(g.y, t.y.max);
    EXPECT_GE(g.z, t.z.min);
    EXPECT_LE(g.z, t.z.max);
    EXPECT_GE(g.yaw, t.yaw.min);
    EXPECT_LE(g.yaw, t.yaw.max);
    EXPECT_EQ(g.roll, 0);
    EXPECT_EQ(g.pitch, 0);
    EXPECT_GE(std::hypot(g.x, g.y), pronk::TargetSampler::kLeastStepDistance) << c.label;
    min_x = std::min(min_x, g.x);
    max_x = std::max(max_x, g.x);
  }
  EXPECT_LT(min_x, -0.55);  // the whole range is used
  EXPECT_GT(max_x, 1.15);
  EXPECT_EQ(cases[7].label, "c #7");
}

TEST(TargetSampler, FlatTargetsMayLieAtTheStart) {
  pronk::TrainingSpec t = omniRegion();
  t.x = {0, 0};
  t.y = {0, 0};
  t.z = {0, 0};
  pronk::Rng rng(1);
  const pronk::TargetSpec g = pronk::TargetSampler(t).draw(rng);  // a twist in place
  EXPECT_EQ(g.x, 0);
  EXPECT_EQ(g.y, 0);
}

TEST(TargetSampler, DrawsItsFlatShareAtZeroHeightAndTheRestAsWithout) {
  pronk::TrainingSpec t = omniRegion();
  t.flat_share = 0.25;
  pronk::Rng rng(9);
  const std::vector<pronk::EpisodeCase> cases = pronk::TargetSampler(t).cases(rng, 4000, "c");
  int flat = 0;
  for (const pronk::EpisodeCase& c : cases) flat += c.target.z == 0;
  // Binomial(4000, 0.25): mean 1000, sd 27; the uniform z is never exactly 0.
  EXPECT_GT(flat, 880);
  EXPECT_LT(flat, 1120);
  // A region without a flat share draws what it drew before flat_share existed:
  // no extra number from the stream.
  pronk::TrainingSpec plain = omniRegion();
  pronk::Rng a(3), b(3);
  const pronk::TargetSpec first = pronk::TargetSampler(plain).draw(a);
  EXPECT_EQ(first.x, t.x.min + (t.x.max - t.x.min) * b.uniform());
  EXPECT_EQ(first.y, t.y.min + (t.y.max - t.y.min) * b.uniform());
  EXPECT_EQ(first.z, t.z.min + (t.z.max - t.z.min) * b.uniform());
}

TEST(ValidationSet, IsFixedForItsSeedAndApartFromTheTrainingDraws) {
  pronk::TrainingSpec t = omniRegion();
  t.validation_count = 50;
  t.validation_seed = 1;
  const std::vector<pronk::EpisodeCase> a = pronk::validationCases(t), b = pronk::validationCases(t);
  ASSERT_EQ(a.size(), 50u);
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].target.x, b[i].target.x);
    EXPECT_EQ(a[i].target.yaw, b[i].target.yaw);
  }
  // A plain stream of the same seed (what a training stream would be without
  // its own derivation) gives other targets.
  pronk::Rng plain(1);
  const std::vector<pronk::EpisodeCase> other = pronk::TargetSampler(t).cases(plain, 50, "t");
  int same = 0;
  for (size_t i = 0; i < a.size(); ++i) same += a[i].target.x == other[i].target.x;
  EXPECT_EQ(same, 0);
  t.validation_seed = 2;
  EXPECT_NE(pronk::validationCases(t)[0].target.x, a[0].target.x);
}

TEST(TargetSampler, PlacesEdgesAndDrawsAgainWhatHasNoRoom) {
  // A room check that takes only targets at least 0.7 m away: every case gets
  // its edge's place in 0 .. 1, and none nearer passes.
  pronk::TrainingSpec t = omniRegion();
  pronk::TargetSampler sampler(t);
  int asked = 0;
  sampler.placeEdges([&asked](const pronk::EpisodeCase& c) {
    ++asked;
    return std::hypot(c.target.x, c.target.y) >= 0.7;
  });
  pronk::Rng rng(5);
  const std::vector<pronk::EpisodeCase> cases = sampler.cases(rng, 500, "c");
  ASSERT_EQ(cases.size(), 500u);
  for (const pronk::EpisodeCase& c : cases) {
    EXPECT_GE(std::hypot(c.target.x, c.target.y), 0.7) << c.label;
    ASSERT_EQ(c.assignments.size(), 1u);
    EXPECT_EQ(c.assignments[0].first, "terrain.edge");
    EXPECT_GE(c.assignments[0].second, 0.0);
    EXPECT_LT(c.assignments[0].second, 1.0);
  }
  EXPECT_GT(asked, 500);  // some were drawn again
  // The same seed, the same cases; the validation set draws its edges too.
  pronk::Rng again(5);
  const std::vector<pronk::EpisodeCase> twice = sampler.cases(again, 500, "c");
  for (size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(cases[i].target.x, twice[i].target.x);
    EXPECT_EQ(cases[i].assignments, twice[i].assignments);
  }
  t.validation_count = 20;
  for (const pronk::EpisodeCase& c : pronk::validationCases(t, sampler)) EXPECT_EQ(c.assignments.size(), 1u);
  // A region with no room at all is an error, not a hang.
  pronk::TargetSampler none(t);
  none.placeEdges([](const pronk::EpisodeCase&) { return false; });
  pronk::Rng r(1);
  EXPECT_THROW(none.cases(r, 1, "c"), pronk::InputError);
}

}  // namespace
