#include "pronk/landing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

namespace pronk {
namespace {

double wrap(double a) { return std::remainder(a, 2 * M_PI); }

std::string endFailure(const TraceSample& end, double tilt) {
  char text[160];
  if (tilt > kTippedAngle) {
    std::snprintf(text, sizeof text, "tipped_over: the trunk is tilted %.0f deg from upright at the episode's end",
                  tilt * 180 / M_PI);
    return text;
  }
  const bool any_down = std::any_of(end.foot_in_contact.begin(), end.foot_in_contact.end(), [](uint8_t c) { return c; });
  if (!end.foot_in_contact.empty() && !any_down) {
    std::snprintf(text, sizeof text, "airborne: no foot touches the ground at the episode's end (t = %.2f s)",
                  end.time);
    return text;
  }
  return "";
}

// Mean height of the feet on the ground (of all feet when none is): the
// surface they stand on, up to the sole's radius that cancels in differences.
double feetHeight(const TraceSample& s) {
  double sum = 0, all = 0;
  int down = 0;
  for (size_t f = 0; f < s.foot_position.size(); ++f) {
    all += s.foot_position[f].z();
    if (f < s.foot_in_contact.size() && s.foot_in_contact[f]) sum += s.foot_position[f].z(), ++down;
  }
  if (down > 0) return sum / down;
  return s.foot_position.empty() ? NAN : all / double(s.foot_position.size());
}

}  // namespace

double yawOf(const Eigen::Vector4d& q_wxyz) {
  const Eigen::Quaterniond q(q_wxyz(0), q_wxyz(1), q_wxyz(2), q_wxyz(3));
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  return std::atan2(R(1, 0), R(0, 0));
}

Landing landingOf(const Trace& trace, const TargetSpec& target) {
  Landing l;
  if (trace.samples.size() < 2) return l;
  const TraceSample& a = trace.samples.front();
  const TraceSample& b = trace.samples.back();
  const double yaw0 = yawOf(a.base_quaternion);
  l.displacement = Eigen::AngleAxisd(-yaw0, Eigen::Vector3d::UnitZ()) * (b.base_position - a.base_position);
  l.yaw = wrap(yawOf(b.base_quaternion) - yaw0);
  l.error_xy = (l.displacement.head<2>() - Eigen::Vector2d(target.x, target.y)).norm();
  l.error_yaw = std::abs(wrap(l.yaw - target.yaw));
  l.height = feetHeight(b) - feetHeight(a);
  l.error = target.z == 0 ? l.error_xy : std::hypot(l.error_xy, l.height - target.z);
  const Eigen::Quaterniond q(b.base_quaternion(0), b.base_quaternion(1), b.base_quaternion(2), b.base_quaternion(3));
  l.tilt = std::acos(std::clamp(q.normalized().toRotationMatrix()(2, 2), -1.0, 1.0));
  bool all_down = !b.foot_in_contact.empty();
  for (uint8_t c : b.foot_in_contact) all_down = all_down && c;
  l.standing = all_down && l.tilt < kUprightAngle;
  l.end_failure = endFailure(b, l.tilt);
  return l;
}

}  // namespace pronk
