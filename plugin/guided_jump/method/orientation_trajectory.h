// Thrust trajectory, orientation: the trunk's ZYX Euler angles
// rpy = (roll phi, pitch theta, yaw psi) follow a cubic Bezier from rest at the
// start orientation to the lift-off orientation, whose Euler rates are the
// action's lift-off rates, over the whole thrust [0, T_th + T_e] (paper,
// "Orientation-Bezier"; docs/method-trajectories.md). Angles are in the start
// frame (thrust_trajectory.h), z up.
//
//   R(rpy) = Rz(psi) Ry(theta) Rx(phi)          (body -> start frame)
//   omega_world = E(rpy) rpy_rate, with the columns of E
//     d/d phi:   Rz(psi) Ry(theta) x = (c_psi c_theta, s_psi c_theta, -s_theta)
//     d/d theta: Rz(psi) y           = (-s_psi, c_psi, 0)
//     d/d psi:   z                   = (0, 0, 1)
//   omega_body = R^T omega_world
// E is singular at theta = +-pi/2 (gimbal lock); the action ranges keep |theta|
// at pi/6.
#pragma once

#include <Eigen/Core>

#include "method/action_mapping.h"
#include "method/thrust_trajectory.h"

namespace pronk::jump {

// Rz(yaw) Ry(pitch) Rx(roll) for rpy = (roll, pitch, yaw).
Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy);

// E(rpy): maps ZYX Euler rates (roll, pitch, yaw order) to the angular velocity
// in the start (world) frame.
Eigen::Matrix3d eulerRateToWorldAngularVelocity(const Eigen::Vector3d& rpy);

Eigen::Vector3d worldAngularVelocity(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate);
Eigen::Vector3d bodyAngularVelocity(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate);
// d/dt (E(rpy) rpy_rate) = E rpy_acc + dE/dt rpy_rate.
Eigen::Vector3d worldAngularAcceleration(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate,
                                         const Eigen::Vector3d& rpy_acceleration);

class OrientationTrajectory {
 public:
  // The Bezier Q0 = Q1 = start_rpy, Q2 = lift-off rpy - T/3 liftoff_rpy_rate,
  // Q3 = lift-off rpy over `duration` (T_th + T_e). The lift-off yaw is moved by
  // a multiple of 2 pi to the one nearest the start yaw (the same orientation),
  // so the trunk never turns the long way round. Throws std::invalid_argument
  // on a non-finite input or duration <= 0.
  OrientationTrajectory(const Eigen::Vector3d& start_rpy, const Eigen::Vector3d& liftoff_rpy,
                        const Eigen::Vector3d& liftoff_rpy_rate, double duration);
  // From the action's lift-off angles and rates; duration = the ThrustPlan's duration().
  OrientationTrajectory(const Eigen::Vector3d& start_rpy, const JumpAction& action, double duration);

  double duration() const { return bezier_.duration(); }

  // t is clamped to [0, duration()], as in CubicBezier.
  Eigen::Vector3d rpy(double t) const { return bezier_.position(t); }
  Eigen::Vector3d rpyRate(double t) const { return bezier_.velocity(t); }
  Eigen::Vector3d rpyAcceleration(double t) const { return bezier_.acceleration(t); }

  Eigen::Matrix3d rotation(double t) const;                // body -> start frame
  Eigen::Vector3d angularVelocityWorld(double t) const;    // rad/s, start frame
  Eigen::Vector3d angularVelocityBody(double t) const;     // rad/s, body frame
  Eigen::Vector3d angularAccelerationWorld(double t) const;  // rad/s^2, start frame

  const Eigen::Vector3d& startRpy() const { return bezier_.controlPoints()[0]; }
  const Eigen::Vector3d& liftOffRpy() const { return bezier_.controlPoints()[3]; }  // after the yaw unwrap
  const Eigen::Vector3d& liftOffRpyRate() const { return liftoff_rate_; }
  // The lift-off angular velocity the trunk should have, start frame: E(rpy_lo) rpy_rate_lo.
  Eigen::Vector3d liftOffAngularVelocityWorld() const;

  const CubicBezier& bezier() const { return bezier_; }

 private:
  CubicBezier bezier_;
  Eigen::Vector3d liftoff_rate_;
};

}  // namespace pronk::jump
