// The DC motor's torque-speed line against its closed form (method/motor_model.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "method/motor_model.h"

namespace pronk::jump {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(MotorModel, DcMotorRangeFollowsTheTorqueSpeedLine) {
  const MotorLimits calf{35.55, 20.06};  // the Go1's knee
  // At rest: the full effort both ways.
  TorqueRange r = availableTorque(MotorModel::kDcMotor, calf, 0.0);
  EXPECT_DOUBLE_EQ(r.upper, 35.55);
  EXPECT_DOUBLE_EQ(r.lower, -35.55);
  // At half the no-load speed: half the effort along the motion, all of it against.
  r = availableTorque(MotorModel::kDcMotor, calf, 10.03);
  EXPECT_NEAR(r.upper, 35.55 / 2, 1e-12);
  EXPECT_DOUBLE_EQ(r.lower, -35.55);
  r = availableTorque(MotorModel::kDcMotor, calf, -10.03);
  EXPECT_DOUBLE_EQ(r.upper, 35.55);
  EXPECT_NEAR(r.lower, -35.55 / 2, 1e-12);
  // At and beyond the no-load speed: nothing along the motion.
  for (double w : {20.06, 30.0}) {
    r = availableTorque(MotorModel::kDcMotor, calf, w);
    EXPECT_NEAR(r.upper, 0.0, 1e-12) << w;
    EXPECT_DOUBLE_EQ(r.lower, -35.55) << w;
  }
  // Linear in between.
  for (double w = 0.0; w <= 20.06; w += 2.5) {
    EXPECT_NEAR(availableTorque(MotorModel::kDcMotor, calf, w).upper, 35.55 * (1.0 - w / 20.06), 1e-12) << w;
  }
}

TEST(MotorModel, EffortBoxAndMissingLimitsIgnoreTheSpeed) {
  const MotorLimits calf{35.55, 20.06};
  for (double w : {-40.0, 0.0, 15.0, 40.0}) {
    const TorqueRange r = availableTorque(MotorModel::kEffortBox, calf, w);
    EXPECT_DOUBLE_EQ(r.upper, 35.55);
    EXPECT_DOUBLE_EQ(r.lower, -35.55);
    // No velocity limit: the DC motor is the effort box.
    const TorqueRange no_speed = availableTorque(MotorModel::kDcMotor, {35.55, kInf}, w);
    EXPECT_DOUBLE_EQ(no_speed.upper, 35.55);
    // No effort limit: unlimited, never NaN.
    const TorqueRange free = availableTorque(MotorModel::kDcMotor, {kInf, 20.0}, w);
    EXPECT_EQ(free.upper, kInf);
    EXPECT_EQ(free.lower, -kInf);
  }
}

TEST(MotorModel, SaturationClampsIntoTheRange) {
  const MotorLimits thigh{23.7, 30.1};
  EXPECT_NEAR(saturateTorque(MotorModel::kDcMotor, thigh, 50.0, 15.05), 23.7 / 2, 1e-12);
  EXPECT_DOUBLE_EQ(saturateTorque(MotorModel::kDcMotor, thigh, -50.0, 15.05), -23.7);
  EXPECT_DOUBLE_EQ(saturateTorque(MotorModel::kDcMotor, thigh, 3.0, 15.05), 3.0);
  EXPECT_DOUBLE_EQ(saturateTorque(MotorModel::kEffortBox, thigh, 50.0, 15.05), 23.7);
}

}  // namespace
}  // namespace pronk::jump
