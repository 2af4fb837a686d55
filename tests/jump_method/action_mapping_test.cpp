// Action mapping: raw policy outputs clipped to [-5, 5] and mapped affinely onto
// the paper's ranges, the clipped amount kept for the penalty, the inverse map
// for warm starts, and the jump plane's azimuth from the target.
#include "method/action_mapping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

namespace pronk::jump {
namespace {

constexpr double kPi = 3.14159265358979323846;
using P = ActionParameter;

ActionVector filled(double value) {
  ActionVector v;
  v.fill(value);
  return v;
}

TEST(ActionRanges, DefaultsAreGo1TableOfThePaper) {
  const ActionRanges r;
  const struct {
    P p;
    double min, max;
  } expected[] = {
      {P::kThrustDuration, 0.4, 1.0},    {P::kLiftOffRadius, 0.2, 0.4},      {P::kLiftOffElevation, kPi / 4, kPi / 2},
      {P::kLiftOffSpeed, 0.5, 5.0},      {P::kVelocityElevation, kPi / 6, kPi / 2},
      {P::kSpeedRatio, 1.0, 3.0},        {P::kExplosiveDistance, 0.0, 0.3},  {P::kLiftOffRoll, -kPi / 6, kPi / 6},
      {P::kLiftOffPitch, -kPi / 6, kPi / 6}, {P::kLiftOffYaw, -kPi / 4, kPi / 4},
      {P::kLiftOffRollRate, -1.0, 1.0},  {P::kLiftOffPitchRate, -1.0, 1.0},  {P::kLiftOffYawRate, -4.0, 4.0},
  };
  for (const auto& e : expected) {
    SCOPED_TRACE(actionParameterName(e.p));
    EXPECT_DOUBLE_EQ(r[e.p].min, e.min);
    EXPECT_DOUBLE_EQ(r[e.p].max, e.max);
  }
  EXPECT_DOUBLE_EQ(r.raw_limit, 5.0);
  EXPECT_NO_THROW(r.check());
  EXPECT_DOUBLE_EQ(go1ActionRanges()[P::kLiftOffRadius].max, 0.4);
}

TEST(ActionRanges, AliengoDiffersFromGo1OnlyInLiftOffRadius) {
  const ActionRanges go1 = go1ActionRanges();
  const ActionRanges aliengo = aliengoActionRanges();
  for (int i = 0; i < kActionSize; ++i) {
    const auto p = static_cast<P>(i);
    SCOPED_TRACE(actionParameterName(p));
    if (p == P::kLiftOffRadius) {
      EXPECT_DOUBLE_EQ(aliengo[p].min, 0.2);
      EXPECT_DOUBLE_EQ(aliengo[p].max, 0.6);
    } else {
      EXPECT_EQ(aliengo[p].min, go1[p].min);
      EXPECT_EQ(aliengo[p].max, go1[p].max);
    }
  }
  EXPECT_NO_THROW(aliengo.check());
}

TEST(ActionRanges, CheckRejectsInvalidRangesNamingTheParameter) {
  const auto message = [](const ActionRanges& r) {
    try {
      r.check();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  ActionRanges r;
  r[P::kLiftOffYaw] = {0.5, -0.5};
  EXPECT_NE(message(r).find("liftoff_yaw"), std::string::npos) << message(r);

  r = ActionRanges();
  r[P::kThrustDuration] = {0.0, 1.0};
  EXPECT_NE(message(r).find("thrust_duration"), std::string::npos) << message(r);

  r = ActionRanges();
  r[P::kLiftOffSpeed] = {0.0, 5.0};
  EXPECT_NE(message(r).find("liftoff_speed"), std::string::npos) << message(r);

  r = ActionRanges();
  r[P::kExplosiveDistance] = {-0.1, 0.3};
  EXPECT_NE(message(r).find("explosive_distance"), std::string::npos) << message(r);

  r = ActionRanges();
  r[P::kSpeedRatio] = {1.0, std::numeric_limits<double>::infinity()};
  EXPECT_NE(message(r).find("speed_ratio"), std::string::npos) << message(r);

  r = ActionRanges();
  r.raw_limit = 0.0;
  EXPECT_NE(message(r).find("raw_limit"), std::string::npos) << message(r);
}

TEST(MapAction, RawLimitsMapToRangeEndsAndZeroToTheMiddle) {
  const ActionRanges r;
  const JumpAction low = mapAction(filled(-5.0), r).action;
  const JumpAction high = mapAction(filled(5.0), r).action;
  const JumpAction mid = mapAction(filled(0.0), r).action;
  const ActionVector lo = toVector(low), hi = toVector(high), md = toVector(mid);
  for (int i = 0; i < kActionSize; ++i) {
    SCOPED_TRACE(actionParameterName(static_cast<P>(i)));
    EXPECT_NEAR(lo[i], r.bounds[i].min, 1e-15);
    EXPECT_NEAR(hi[i], r.bounds[i].max, 1e-15);
    EXPECT_NEAR(md[i], 0.5 * (r.bounds[i].min + r.bounds[i].max), 1e-15);
  }
  // Spot-check named fields against the table.
  EXPECT_NEAR(mid.thrust_duration_s, 0.7, 1e-15);
  EXPECT_NEAR(mid.liftoff_speed_mps, 2.75, 1e-15);
  EXPECT_NEAR(mid.speed_ratio, 2.0, 1e-15);
  EXPECT_NEAR(mid.explosive_distance_m, 0.15, 1e-15);
  EXPECT_NEAR(high.liftoff_rpy_rate_radps.z(), 4.0, 1e-15);
  EXPECT_NEAR(low.liftoff_rpy_rad.z(), -kPi / 4, 1e-15);
}

TEST(MapAction, InteriorRawValuesMapAffinely) {
  const ActionRanges r;
  ActionVector raw = filled(0.0);
  raw[actionIndex(P::kThrustDuration)] = 2.5;     // 3/4 of the way: 0.4 + 0.75 * 0.6
  raw[actionIndex(P::kLiftOffSpeed)] = -4.0;      // 1/10: 0.5 + 0.1 * 4.5
  raw[actionIndex(P::kLiftOffPitchRate)] = 1.0;   // 0.6: -1 + 0.6 * 2
  const MappedAction m = mapAction(raw, r);
  EXPECT_NEAR(m.action.thrust_duration_s, 0.85, 1e-15);
  EXPECT_NEAR(m.action.liftoff_speed_mps, 0.95, 1e-15);
  EXPECT_NEAR(m.action.liftoff_rpy_rate_radps.y(), 0.2, 1e-15);
  EXPECT_EQ(m.totalRawExcess(), 0.0);
}

TEST(MapAction, ClipsOutOfRangeRawValuesAndReportsTheExcess) {
  const ActionRanges r;
  ActionVector raw = filled(0.0);
  raw[actionIndex(P::kThrustDuration)] = 7.0;       // 2 above
  raw[actionIndex(P::kLiftOffRadius)] = -6.5;       // 1.5 below
  raw[actionIndex(P::kLiftOffYawRate)] = 5.0;       // exactly at the limit: no excess
  raw[actionIndex(P::kExplosiveDistance)] = 4.999;  // inside
  const MappedAction m = mapAction(raw, r);
  EXPECT_DOUBLE_EQ(m.action.thrust_duration_s, 1.0);
  EXPECT_DOUBLE_EQ(m.action.liftoff_radius_m, 0.2);
  EXPECT_DOUBLE_EQ(m.action.liftoff_rpy_rate_radps.z(), 4.0);
  EXPECT_DOUBLE_EQ(m.raw_excess[actionIndex(P::kThrustDuration)], 2.0);
  EXPECT_DOUBLE_EQ(m.raw_excess[actionIndex(P::kLiftOffRadius)], 1.5);
  EXPECT_EQ(m.raw_excess[actionIndex(P::kLiftOffYawRate)], 0.0);
  EXPECT_EQ(m.raw_excess[actionIndex(P::kExplosiveDistance)], 0.0);
  EXPECT_DOUBLE_EQ(m.totalRawExcess(), 3.5);
}

TEST(MapAction, HonoursACustomRawLimit) {
  ActionRanges r;
  r.raw_limit = 1.0;  // e.g. a tanh-squashed policy
  const MappedAction m = mapAction(filled(1.5), r);
  EXPECT_DOUBLE_EQ(m.action.speed_ratio, 3.0);
  EXPECT_DOUBLE_EQ(m.raw_excess[0], 0.5);
  EXPECT_NEAR(mapAction(filled(0.0), r).action.speed_ratio, 2.0, 1e-15);
}

TEST(MapAction, InfiniteRawClipsAndNanIsRejectedByName) {
  const ActionRanges r;
  ActionVector raw = filled(0.0);
  raw[actionIndex(P::kLiftOffRoll)] = -std::numeric_limits<double>::infinity();
  const MappedAction m = mapAction(raw, r);
  EXPECT_DOUBLE_EQ(m.action.liftoff_rpy_rad.x(), -kPi / 6);
  EXPECT_TRUE(std::isinf(m.raw_excess[actionIndex(P::kLiftOffRoll)]));

  raw[actionIndex(P::kLiftOffYaw)] = std::nan("");
  try {
    mapAction(raw, r);
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("liftoff_yaw"), std::string::npos) << e.what();
  }
}

TEST(UnmapAction, InvertsMapActionInsideTheRawLimits) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-5.0, 5.0);
  for (const ActionRanges& r : {go1ActionRanges(), aliengoActionRanges()}) {
    for (int trial = 0; trial < 100; ++trial) {
      ActionVector raw;
      for (double& a : raw) a = uniform(rng);
      const ActionVector back = unmapAction(mapAction(raw, r).action, r);
      for (int i = 0; i < kActionSize; ++i) {
        EXPECT_NEAR(back[i], raw[i], 1e-12) << actionParameterName(static_cast<P>(i));
      }
    }
  }
}

TEST(UnmapAction, PhysicalRoundTripAndValuesOutsideTheRange) {
  const ActionRanges r;
  JumpAction a;
  a.thrust_duration_s = 0.55;
  a.liftoff_radius_m = 0.31;
  a.liftoff_elevation_rad = 1.2;
  a.liftoff_speed_mps = 2.2;
  a.velocity_elevation_rad = 0.9;
  a.speed_ratio = 1.4;
  a.explosive_distance_m = 0.12;
  a.liftoff_rpy_rad = {0.1, -0.2, 0.3};
  a.liftoff_rpy_rate_radps = {-0.5, 0.25, 3.0};
  const ActionVector raw = unmapAction(a, r);
  const MappedAction m = mapAction(raw, r);
  EXPECT_EQ(m.totalRawExcess(), 0.0);
  const ActionVector in = toVector(a), out = toVector(m.action);
  for (int i = 0; i < kActionSize; ++i) EXPECT_NEAR(out[i], in[i], 1e-12) << actionParameterName(static_cast<P>(i));

  // Out of range: the raw value goes past the limit (not clipped) and maps back to the range end.
  a.thrust_duration_s = 1.3;  // 0.3 s above a 0.6 s wide range: raw 5 + 10 * 0.5
  const ActionVector raw_out = unmapAction(a, r);
  EXPECT_NEAR(raw_out[actionIndex(P::kThrustDuration)], 10.0, 1e-12);
  const MappedAction clipped = mapAction(raw_out, r);
  EXPECT_DOUBLE_EQ(clipped.action.thrust_duration_s, 1.0);
  EXPECT_NEAR(clipped.raw_excess[actionIndex(P::kThrustDuration)], 5.0, 1e-12);
}

TEST(UnmapAction, DegenerateRangeGivesRawZero) {
  ActionRanges r;
  r[P::kSpeedRatio] = {1.0, 1.0};  // k fixed
  JumpAction a = mapAction(filled(3.0), r).action;
  EXPECT_DOUBLE_EQ(a.speed_ratio, 1.0);
  EXPECT_EQ(unmapAction(a, r)[actionIndex(P::kSpeedRatio)], 0.0);
}

TEST(ActionVectorLayout, FieldsFollowTheParameterOrder) {
  ActionVector v;
  for (int i = 0; i < kActionSize; ++i) v[i] = 10.0 + i;
  const JumpAction a = fromVector(v);
  EXPECT_EQ(a.thrust_duration_s, 10.0);
  EXPECT_EQ(a.liftoff_radius_m, 11.0);
  EXPECT_EQ(a.liftoff_elevation_rad, 12.0);
  EXPECT_EQ(a.liftoff_speed_mps, 13.0);
  EXPECT_EQ(a.velocity_elevation_rad, 14.0);
  EXPECT_EQ(a.speed_ratio, 15.0);
  EXPECT_EQ(a.explosive_distance_m, 16.0);
  EXPECT_EQ(a.liftoff_rpy_rad, Eigen::Vector3d(17.0, 18.0, 19.0));
  EXPECT_EQ(a.liftoff_rpy_rate_radps, Eigen::Vector3d(20.0, 21.0, 22.0));
  EXPECT_EQ(toVector(a), v);

  std::set<std::string> names;
  for (int i = 0; i < kActionSize; ++i) names.insert(actionParameterName(static_cast<P>(i)));
  EXPECT_EQ(names.size(), static_cast<size_t>(kActionSize));
  EXPECT_STREQ(actionParameterUnit(P::kLiftOffSpeed), "m/s");
  EXPECT_STREQ(actionParameterUnit(P::kLiftOffYawRate), "rad/s");
}

TEST(JumpPlaneAzimuth, ForwardLateralBackwardAndDiagonal) {
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({0.6, 0.0, 0.0}), 0.0);
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({0.0, 0.3, 0.0}), kPi / 2);   // left
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({0.0, -0.3, 0.2}), -kPi / 2);  // right, dz ignored
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({-0.5, 0.0, 0.0}), kPi);      // backward
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({-0.5, -0.0, 0.0}), kPi);     // not -pi
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({0.3, 0.3, -0.4}), kPi / 4);
  EXPECT_DOUBLE_EQ(jumpPlaneAzimuth({-0.3, -0.3, 0.0}), -3 * kPi / 4);
}

