#include "control/jump_plan.h"

#include <algorithm>
#include <cmath>

#include "control/robot_state.h"
#include "method/ballistics.h"

namespace pronk::guided_jump {

JumpPlan makeJumpPlan(const LegDrive& drive, const pronk_robot_state& s, const jump::JumpAction& action,
                      double azimuth, double landing_height) {
  JumpPlan p;
  const Eigen::Matrix3d R = rotationOf(s);
  const StartFrame S = takeOffFrame(drive.host(), s);
  p.heading = S.heading;
  p.origin = S.origin;
  p.start_time = s.time;
  p.landing_height = landing_height;
  const double ground = p.origin.z();
  p.standing_height = s.com_position[2] - ground;
  const Eigen::Vector3d com_start_S(0, 0, s.com_position[2] - ground);
  p.thrust = std::make_unique<jump::ThrustPlan>(action, azimuth, com_start_S, Eigen::Vector3d::Zero());
  const Eigen::Vector3d rpy0 = rpyFromRotation(p.heading.transpose() * R);
  p.orientation = std::make_unique<jump::OrientationTrajectory>(rpy0, action, p.thrust->duration());
  const jump::PointState& lo = p.thrust->liftOff();
  const jump::BallisticFlight flight({lo.position, lo.velocity}, p.heading.transpose() * drive.gravity());
  p.flight_time = std::max(0.05, flight.landingTime(p.standing_height + landing_height).value_or(0.0));
  p.touchdown_yaw = std::atan2(p.heading(1, 0), p.heading(0, 0)) + p.orientation->liftOffRpy().z() +
                    p.orientation->liftOffRpyRate().z() * p.flight_time;
  const int feet = drive.footCount();
  p.start_feet.resize(3, feet);
  for (int f = 0; f < feet; ++f) p.start_feet.col(f) = vec(s.foot_position + 3 * f);
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (int f = 0; f < feet; ++f) centroid += p.start_feet.col(f) / feet;
  p.stance_offset = R.transpose() * (vec(s.base_position) - centroid);
  Eigen::VectorXd stance(drive.jointCount());
  for (int j = 0; j < drive.jointCount(); ++j) stance(j) = drive.hold().stance[j % 3];
  p.stance_feet = drive.feetAt(stance);
  return p;
}

}  // namespace pronk::guided_jump
