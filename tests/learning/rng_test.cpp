// Rng: the published algorithm's outputs for a seed (so a run is the same on
// every machine), and its distributions.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pronk/error.h"
#include "pronk/rng.h"

namespace {

TEST(Rng, SeedsThroughSplitMix64AndStepsAsXoshiro256StarStar) {
  // Reference values from an independent Python transcription of
  // splitmix64.c and xoshiro256starstar.c.
  pronk::Rng rng(42);
  const pronk::Rng::State seeded{0xbdd732262feb6e95ULL, 0x28efe333b266f103ULL, 0x47526757130f9f52ULL,
                                 0x581ce1ff0e4ae394ULL};
  EXPECT_EQ(rng.state(), seeded);
  EXPECT_EQ(rng.next(), 0x15780b2e0c2ec716ULL);
  EXPECT_EQ(rng.next(), 0x6104d9866d113a7eULL);
  EXPECT_EQ(rng.next(), 0xae17533239e499a1ULL);
  EXPECT_EQ(rng.uniform(), 0.9246929453253876);
  EXPECT_DOUBLE_EQ(rng.normal(), 0.3834617912676943);  // Box-Muller through libm's log and cos
}

TEST(Rng, NormalsHaveMeanZeroAndUnitVariance) {
  pronk::Rng rng(7);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double z = rng.normal();
    sum += z;
    sum2 += z * z;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 0.01);  // 4.5 standard errors
  EXPECT_NEAR(sum2 / n - mean * mean, 1.0, 0.015);
}

TEST(Rng, BelowCoversItsRangeEvenly) {
  pronk::Rng rng(3);
  std::vector<int> counts(6, 0);
  for (int i = 0; i < 60000; ++i) ++counts[rng.below(6)];
  for (int c : counts) EXPECT_NEAR(c, 10000, 450);
}

TEST(Rng, StateRoundTripsAndRefusesZero) {
  pronk::Rng a(11);
  a.next();
  pronk::Rng b(0);
  b.setState(a.state());
  EXPECT_EQ(a.next(), b.next());
  EXPECT_THROW(b.setState({0, 0, 0, 0}), pronk::Error);
}

}  // namespace
