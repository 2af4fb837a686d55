#include "method/ballistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace pronk::jump {
namespace {

constexpr double kG = 9.81;
constexpr double kExact = 1e-12;

FlightState state(double px, double py, double pz, double vx, double vy, double vz) {
  return FlightState{Eigen::Vector3d(px, py, pz), Eigen::Vector3d(vx, vy, vz)};
}

TEST(Ballistics, PositionAndVelocityFollowTheClosedForm) {
  const BallisticFlight flight(state(0.1, -0.2, 0.35, 1.2, 0.4, 1.8));
  for (double t : {0.0, 0.05, 0.2, 0.37, 0.6}) {
    const Eigen::Vector3d p = flight.position(t);
    EXPECT_NEAR(p.x(), 0.1 + 1.2 * t, kExact);
    EXPECT_NEAR(p.y(), -0.2 + 0.4 * t, kExact);
    EXPECT_NEAR(p.z(), 0.35 + 1.8 * t - 0.5 * kG * t * t, kExact);
    const Eigen::Vector3d v = flight.velocity(t);
    EXPECT_NEAR(v.x(), 1.2, kExact);
    EXPECT_NEAR(v.y(), 0.4, kExact);
    EXPECT_NEAR(v.z(), 1.8 - kG * t, kExact);
  }
}

TEST(Ballistics, GeneralGravityVectorIsHonoured) {
  const Eigen::Vector3d g(0.5, -0.3, -9.0);
  const BallisticFlight flight(state(0, 0, 1, 1, 0, 2), g);
  const double t = 0.4;
  EXPECT_LT((flight.position(t) - (Eigen::Vector3d(0, 0, 1) + Eigen::Vector3d(1, 0, 2) * t + 0.5 * g * t * t)).norm(),
            kExact);
  EXPECT_NEAR(flight.apexTime(), 2.0 / 9.0, kExact);
}

TEST(Ballistics, ApexIsWhereVerticalVelocityVanishes) {
  const BallisticFlight flight(state(0, 0, 0.3, 0.8, -0.2, 2.1));
  const double t_apex = flight.apexTime();
  EXPECT_NEAR(t_apex, 2.1 / kG, kExact);
  EXPECT_NEAR(flight.velocity(t_apex).z(), 0.0, kExact);
  EXPECT_NEAR(flight.apexHeight(), 0.3 + 2.1 * 2.1 / (2 * kG), kExact);
  EXPECT_NEAR(flight.position(t_apex).z(), flight.apexHeight(), kExact);
  EXPECT_LT((flight.apexPoint() - flight.position(t_apex)).norm(), kExact);
  // It is the highest point: just before and after are lower.
  EXPECT_LT(flight.position(t_apex - 1e-3).z(), flight.apexHeight());
  EXPECT_LT(flight.position(t_apex + 1e-3).z(), flight.apexHeight());
}

TEST(Ballistics, DownwardLiftOffHasItsApexAtLiftOff) {
  const BallisticFlight flight(state(0, 0, 0.5, 1, 0, -0.4));
  EXPECT_EQ(flight.apexTime(), 0.0);
  EXPECT_EQ(flight.apexHeight(), 0.5);
}

TEST(Ballistics, LandingIsTheLaterRoot) {
  const FlightState lo = state(0.0, 0.0, 0.30, 1.0, 0.5, 2.0);
  const BallisticFlight flight(lo);
  const double h = 0.40;  // between lift-off and apex: two crossings
  ASSERT_LT(h, flight.apexHeight());
  const auto t = flight.landingTime(h);
  ASSERT_TRUE(t.has_value());
  const double disc = std::sqrt(2.0 * 2.0 - 2 * kG * (h - 0.30));
  const double early = (2.0 - disc) / kG;
  const double late = (2.0 + disc) / kG;
  EXPECT_NEAR(*t, late, kExact);
  EXPECT_GT(*t, flight.apexTime());
  EXPECT_GT(*t, early + 0.1);
  EXPECT_NEAR(flight.position(*t).z(), h, kExact);
  EXPECT_LT(flight.velocity(*t).z(), 0.0);
  const auto p = flight.landingPoint(h);
  ASSERT_TRUE(p.has_value());
  EXPECT_LT((*p - flight.position(late)).norm(), kExact);
  const auto s = flight.landingState(h);
  ASSERT_TRUE(s.has_value());
  EXPECT_LT((s->velocity - flight.velocity(late)).norm(), kExact);
}

TEST(Ballistics, SurfaceBelowLiftOffHasOneCrossing) {
  const BallisticFlight flight(state(0, 0, 0.3, 1, 0, 1.5));
  const auto t = flight.landingTime(-0.2);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, (1.5 + std::sqrt(1.5 * 1.5 + 2 * kG * 0.5)) / kG, kExact);
}

