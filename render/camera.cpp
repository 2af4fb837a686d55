#include "render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace pronk::render {

Eigen::Matrix4d lookAt(const Camera& c) {
  const Eigen::Vector3d f = (c.target - c.eye).normalized();
  const Eigen::Vector3d s = f.cross(c.up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(c.eye);
  m(1, 3) = -u.dot(c.eye);
  m(2, 3) = f.dot(c.eye);
  return m;
}

Eigen::Matrix4d perspective(double fovy_deg, double aspect, double near_m, double far_m) {
  const double f = 1.0 / std::tan(0.5 * fovy_deg * M_PI / 180.0);
  Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
  m(0, 0) = f / aspect;
  m(1, 1) = f;
  m(2, 2) = (far_m + near_m) / (near_m - far_m);
  m(2, 3) = 2 * far_m * near_m / (near_m - far_m);
  m(3, 2) = -1;
  return m;
}

Camera frameJump(const std::string& mode, const Eigen::Vector3d& start, const Eigen::Vector3d& goal, double height,
                 double fovy_deg, double aspect, const Eigen::Vector3d& follow_point, double heading) {
  Camera c;
  c.fovy_deg = fovy_deg;
  Eigen::Vector3d along = goal - start;
  along.z() = 0;
  if (along.norm() < 0.05) along = Eigen::Vector3d::UnitX();
  along.normalize();
  const Eigen::Vector3d side = Eigen::Vector3d::UnitZ().cross(along);  // left of the jump
  const Eigen::Vector3d middle = 0.5 * (start + goal) + Eigen::Vector3d(0, 0, 0.5 * height);
  // Distance that fits the span (plus a robot length each side) in the narrower field of view.
  const double span = (goal - start).head<2>().norm() + 1.0;
  const double half_fov = 0.5 * fovy_deg * M_PI / 180.0;
  const double fit_w = 0.5 * span / (std::tan(half_fov) * aspect);
  const double fit_h = 0.5 * (height + 0.6) / std::tan(half_fov);
  const double distance = std::max({fit_w, fit_h, 1.2});
  if (mode == "top") {
    c.eye = middle + Eigen::Vector3d(0, 0, distance + 0.5);
    c.target = middle;
    c.up = along;
  } else if (mode == "follow") {
    c.target = follow_point;
    c.eye = follow_point - 1.6 * along - 1.2 * side + Eigen::Vector3d(0, 0, 0.7);
  } else {  // side view, perpendicular to the jump plane, slightly from above
    // Turned towards the trunk's flank by |sin| of the jump's angle to the
    // heading (0 for a forward jump, the whole turn for a lateral one), the
    // camera moving back along the jump.
    const double across = std::abs(std::sin(std::atan2(along.y(), along.x()) - heading));
    const double turn = kSideViewTurnDeg * M_PI / 180.0 * across;
    const Eigen::Vector3d view = std::cos(turn) * -side - std::sin(turn) * along;
    c.target = middle;
    c.eye = middle + distance * view + Eigen::Vector3d(0, 0, 0.25 * distance);
  }
  return c;
}

bool project(const Camera& camera, int width, int height, const Eigen::Vector3d& point, Eigen::Vector2d& pixel) {
  const Eigen::Matrix4d pv = perspective(camera.fovy_deg, double(width) / height, 0.05, 100) * lookAt(camera);
  const Eigen::Vector4d clip = pv * point.homogeneous();
  if (clip.w() <= 0) return false;
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  pixel = Eigen::Vector2d((ndc.x() + 1) * 0.5 * width, (1 - ndc.y()) * 0.5 * height);
  return true;
}

}  // namespace pronk::render