TEST(JumpPlaneAzimuth, TwistInPlaceIsForwardAndNonFiniteIsRejected) {
  EXPECT_EQ(jumpPlaneAzimuth({0.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(jumpPlaneAzimuth({0.0, 0.0, 0.3}), 0.0);
  EXPECT_EQ(jumpPlaneAzimuth({-4e-6, 6e-6, 0.0}), 0.0);           // below kPureTwistDistance
  EXPECT_NEAR(jumpPlaneAzimuth({-2e-5, 0.0, 0.0}), kPi, 1e-15);  // above it: a (tiny) backward jump
  EXPECT_THROW(jumpPlaneAzimuth({std::nan(""), 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(jumpPlaneAzimuth({0.0, std::numeric_limits<double>::infinity(), 0.0}), std::invalid_argument);
}

}  // namespace
// Lengths scale with the robot's legs; the Go1 keeps the paper's numbers exactly.
TEST(ActionMapping, RangesScaleTheirLengthsWithTheLegs) {
  using P = ActionParameter;
  EXPECT_EQ(lengthScaleToGo1(0.426 + 1e-7), 1.0);
  EXPECT_DOUBLE_EQ(lengthScaleToGo1(0.5), 0.5 / 0.426);
  EXPECT_THROW(lengthScaleToGo1(0.0), std::invalid_argument);
  EXPECT_THROW(lengthScaleToGo1(std::nan("")), std::invalid_argument);
  const ActionRanges go1 = scaledActionRanges(1.0), big = scaledActionRanges(1.5);
  for (int i = 0; i < kActionSize; ++i) {
    EXPECT_EQ(go1.bounds[i].min, ActionRanges().bounds[i].min);
    EXPECT_EQ(go1.bounds[i].max, ActionRanges().bounds[i].max);
  }
  EXPECT_DOUBLE_EQ(big[P::kLiftOffRadius].max, 0.6);
  EXPECT_DOUBLE_EQ(big[P::kLiftOffRadius].min, 0.3);
  EXPECT_DOUBLE_EQ(big[P::kExplosiveDistance].max, 0.45);
  EXPECT_EQ(big[P::kThrustDuration].max, go1[P::kThrustDuration].max);  // times and speeds stay
  EXPECT_EQ(big[P::kLiftOffSpeed].max, go1[P::kLiftOffSpeed].max);
}

}  // namespace pronk::jump
