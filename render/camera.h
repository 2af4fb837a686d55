// Cameras for episode videos: where the eye is and the two matrices OpenGL
// needs, computed here (no GLU).
#pragma once

#include <Eigen/Core>
#include <string>

namespace pronk::render {

struct Camera {
  Eigen::Vector3d eye{0, -2, 0.6};
  Eigen::Vector3d target{0, 0, 0.3};
  Eigen::Vector3d up{0, 0, 1};
  double fovy_deg = 45;
};

// Column-major 4x4 matrices, as glLoadMatrixd wants them.
Eigen::Matrix4d lookAt(const Camera& camera);
Eigen::Matrix4d perspective(double fovy_deg, double aspect, double near_m, double far_m);

// A camera that frames the segment from `start` to `goal` (plus `height` of
// headroom) from the side of the jump plane ("side"), from above ("top"), or
// chasing `follow_point` ("follow"). `heading` is the robot's yaw at the start
// (rad): a side view of a jump across the trunk (lateral, diagonal) turns up to
// kSideViewTurnDeg towards the trunk's flank, so that its legs do not hide each
// other as they do seen straight from the front.
constexpr double kSideViewTurnDeg = 35.0;
Camera frameJump(const std::string& mode, const Eigen::Vector3d& start, const Eigen::Vector3d& goal, double height,
                 double fovy_deg, double aspect, const Eigen::Vector3d& follow_point, double heading = 0.0);

// Pixel of a world point for a camera and image size (x right, y down), and
// whether it is in front of the camera.
bool project(const Camera& camera, int width, int height, const Eigen::Vector3d& point, Eigen::Vector2d& pixel);

}  // namespace pronk::render
