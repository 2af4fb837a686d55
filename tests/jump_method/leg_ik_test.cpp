#include "method/leg_ik.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>

namespace pronk::jump {
namespace {

constexpr Leg kLegs[] = {Leg::kFrontRight, Leg::kFrontLeft, Leg::kRearRight, Leg::kRearLeft};

// The leg-plane z' of the foot (below the hip axis when negative).
double legPlaneZ(const LegGeometry& g, const Eigen::Vector3d& q) {
  return -g.thigh_length * std::cos(q[1]) - g.calf_length * std::cos(q[1] + q[2]);
}

TEST(LegIk, Go1StanceFootPosition) {
  const Eigen::Vector3d stance(0.0, 0.75, -1.5);
  for (Leg leg : kLegs) {
    const LegGeometry g = go1Leg(leg);
    const Eigen::Vector3d foot = footPosition(g, stance);
    const double sx = isFrontLeg(leg) ? 1.0 : -1.0;
    const double sy = isLeftLeg(leg) ? 1.0 : -1.0;
    EXPECT_NEAR(foot.x(), sx * 0.1881, 1e-12) << legName(leg);
    EXPECT_NEAR(foot.y(), sy * 0.12675, 1e-12) << legName(leg);
    EXPECT_NEAR(foot.z(), -2 * 0.213 * std::cos(0.75), 1e-12) << legName(leg);
  }
}

TEST(LegIk, TheKneeLiesOneThighLengthFromTheThighJointAndOneCalfLengthFromTheFoot) {
  // Go1 stance: the thigh at 0.75 rad swings the knee back, l1 sin 0.75 behind
  // and l1 cos 0.75 below the thigh joint; the calf at -1.5 rad brings the foot
  // back under the hip, l2 cos(0.75 - 1.5) below the knee.
  const Eigen::Vector3d stance(0.0, 0.75, -1.5);
  for (Leg leg : kLegs) {
    const LegGeometry g = go1Leg(leg);
    const Eigen::Vector3d knee = kneePosition(g, stance);
    const Eigen::Vector3d thigh_joint = g.hipPosition() + Eigen::Vector3d(0, g.side * g.thigh_offset, 0);
    EXPECT_LT((knee - thigh_joint - Eigen::Vector3d(-0.213 * std::sin(0.75), 0, -0.213 * std::cos(0.75))).norm(), 1e-12)
        << legName(leg);
    EXPECT_NEAR(knee.z() - footPosition(g, stance).z(), 0.213 * std::cos(-0.75), 1e-12) << legName(leg);
  }
  // Abducted, turned and bent anywhere: the calf keeps its length.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> angle(-2.5, 2.5);
  const LegGeometry g = aliengoLeg(Leg::kRearLeft);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d q(angle(rng), angle(rng), angle(rng));
    EXPECT_NEAR((footPosition(g, q) - kneePosition(g, q)).norm(), g.calf_length, 1e-12) << q.transpose();
  }
}

TEST(LegIk, ZeroConfigurationHangsStraightDown) {
  for (Leg leg : kLegs) {
    const LegGeometry g = aliengoLeg(leg);
    const Eigen::Vector3d foot = footPosition(g, Eigen::Vector3d::Zero());
    const Eigen::Vector3d expected = g.hipPosition() + Eigen::Vector3d(0, g.side * 0.0868, -0.5);
    EXPECT_LT((foot - expected).norm(), 1e-12) << legName(leg);
  }
}

TEST(LegIk, UnitreeSignConvention) {
  const LegGeometry fl = go1Leg(Leg::kFrontLeft);
  const LegGeometry fr = go1Leg(Leg::kFrontRight);
  const Eigen::Vector3d stance(0.0, 0.75, -1.5);
  // Thigh positive swings the foot back.
  EXPECT_LT(footPosition(fl, stance + Eigen::Vector3d(0, 0.1, 0)).x(), footPosition(fl, stance).x());
  // Hip positive moves a left foot outward (+y) and a right foot inward (+y too).
  EXPECT_GT(footPosition(fl, stance + Eigen::Vector3d(0.1, 0, 0)).y(), footPosition(fl, stance).y());
  EXPECT_GT(footPosition(fr, stance + Eigen::Vector3d(0.1, 0, 0)).y(), footPosition(fr, stance).y());
  // The IK of a standing foot returns a negative knee.
  const LegIkResult ik = solveLegIk(fl, footPosition(fl, stance));
  ASSERT_TRUE(ik.ok());
  EXPECT_LT(ik.q[2], 0.0);
}

void roundTripOverJointRanges(const LegGeometry& g, int* round_trips) {
  const int n0 = 9;
  const int n1 = 25;
  const int n2 = 13;
  const double margin = 1e-3;  // stay off the range ends (the Aliengo thigh range spans 2 pi)
  for (int i0 = 0; i0 < n0; ++i0) {
    for (int i1 = 0; i1 < n1; ++i1) {
      for (int i2 = 0; i2 < n2; ++i2) {
        Eigen::Vector3d q;
        const int idx[3] = {i0, i1, i2};
        const int n[3] = {n0, n1, n2};
        for (int j = 0; j < 3; ++j) {
          const double lo = g.limits[j].min + margin;
          const double hi = g.limits[j].max - margin;
          q[j] = lo + (hi - lo) * idx[j] / (n[j] - 1);
        }
        const Eigen::Vector3d foot = footPosition(g, q);
        const LegIkResult ik = solveLegIk(g, foot);
        ASSERT_TRUE(ik.ok()) << ik.message;
        // Any solution reproduces the foot.
        EXPECT_LT((footPosition(g, ik.q) - foot).norm(), 1e-9) << q.transpose();
        // With the foot clearly below the hip axis in the leg plane (the
        // abduction solution is then unique within the limits) the angles come back.
        if (legPlaneZ(g, q) < -0.02) {
          EXPECT_TRUE(ik.within_limits) << q.transpose();
          EXPECT_LT((ik.q - q).cwiseAbs().maxCoeff(), 1e-9) << "q " << q.transpose() << " ik " << ik.q.transpose();
          ++*round_trips;
        }
      }
    }
  }
}

TEST(LegIk, InverseOfForwardRoundTripsOverTheJointRanges) {
  int round_trips = 0;
  for (Leg leg : kLegs) {
    roundTripOverJointRanges(go1Leg(leg), &round_trips);
    roundTripOverJointRanges(aliengoLeg(leg), &round_trips);
  }
  EXPECT_GT(round_trips, 8 * 9 * 25 * 13 / 3);  // most of the grid has the foot below the hip
}

TEST(LegIk, FootAboveTheHipAxisWithinLimitsIsFound) {
  // Thigh 3 rad swings the leg up behind the trunk; the foot-above abduction solution is the one within limits.
  const LegGeometry g = go1Leg(Leg::kRearLeft);
  const Eigen::Vector3d q(0.3, 3.0, -1.0);
  ASSERT_GT(legPlaneZ(g, q), 0.0);
  const LegIkResult ik = solveLegIk(g, footPosition(g, q));
  ASSERT_TRUE(ik.ok());
  EXPECT_TRUE(ik.within_limits);
  EXPECT_LT((ik.q - q).cwiseAbs().maxCoeff(), 1e-9) << ik.q.transpose();
}

TEST(LegIk, OutOfLimitsSolutionIsFlagged) {
  // Foot far in front of the hip: the thigh needs -0.9 rad, below Go1's -0.686.
  const LegGeometry g = go1Leg(Leg::kFrontLeft);
  const Eigen::Vector3d q(0.0, -0.9, -1.0);
  ASSERT_LT(legPlaneZ(g, q), 0.0);
  const LegIkResult ik = solveLegIk(g, footPosition(g, q));
  ASSERT_TRUE(ik.ok());
  EXPECT_FALSE(ik.within_limits);
  EXPECT_LT((ik.q - q).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(LegIk, UnreachablePointsFail) {
  const LegGeometry g = go1Leg(Leg::kFrontRight);
  const Eigen::Vector3d hip = g.hipPosition();

  const LegIkResult far = solveLegIk(g, hip + Eigen::Vector3d(0.0, -0.08, -0.43));
  EXPECT_EQ(far.status, LegIkStatus::kTooFar);
  EXPECT_FALSE(far.ok());
  EXPECT_STREQ(legIkStatusName(far.status), "too_far");
  EXPECT_NE(far.message.find("0.426"), std::string::npos) << far.message;

  const LegIkResult inside = solveLegIk(g, hip + Eigen::Vector3d(0.1, 0.0, -0.03));
  EXPECT_EQ(inside.status, LegIkStatus::kInsideHipOffset);
  EXPECT_FALSE(inside.message.empty());

  const LegIkResult nan = solveLegIk(g, Eigen::Vector3d(NAN, 0, 0));
  EXPECT_EQ(nan.status, LegIkStatus::kNotFinite);

  LegGeometry uneven = g;
  uneven.thigh_length = 0.3;
  uneven.calf_length = 0.2;
  const LegIkResult close = solveLegIk(uneven, hip + Eigen::Vector3d(0.0, -0.08, -0.05));
  EXPECT_EQ(close.status, LegIkStatus::kTooClose);

  // Just inside full extension is still reachable.
  const LegIkResult edge = solveLegIk(g, hip + Eigen::Vector3d(0.0, -0.08, -0.4259));
  EXPECT_TRUE(edge.ok()) << edge.message;
}

TEST(LegIk, JacobianMatchesFiniteDifferences) {
  const double step = 1e-6;
  const Eigen::Vector3d configs[] = {
      {0.0, 0.75, -1.5}, {0.3, 1.2, -2.2}, {-0.5, -0.4, -1.0}, {0.7, 2.5, -0.95}, {-0.2, 3.8, -2.6}};
  for (Leg leg : kLegs) {
    for (const LegGeometry& g : {go1Leg(leg), aliengoLeg(leg)}) {
      for (const Eigen::Vector3d& q : configs) {
        const Eigen::Matrix3d j = footJacobian(g, q);
        for (int c = 0; c < 3; ++c) {
          Eigen::Vector3d dq = Eigen::Vector3d::Zero();
          dq[c] = step;
          const Eigen::Vector3d fd = (footPosition(g, q + dq) - footPosition(g, q - dq)) / (2 * step);
          EXPECT_LT((j.col(c) - fd).norm(), 1e-8) << legName(leg) << " q " << q.transpose() << " col " << c;
        }
      }
    }
  }
}

TEST(LegIk, JointVelocitiesReproduceTheFootVelocity) {
  const LegGeometry g = go1Leg(Leg::kRearRight);
  const Eigen::Vector3d q(0.1, 0.9, -1.7);
  const Eigen::Vector3d v(0.3, -0.2, 1.1);
  const JointVelocityResult r = jointVelocitiesForFootVelocity(g, q, v);
  EXPECT_FALSE(r.singular);
  EXPECT_TRUE(r.message.empty());
  EXPECT_GT(r.least_singular_value, kLegSingularityThreshold);
  EXPECT_LT((footJacobian(g, q) * r.qd - v).norm(), 1e-12);
}

TEST(LegIk, SingularJacobianIsReported) {
  // Straight knee: the foot cannot move along the leg.
  const LegGeometry g = go1Leg(Leg::kFrontLeft);
  const Eigen::Vector3d q(0.0, 0.2, 0.0);
  const Eigen::Vector3d v(0.4, 0.0, 0.0);
  const JointVelocityResult r = jointVelocitiesForFootVelocity(g, q, v);
  EXPECT_TRUE(r.singular);
  EXPECT_LT(r.least_singular_value, 1e-12);
  EXPECT_NE(r.message.find("singular"), std::string::npos);
  EXPECT_TRUE(r.qd.allFinite());
  // The solution delivers the part of v the leg can produce (least squares).
  const Eigen::Matrix3d j = footJacobian(g, q);
  const Eigen::Vector3d achieved = j * r.qd;
  EXPECT_LT((j.transpose() * (achieved - v)).norm(), 1e-9);
}

TEST(LegIk, FootVelocityInTheTrunkFrame) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d trunk(0.1, 0.2, 0.3);
  const Eigen::Vector3d foot(0.3, 0.3, 0.0);
  const Eigen::Vector3d v_trunk(0.5, 0.0, 1.0);
  const Eigen::Vector3d w(0.0, 0.0, 2.0);
  const Eigen::Vector3d v = footVelocityInTrunk(rot, trunk, v_trunk, w, foot, Eigen::Vector3d::Zero());
  // Finite difference of the trunk-frame foot position of a stance foot.
  const double dt = 1e-7;
  const Eigen::Matrix3d rot2 = Eigen::AngleAxisd(0.4 + 2.0 * dt, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d fd =
      (rot2.transpose() * (foot - (trunk + v_trunk * dt)) - rot.transpose() * (foot - trunk)) / dt;
  EXPECT_LT((v - fd).norm(), 1e-6);
}

TEST(LegIk, FeetReachableForAStandingTrunkOnly) {
  const auto legs = go1Legs();
  const Eigen::Vector3d stance(0.0, 0.75, -1.5);
  std::array<Eigen::Vector3d, kLegCount> feet;
  const Eigen::Vector3d trunk(0.0, 0.0, 0.3117);
  for (int i = 0; i < kLegCount; ++i) feet[i] = trunk + footPosition(legs[i], stance);
  const Eigen::Matrix3d level = Eigen::Matrix3d::Identity();
  EXPECT_TRUE(feetReachable(legs, feet, trunk, level));
  // Trunk 0.2 m higher: the legs cannot reach the ground.
  EXPECT_FALSE(feetReachable(legs, feet, trunk + Eigen::Vector3d(0, 0, 0.2), level));
  // Pitched 0.2 rad nose-down about the trunk centre: reachable, and within the limits.
  const Eigen::Matrix3d pitched = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()).toRotationMatrix();
  EXPECT_TRUE(feetReachable(legs, feet, trunk, pitched));
  // Trunk 0.35 m back and 0.12 m lower: the feet are far ahead of the hips and
  // the knees nearly straight (calf above its -0.888 rad limit); reachable only
  // when the limits are ignored.
  const Eigen::Vector3d behind = trunk + Eigen::Vector3d(-0.35, 0, -0.12);
  EXPECT_FALSE(feetReachable(legs, feet, behind, level));
  EXPECT_TRUE(feetReachable(legs, feet, behind, level, false));
}

// LegReachCheck must give solveLegIk's verdict everywhere: in and out of reach,
// and at joint angles a hair on either side of each limit.
TEST(LegIk, ReachCheckGivesTheIkVerdict) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(-0.6, 0.6), unit(0.0, 1.0);
  LegGeometry unlimited = go1Leg(Leg::kFrontLeft);
  unlimited.limits = {};
  LegGeometry turn = go1Leg(Leg::kRearRight);  // a thigh range of more than a turn
  turn.limits[1] = JointRange{-4.0, 4.0};
  LegGeometry straight = go1Leg(Leg::kFrontLeft);  // a knee limit near the straight leg
  straight.limits[2] = JointRange{-3.1, -1e-6};
  std::vector<LegGeometry> legs{unlimited, turn, straight};
  for (const auto& all : {go1Legs(), aliengoLegs()}) legs.insert(legs.end(), all.begin(), all.end());
  int compared = 0;
  for (const LegGeometry& leg : legs) {
    const LegReachCheck check(leg);
    auto expectSame = [&](const Eigen::Vector3d& foot) {
      const LegIkResult ik = solveLegIk(leg, foot);
      EXPECT_EQ(check.reaches(foot, true), ik.ok() && ik.within_limits) << foot.transpose();
      EXPECT_EQ(check.reaches(foot, false), ik.ok()) << foot.transpose();
      ++compared;
    };
    for (int i = 0; i < 4000; ++i) expectSame(Eigen::Vector3d(coord(rng), coord(rng), coord(rng)));
    for (int i = 0; i < 2000; ++i) {
      Eigen::Vector3d q;
      for (int j = 0; j < 3; ++j) {
        const JointRange& r = leg.limits[j];
        q[j] = std::isfinite(r.min) ? r.min + (r.max - r.min) * unit(rng) : 6.0 * unit(rng) - 3.0;
      }
      const int j = i % 3;
      const JointRange& r = leg.limits[j];
      if (std::isfinite(r.min)) {  // onto a limit, then a hair either side of it
        const double hair[] = {0.0, 1e-15, -1e-15, 1e-11, -1e-11, 1e-8, -1e-8, 1e-6, -1e-6};
        q[j] = (i % 2 ? r.min : r.max) + hair[(i / 6) % 9];
      }
      expectSame(footPosition(leg, q));
    }
  }
  EXPECT_EQ(compared, 11 * 6000);
}

TEST(LegIk, GeometryIsChecked) {
  EXPECT_NO_THROW(go1Leg(Leg::kRearLeft).check());
  EXPECT_NO_THROW(aliengoLeg(Leg::kFrontRight).check());
  LegGeometry bad = go1Leg(Leg::kFrontLeft);
  bad.thigh_length = -0.1;
  EXPECT_THROW(bad.check(), std::invalid_argument);
  bad = go1Leg(Leg::kFrontLeft);
  bad.side = 0.5;
  EXPECT_THROW(bad.check(), std::invalid_argument);
  bad = go1Leg(Leg::kFrontLeft);
  bad.limits[2] = JointRange{1.0, -1.0};
  EXPECT_THROW(bad.check(), std::invalid_argument);
  EXPECT_STREQ(legName(Leg::kRearLeft), "RL");
}

}  // namespace
}  // namespace pronk::jump
