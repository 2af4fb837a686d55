#include "method/orientation_trajectory.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <Eigen/Geometry>

namespace pronk::jump {
namespace {

constexpr double kTwoPi = 6.28318530717958647692;

CubicBezier makeOrientationBezier(const Eigen::Vector3d& start_rpy, const Eigen::Vector3d& liftoff_rpy,
                                  const Eigen::Vector3d& liftoff_rpy_rate, double duration) {
  if (!start_rpy.allFinite() || !liftoff_rpy.allFinite() || !liftoff_rpy_rate.allFinite()) {
    std::ostringstream msg;
    msg << "orientation trajectory: non-finite input: start rpy (" << start_rpy.transpose() << "), lift-off rpy ("
        << liftoff_rpy.transpose() << "), lift-off rpy rate (" << liftoff_rpy_rate.transpose() << ")";
    throw std::invalid_argument(msg.str());
  }
  PointState start;
  start.position = start_rpy;
  PointState end;
  end.position = liftoff_rpy;
  end.position.z() -= kTwoPi * std::round((liftoff_rpy.z() - start_rpy.z()) / kTwoPi);
  end.velocity = liftoff_rpy_rate;
  return CubicBezier::fromBoundaryStates(start, end, duration);
}

}  // namespace

Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy) {
  // A pure yaw (the planner's thrust paths, checked at ~60 samples each): the
  // matrix the quaternion route below gives for it (its roll and pitch factors
  // are exact identities; zeros aside, bit for bit), from one sine and cosine
  // instead of three.
  if (rpy.x() == 0.0 && rpy.y() == 0.0) {
    const double half = 0.5 * rpy.z();
    const double w = std::cos(half), z = std::sin(half);
    const double tz = 2.0 * z;
    const double twz = tz * w, tzz = tz * z;
    Eigen::Matrix3d r;
    r << 1.0 - tzz, -twz, 0.0,  //
        twz, 1.0 - tzz, 0.0,    //
        0.0, 0.0, 1.0;
    return r;
  }
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Matrix3d eulerRateToWorldAngularVelocity(const Eigen::Vector3d& rpy) {
  const double cp = std::cos(rpy.y()), sp = std::sin(rpy.y());
  const double cy = std::cos(rpy.z()), sy = std::sin(rpy.z());
  Eigen::Matrix3d e;
  e << cy * cp, -sy, 0.0,  //
      sy * cp, cy, 0.0,    //
      -sp, 0.0, 1.0;
  return e;
}

Eigen::Vector3d worldAngularVelocity(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate) {
  return eulerRateToWorldAngularVelocity(rpy) * rpy_rate;
}

Eigen::Vector3d bodyAngularVelocity(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate) {
  return rotationFromRpy(rpy).transpose() * worldAngularVelocity(rpy, rpy_rate);
}

Eigen::Vector3d worldAngularAcceleration(const Eigen::Vector3d& rpy, const Eigen::Vector3d& rpy_rate,
                                         const Eigen::Vector3d& rpy_acceleration) {
  const double cp = std::cos(rpy.y()), sp = std::sin(rpy.y());
  const double cy = std::cos(rpy.z()), sy = std::sin(rpy.z());
  const double roll_rate = rpy_rate.x(), pitch_rate = rpy_rate.y(), yaw_rate = rpy_rate.z();
  // Time derivatives of E's roll and pitch columns (the yaw column is constant).
  const Eigen::Vector3d d_roll_column(-sy * cp * yaw_rate - cy * sp * pitch_rate,
                                      cy * cp * yaw_rate - sy * sp * pitch_rate, -cp * pitch_rate);
  const Eigen::Vector3d d_pitch_column(-cy * yaw_rate, -sy * yaw_rate, 0.0);
  return eulerRateToWorldAngularVelocity(rpy) * rpy_acceleration + roll_rate * d_roll_column +
         pitch_rate * d_pitch_column;
}

OrientationTrajectory::OrientationTrajectory(const Eigen::Vector3d& start_rpy, const Eigen::Vector3d& liftoff_rpy,
                                             const Eigen::Vector3d& liftoff_rpy_rate, double duration)
    : bezier_(makeOrientationBezier(start_rpy, liftoff_rpy, liftoff_rpy_rate, duration)),
      liftoff_rate_(liftoff_rpy_rate) {}

OrientationTrajectory::OrientationTrajectory(const Eigen::Vector3d& start_rpy, const JumpAction& action,
                                             double duration)
    : OrientationTrajectory(start_rpy, action.liftoff_rpy_rad, action.liftoff_rpy_rate_radps, duration) {}

Eigen::Matrix3d OrientationTrajectory::rotation(double t) const { return rotationFromRpy(rpy(t)); }

Eigen::Vector3d OrientationTrajectory::angularVelocityWorld(double t) const {
  return worldAngularVelocity(rpy(t), rpyRate(t));
}

Eigen::Vector3d OrientationTrajectory::angularVelocityBody(double t) const {
  return bodyAngularVelocity(rpy(t), rpyRate(t));
}

Eigen::Vector3d OrientationTrajectory::angularAccelerationWorld(double t) const {
  return worldAngularAcceleration(rpy(t), rpyRate(t), rpyAcceleration(t));
}

Eigen::Vector3d OrientationTrajectory::liftOffAngularVelocityWorld() const {
  return worldAngularVelocity(liftOffRpy(), liftoff_rate_);
}

}  // namespace pronk::jump