TEST(Ballistics, DescendingLiftOffRootIsAccurate) {
  // vz < 0 and a tiny drop: the textbook formula cancels, ours must not.
  const BallisticFlight flight(state(0, 0, 1.0, 0, 0, -3.0));
  const double drop = std::ldexp(1.0, -30);  // exact in binary, about 1e-9 m
  const auto t = flight.landingTime(1.0 - drop);
  ASSERT_TRUE(t.has_value());
  // Series of the root of (g/2) t^2 + 3 t - drop = 0, exact to O(drop^3).
  const double expected = drop / 3.0 * (1.0 - 0.5 * kG * drop / 9.0);
  EXPECT_NEAR(*t, expected, 1e-12 * expected);
  EXPECT_NEAR(*flight.landingTime(1.0), 0.0, 0.0);
}

TEST(Ballistics, SurfaceAboveApexIsNeverReached) {
  const BallisticFlight flight(state(0, 0, 0.3, 1, 0, 1.0));
  EXPECT_FALSE(flight.landingTime(flight.apexHeight() + 1e-6).has_value());
  EXPECT_FALSE(flight.landingPoint(2.0).has_value());
  EXPECT_FALSE(flight.landingState(2.0).has_value());
  // Exactly at the apex: the apex itself.
  const auto t = flight.landingTime(flight.apexHeight());
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(*t, flight.apexTime(), 1e-12);
}

TEST(Ballistics, HeuristicEventTimes) {
  const FlightState lo = state(0.05, 0, 0.36, 1.1, 0, 1.9);
  const double t_lo = 0.73;
  EXPECT_NEAR(heuristicApexTime(t_lo, lo), t_lo + 1.9 / kG, kExact);
  const double touchdown_height = 0.31;
  const auto t_td = heuristicTouchdownTime(t_lo, lo, touchdown_height);
  ASSERT_TRUE(t_td.has_value());
  const double flight_time = (1.9 + std::sqrt(1.9 * 1.9 + 2 * kG * (0.36 - touchdown_height))) / kG;
  EXPECT_NEAR(*t_td, t_lo + flight_time, kExact);
  EXPECT_FALSE(heuristicTouchdownTime(t_lo, lo, 5.0).has_value());
}

TEST(Ballistics, BadGravityOrInputsThrow) {
  EXPECT_THROW(BallisticFlight(state(0, 0, 0, 1, 0, 1), Eigen::Vector3d(0, 0, 9.81)), std::invalid_argument);
  EXPECT_THROW(BallisticFlight(state(0, 0, 0, 1, 0, 1), Eigen::Vector3d(0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(BallisticFlight(state(0, 0, NAN, 1, 0, 1)), std::invalid_argument);
  EXPECT_THROW(liftOffVelocityForFlightTime(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), 0.0),
               std::invalid_argument);
  EXPECT_THROW(liftOffVelocityForHorizontalSpeed(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), -1.0),
               std::invalid_argument);
  EXPECT_THROW(liftOffVelocityForHorizontalSpeed(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 0, 0), 1.0,
                                                 Eigen::Vector3d(0.1, 0, -9.81)),
               std::invalid_argument);
}

