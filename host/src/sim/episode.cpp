#include "pronk/episode.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace pronk {
namespace {

// The "apex_platform" event's detail, written and read here only.
constexpr const char* kApexDetail = "top z = %.4f m";

TraceSample sampleOf(const World& world, const RobotState& s, const Eigen::VectorXd& torque, bool poses) {
  TraceSample out;
  out.time = s.time;
  out.base_position = s.base_position;
  out.base_quaternion = s.base_quaternion;
  out.base_linear_velocity = s.base_linear_velocity;
  out.com_position = s.com_position;
  out.com_velocity = s.com_velocity;
  out.q = s.q;
  out.qd = s.qd;
  out.torque = torque;
  out.foot_position = s.foot_position;
  out.foot_force = s.foot_force;
  out.foot_in_contact = s.foot_in_contact;
  if (poses) out.body_poses = world.bodyPoses();
  return out;
}

// The terrain once the apex platform appears: its top is the target's surface
// or, when the lowest sole does not clear it, `clearance` below that sole
// (never below the floor).
Terrain apexTerrain(const World& world, const ApexPlatform& a, double* top) {
  const RobotState& s = world.state();
  double sole = INFINITY;
  for (int f = 0; f < world.footCount(); ++f) sole = std::min(sole, s.foot_position[f].z() - world.footRadius(f));
  *top = std::clamp(std::min(a.top, sole - a.clearance), a.floor, a.top);
  return withApexPlatform(world.terrain(), a, *top);
}

}  // namespace

std::optional<ApexPlatformEvent> apexPlatformEvent(const Trace& trace) {
  const TraceEvent* e = trace.findEvent("apex_platform");
  ApexPlatformEvent out;
  if (!e || std::sscanf(e->detail.c_str(), "top z = %lf m", &out.top) != 1) return std::nullopt;
  out.time = e->time;
  return out;
}

EpisodeResult runEpisode(World& world, Controller& controller, const EpisodeOptions& options) {
  EpisodeResult result;
  Trace& trace = result.trace;
  trace.joint_names = world.jointNames();
  trace.foot_links = world.footLinks();
  const auto start = std::chrono::steady_clock::now();
  if (!(options.duration > 0 && options.duration <= kMaxEpisodeSeconds)) {
    throw Error("episode duration " + std::to_string(options.duration) + " s is not in (0, " +
                std::to_string(kMaxEpisodeSeconds) + "] s");
  }
  const long ticks = std::lround(options.duration / world.controlPeriod());
  bool was_airborne = false;
  bool landed = false;      // a touchdown after a flight
  bool lifted_off = false;
  bool apex_placed = !options.apex_platform;
  double rest_since = NAN;  // when the robot last came to rest
  try {
    controller.reset(world.state());
    for (long k = 0; k < ticks; ++k) {
      const RobotState& s = world.state();
      const Eigen::VectorXd torque = controller.compute(s);
      if (options.record_samples || k == 0) trace.samples.push_back(sampleOf(world, s, torque, options.record_body_poses));
      if (!world.step(torque)) break;
      if (controller.finished()) break;
      if (options.stop && options.stop->load()) {
        trace.addEvent(world.time(), "stopped", "by a signal");
        break;
      }
      // Contact changes of the whole robot: all feet off, then any foot back on.
      bool any_contact = false;
      for (uint8_t c : world.state().foot_in_contact) any_contact = any_contact || c;
      if (!any_contact && !was_airborne) {
        trace.addEvent(world.time(), "lift_off");
        lifted_off = true;
      }
      if (!apex_placed && lifted_off && !any_contact && world.state().com_velocity.z() <= 0) {
        double top = 0;
        world.replaceTerrain(apexTerrain(world, *options.apex_platform, &top));
        char detail[64];
        std::snprintf(detail, sizeof detail, kApexDetail, top);
        trace.addEvent(world.time(), "apex_platform", detail);
        apex_placed = true;
      }
      if (any_contact && was_airborne) {
        trace.addEvent(world.time(), "touchdown");
        landed = true;
      }
      was_airborne = !any_contact;
      if (landed) {
        // At rest after the landing: every foot down, the CoM and the trunk still.
        const RobotState& now = world.state();
        bool still = now.com_velocity.norm() < kRestSpeed && now.base_angular_velocity.norm() < kRestRate;
        for (uint8_t c : now.foot_in_contact) still = still && c;
        if (!still) rest_since = NAN;
        else if (std::isnan(rest_since)) rest_since = now.time;
        if (options.end_at_rest > 0 && !std::isnan(rest_since) && now.time - rest_since >= options.end_at_rest - 1e-9) {
          break;
        }
      }
    }
  } catch (const Error& e) {
    result.failure = Failure{world.time(), "controller", e.what()};
  }
  if (!result.failure && world.failure()) result.failure = world.failure();
  if (!result.failure && !std::isnan(rest_since)) trace.addEvent(rest_since, "at_rest");
  if (result.failure) trace.addEvent(result.failure->time, "failure", result.failure->reason + ": " + result.failure->detail);
  // The final state, so the trace ends where the robot did.
  trace.samples.push_back(sampleOf(world, world.state(), Eigen::VectorXd::Zero(world.jointCount()),
                                   options.record_body_poses));
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.statistics = world.statistics();
  return result;
}

}  // namespace pronk
