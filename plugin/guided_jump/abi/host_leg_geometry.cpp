#include "abi/host_leg_geometry.h"

#include <cmath>
#include <vector>

#include <Eigen/Core>

namespace pronk::guided_jump {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTolerance = 1e-4;  // m between the analytic model and the host

bool hostFoot(const pronk_host_api* host, int foot, const Eigen::Vector3d& leg_q, Eigen::Vector3d* out) {
  const int n = host->joint_count(host->host);
  std::vector<double> q(static_cast<size_t>(n), 0.0);
  for (int k = 0; k < 3; ++k) q[static_cast<size_t>(3 * foot + k)] = leg_q[k];
  double p[3];
  if (host->foot_position_base(host->host, foot, q.data(), p) != PRONK_OK) return false;
  *out = Eigen::Vector3d(p[0], p[1], p[2]);
  return true;
}

double signOf(double v) { return v < 0 ? -1.0 : 1.0; }

}  // namespace

std::optional<std::array<jump::LegGeometry, jump::kLegCount>> legGeometryFromHost(const pronk_host_api* host,
                                                                                    std::string* why) {
  auto fail = [&](const std::string& message) {
    if (why) *why = message;
    return std::nullopt;
  };
  if (!host || !host->foot_position_base || !host->joint_limits) return fail("the host has no forward kinematics");
  if (host->foot_count(host->host) != jump::kLegCount || host->joint_count(host->host) != 3 * jump::kLegCount) {
    return fail("the leg model needs 4 legs of 3 joints");
  }
  std::array<jump::LegGeometry, jump::kLegCount> legs{};
  for (int f = 0; f < jump::kLegCount; ++f) {
    Eigen::Vector3d straight, knee, abducted;
    if (!hostFoot(host, f, {0, 0, 0}, &straight) || !hostFoot(host, f, {0, 0, -kPi / 2}, &knee) ||
        !hostFoot(host, f, {kPi / 2, 0, 0}, &abducted)) {
      return fail("the host's forward kinematics failed for foot " + std::to_string(f));
    }
    jump::LegGeometry& leg = legs[f];
    leg.front = signOf(straight.x());
    leg.side = signOf(straight.y());
    leg.hip_x = std::abs(straight.x());
    leg.calf_length = knee.x() - straight.x();
    leg.thigh_length = -knee.z();
    leg.thigh_offset = std::abs(abducted.z());
    leg.hip_y = std::abs(straight.y()) - leg.thigh_offset;
    for (int k = 0; k < 3; ++k) {
      double lower = 0, upper = 0;
      host->joint_limits(host->host, 3 * f + k, &lower, &upper, nullptr, nullptr);
      leg.limits[k] = {lower, upper};
    }
    try {
      leg.check();
    } catch (const std::exception& e) {
      return fail("foot " + std::to_string(f) + ": " + e.what());
    }
    // The model must reproduce the host at poses it was not fitted on.
    const Eigen::Vector3d poses[] = {{0.1, 0.8, -1.6}, {-0.3, 1.2, -2.2}, {0.4, -0.3, -1.0}, {0, 0.75, -1.5}};
    for (const Eigen::Vector3d& q : poses) {
      Eigen::Vector3d p;
      if (!hostFoot(host, f, q, &p)) return fail("the host's forward kinematics failed for foot " + std::to_string(f));
      const double error = (jump::footPosition(leg, q) - p).norm();
      if (!(error <= kTolerance)) {
        return fail("foot " + std::to_string(f) + " is not a Unitree-form leg: the analytic model is " +
                    std::to_string(error * 1000) + " mm off the robot's kinematics");
      }
    }
  }
  return legs;
}

}  // namespace pronk::guided_jump