// Targets around a lift-off point: forward, backward, lateral, diagonal, up, down.
std::vector<Eigen::Vector3d> targets() {
  return {Eigen::Vector3d(0.6, 0.0, 0.31),  Eigen::Vector3d(-0.5, 0.0, 0.31), Eigen::Vector3d(0.0, 0.4, 0.31),
          Eigen::Vector3d(0.8, -0.5, 0.31), Eigen::Vector3d(0.4, 0.2, 0.71),  Eigen::Vector3d(1.2, 0.3, -0.09),
          Eigen::Vector3d(0.05, 0.0, 0.25)};
}
const Eigen::Vector3d kLiftOff(0.1, 0.02, 0.36);

TEST(Ballistics, FlightTimeInverseHitsTheTarget) {
  for (const Eigen::Vector3d& target : targets()) {
    for (double T : {0.2, 0.36, 0.5, 0.8}) {
      const LiftOffVelocity sol = liftOffVelocityForFlightTime(kLiftOff, target, T);
      EXPECT_EQ(sol.flight_time, T);
      const BallisticFlight flight(FlightState{kLiftOff, sol.velocity});
      EXPECT_LT((flight.position(T) - target).norm(), kExact) << target.transpose() << " T " << T;
      EXPECT_EQ(sol.arrives_descending, flight.velocity(T).z() <= 0.0);
    }
  }
  // Vertical jump, and a general gravity vector.
  const Eigen::Vector3d above = kLiftOff + Eigen::Vector3d(0, 0, 0.1);
  const LiftOffVelocity up = liftOffVelocityForFlightTime(kLiftOff, above, 0.5);
  EXPECT_NEAR(up.velocity.head<2>().norm(), 0.0, kExact);
  EXPECT_TRUE(up.arrives_descending);
  const Eigen::Vector3d g(0.2, 0.1, -9.7);
  const LiftOffVelocity tilted = liftOffVelocityForFlightTime(kLiftOff, targets()[3], 0.45, g);
  EXPECT_LT((BallisticFlight(FlightState{kLiftOff, tilted.velocity}, g).position(0.45) - targets()[3]).norm(), kExact);
}

TEST(Ballistics, ShortFlightToAHighTargetArrivesRising) {
  const LiftOffVelocity sol = liftOffVelocityForFlightTime(kLiftOff, kLiftOff + Eigen::Vector3d(0.3, 0, 0.3), 0.1);
  EXPECT_FALSE(sol.arrives_descending);
}

TEST(Ballistics, HorizontalSpeedInverseHitsTheTarget) {
  for (const Eigen::Vector3d& target : targets()) {
    for (double s : {0.3, 0.9, 1.6, 2.5}) {
      const auto sol = liftOffVelocityForHorizontalSpeed(kLiftOff, target, s);
      ASSERT_TRUE(sol.has_value());
      EXPECT_NEAR(sol->velocity.head<2>().norm(), s, kExact);
      const double h = (target - kLiftOff).head<2>().norm();
      EXPECT_NEAR(sol->flight_time, h / s, kExact);
      const BallisticFlight flight(FlightState{kLiftOff, sol->velocity});
      EXPECT_LT((flight.position(sol->flight_time) - target).norm(), kExact);
      // The velocity points at the target horizontally.
      EXPECT_LT((sol->velocity.head<2>() / s - (target - kLiftOff).head<2>() / h).norm(), kExact);
    }
  }
  EXPECT_FALSE(liftOffVelocityForHorizontalSpeed(kLiftOff, kLiftOff + Eigen::Vector3d(0, 0, 0.2), 1.0).has_value());
}

TEST(Ballistics, HyperbolaMembersAllLandOnTheTarget) {
  for (const Eigen::Vector3d& target : targets()) {
    const LiftOffHyperbola family(kLiftOff, target);
    const double h = family.horizontalDistance();
    const double dz = family.heightChange();
    std::vector<LiftOffVelocity> members;
    for (double s = 0.2; s < 4.0; s += 0.35) members.push_back(family.atHorizontalSpeed(s));
    for (double T : {0.15, 0.3, 0.45, 0.7}) members.push_back(family.atFlightTime(T));
    const double lo = family.minimumElevation();
    for (double f : {0.05, 0.3, 0.6, 0.95}) {
      const auto m = family.atElevation(lo + f * (M_PI / 2 - lo));
      ASSERT_TRUE(m.has_value());
      members.push_back(*m);
    }
    members.push_back(family.leastSpeed());
    for (const LiftOffVelocity& m : members) {
      const BallisticFlight flight(FlightState{kLiftOff, m.velocity});
      EXPECT_LT((flight.position(m.flight_time) - target).norm(), kExact)
          << "target " << target.transpose() << " v " << m.velocity.transpose();
      // On the hyperbola v_z = dz s / h + g h / (2 s).
      const double s = m.velocity.head<2>().norm();
      EXPECT_NEAR(m.velocity.z(), dz * s / h + kG * h / (2 * s), 1e-9);
      EXPECT_NEAR(m.velocity.z(), family.verticalSpeed(s), 1e-9);
    }
  }
}

TEST(Ballistics, HyperbolaInTheSagittalPlaneMatchesThePaper) {
  // Forward jump in x-z: the paper's relation with the sign of the height term
  // corrected, v_z = (z_tg - z_lo) / (x_tg - x_lo) v_x + (x_tg - x_lo) g / (2 v_x).
  const Eigen::Vector3d lo(0.0, 0.0, 0.35);
  const Eigen::Vector3d tg(0.7, 0.0, 0.55);
  const LiftOffHyperbola family(lo, tg);
  for (double vx : {0.5, 1.0, 1.5}) {
    const LiftOffVelocity m = family.atHorizontalSpeed(vx);
    EXPECT_NEAR(m.velocity.x(), vx, kExact);
    EXPECT_NEAR(m.velocity.y(), 0.0, kExact);
    EXPECT_NEAR(m.velocity.z(), (0.2 / 0.7) * vx + 0.7 * kG / (2 * vx), 1e-12);
  }
}

TEST(Ballistics, LeastSpeedMemberIsTheMinimum) {
  for (const Eigen::Vector3d& target : targets()) {
    const LiftOffHyperbola family(kLiftOff, target);
    const LiftOffVelocity best = family.leastSpeed();
    const double h = family.horizontalDistance();
    const double dz = family.heightChange();
    EXPECT_NEAR(best.velocity.squaredNorm(), kG * (dz + std::hypot(h, dz)), 1e-9);
    const double s = best.velocity.head<2>().norm();
    for (double f : {0.9, 0.99, 1.01, 1.1}) {
      EXPECT_GT(family.atHorizontalSpeed(s * f).velocity.norm(), best.velocity.norm());
    }
    EXPECT_NEAR(std::atan2(best.velocity.z(), s), M_PI / 4 + std::atan2(dz, h) / 2, 1e-9);
  }
}

TEST(Ballistics, HyperbolaElevationOutsideItsRangeHasNoMember) {
  const LiftOffHyperbola family(kLiftOff, Eigen::Vector3d(0.6, 0.0, 0.56));  // 0.2 m up
  EXPECT_FALSE(family.atElevation(family.minimumElevation()).has_value());
  EXPECT_FALSE(family.atElevation(family.minimumElevation() - 0.1).has_value());
  EXPECT_FALSE(family.atElevation(M_PI / 2).has_value());
  EXPECT_TRUE(family.atElevation(family.minimumElevation() + 0.01).has_value());
}

TEST(Ballistics, VerticalTargetHasNoHyperbola) {
  EXPECT_THROW(LiftOffHyperbola(kLiftOff, kLiftOff + Eigen::Vector3d(0, 0, 0.3)), std::invalid_argument);
  EXPECT_THROW(LiftOffHyperbola(kLiftOff, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0.3, 0, -9.81)),
               std::invalid_argument);
  const LiftOffHyperbola family(kLiftOff, Eigen::Vector3d(1, 0, 0.36));
  EXPECT_THROW(family.atHorizontalSpeed(0.0), std::invalid_argument);
  EXPECT_THROW(family.atFlightTime(-0.1), std::invalid_argument);
}

TEST(LandingStop, FrictionTakesMuTimesTheVerticalSpeedAndTheRestStopsOverOneOverOmega) {
  // 1.2 m/s ahead, 1 m/s down: friction 0.6 takes 0.6 m/s, 0.6 m/s left stops
  // 0.6 / 5 = 0.12 m further, along the horizontal velocity.
  const Eigen::Vector2d stop = landingStopOffset({1.2 * 0.6, 1.2 * 0.8, -1.0}, 0.6, 5.0);
  EXPECT_NEAR(stop.norm(), 0.12, 1e-12);
  EXPECT_NEAR(stop.x() / stop.y(), 0.6 / 0.8, 1e-12);
  // The sign of v_z does not matter; friction that takes it all leaves nothing.
  EXPECT_NEAR((landingStopOffset({1.2, 0.0, 1.0}, 0.6, 5.0) - Eigen::Vector2d(0.12, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(landingStopOffset({0.5, 0.0, -1.0}, 0.6, 5.0), Eigen::Vector2d::Zero());
  EXPECT_EQ(landingStopOffset({0.0, 0.0, -1.0}, 0.6, 5.0), Eigen::Vector2d::Zero());
  // Without friction the whole speed is stopped by the damped return: v / omega.
  EXPECT_NEAR((landingStopOffset({-1.0, 0.0, -1.0}, 0.0, 5.0) - Eigen::Vector2d(-0.2, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_THROW(landingStopOffset({1.0, 0.0, -1.0}, -0.1, 5.0), std::invalid_argument);
  EXPECT_THROW(landingStopOffset({1.0, 0.0, -1.0}, 0.6, 0.0), std::invalid_argument);
}

TEST(LandingExtension, TheStrokeKneesThatSaturateNeedBeyondTheStancePose) {
  // Four knees of 40 N m at a 0.1 m lever hold 1600 N; 20 kg decelerate at
  // 80 - 9.81 = 70.19 m/s^2. A fall of 1.44 legs of 0.5 m takes 1.44 g / a =
  // 0.2013 legs of stroke, under the stance pose's 0.22: no extension.
  EXPECT_EQ(landingExtension(0.5, 0.1, 40.0, 20.0, 9.81, 4), 0.0);
  // Twice the mass: a = 30.19 m/s^2, 0.4679 legs of stroke, 0.2479 more than the
  // stance gives, 0.124 m of 0.5 m legs.
  const double heavy = landingExtension(0.5, 0.1, 40.0, 40.0, 9.81, 4);
  EXPECT_NEAR(heavy, 0.5 * (1.44 * 9.81 / (1600.0 / 40.0 - 9.81) - 0.22), 1e-12);
  EXPECT_NEAR(heavy, 0.124, 1e-3);
  // It scales with the legs: the same knees per weight and lever per leg.
  EXPECT_NEAR(landingExtension(1.0, 0.2, 80.0, 40.0, 9.81, 4), 2.0 * heavy, 1e-12);
  // Knees that cannot hold the weight get the most the landing pose allows.
  EXPECT_EQ(landingExtension(0.5, 0.1, 1.0, 40.0, 9.81, 4), 0.5 * kMaxLandingExtension);
  EXPECT_THROW(landingExtension(0.5, 0.0, 40.0, 20.0, 9.81, 4), std::invalid_argument);
  EXPECT_THROW(landingExtension(0.5, 0.1, 40.0, -1.0, 9.81, 4), std::invalid_argument);
}

}  // namespace
}  // namespace pronk::jump
