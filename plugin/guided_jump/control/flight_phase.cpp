#include "control/flight_phase.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "control/robot_state.h"
#include "method/ballistics.h"

namespace pronk::guided_jump {

namespace {
constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
}  // namespace

const std::vector<pronk_param_decl>& FlightSettings::parameters() {
  static const std::vector<pronk_param_decl> decls = {
      {kDeclSize, "landing_extension", PRONK_PARAM_REAL, 0, -1.0, 0.3, 0, "-1", "m",
       "descent: the landing pose reaches this far below the stance feet, for the stroke saturated knees need to stop "
       "a fall (-1: derived from the robot's knee effort, mass and legs; 0: the stance pose)"},
      {kDeclSize, "landing_pose_levelling", PRONK_PARAM_REAL, 0, -5.0, 5.0, 0, "1.5", "",
       "descent: the landing pose's feet turn against the trunk's tilt by this multiple of it (1: as under a level "
       "trunk; above 1 further, as the trunk turns against the legs' swing; 0: the pose in the trunk's frame)"},
  };
  return decls;
}

FlightSettings FlightSettings::read(const ParamReader& read) {
  FlightSettings s;
  s.extension = read.real("landing_extension");
  s.pose_levelling = read.real("landing_pose_levelling");
  return s;
}

FlightPhase::FlightPhase(LegDrive& drive, const FlightSettings& settings, const LandingPhase& landing)
    : drive_(drive), settings_(settings), landing_(landing), clearance_(drive), blend_from_(Eigen::VectorXd::Zero(drive.jointCount())) {
  if (settings_.extension < 0.0) {
    settings_.extension = 0.0;
    if (drive_.legs() && drive_.footCount() == jump::kLegCount) {
      double effort = std::numeric_limits<double>::infinity();
      for (int f = 0; f < jump::kLegCount; ++f) effort = std::min(effort, drive_.motors()[3 * f + 2].effort);
      settings_.extension =
          derivedExtension(*drive_.legs(), drive_.hold().stance, effort, drive_.mass(), drive_.gravity().norm());
    }
  }
}

double FlightPhase::derivedExtension(const LegModels& legs, const std::array<double, 3>& stance, double knee_effort,
                                     double mass, double gravity) {
  if (!(gravity > 0.0) || !(mass > 0.0) || !std::isfinite(knee_effort)) return 0.0;
  const Eigen::Vector3d q(stance[0], stance[1], stance[2]);
  double lever = 0.0;
  for (const jump::LegGeometry& leg : legs) {
    lever += std::abs(jump::footPosition(leg, q).x() - jump::kneePosition(leg, q).x()) / legs.size();
  }
  if (!(lever > 0.0)) return 0.0;  // knees that hold any load need no extension
  return jump::landingExtension(jump::meanLegLength(legs), lever, knee_effort, mass, gravity,
                                static_cast<int>(legs.size()));
}

void FlightPhase::liftOff(const pronk_robot_state& s) {
  for (int j = 0; j < drive_.jointCount(); ++j) blend_from_(j) = s.q[j];
}

bool FlightPhase::descentDue(const pronk_robot_state& s, const JumpPlan& plan) const {
  if (!(s.com_velocity[2] < 0.0)) return false;
  // The CoM touches down `extension` higher than it stands.
  const Eigen::Vector3d g = drive_.gravity();
  if (!(g.z() < 0.0)) return false;
  const jump::BallisticFlight fall({vec(s.com_position), vec(s.com_velocity)}, g);
  return fall.landingTime(plan.landingComHeight() + settings_.extension).value_or(0.0) <= kBlendTime + kExtensionLead;
}

void FlightPhase::descend(double elapsed) {
  const double a = smoothstep(elapsed / kBlendTime);
  for (int j = 0; j < drive_.jointCount(); ++j) blend_from_(j) = blend_from_(j) + a * (settings_.tuck[j % 3] - blend_from_(j));
}

void FlightPhase::compute(const pronk_robot_state& s, const JumpPlan& plan, bool descending, double elapsed,
                          double* torque) {
  const int n = drive_.jointCount(), feet = drive_.footCount();
  const double a = smoothstep(elapsed / kBlendTime);
  Eigen::VectorXd goal(n);
  if (!descending) {
    for (int j = 0; j < n; ++j) goal(j) = settings_.tuck[j % 3];
  } else {
    // The landing pose: the stance feet as they would be under a level trunk, so
    // that a pitched or rolled trunk still lands on all four feet together.
    // Levelling swings the legs against the trunk's tilt (R = level tilt); in the
    // air the legs carry most of the roll inertia, so the trunk turns further
    // against that swing than the legs do. A levelling above 1 swings them
    // further, so that they come nearer the pose they aim for.
    // The feet land where the landing will stop the CoM (landingStop), with the
    // vertical speed the CoM will have when it is back at the standing height.
    const Eigen::Matrix3d R = rotationOf(s);
    const Eigen::Matrix3d level = headingOf(R);
    const Eigen::AngleAxisd tilt(level.transpose() * R);
    const Eigen::Matrix3d counter =
        Eigen::AngleAxisd(-settings_.pose_levelling * tilt.angle(), tilt.axis()).toRotationMatrix();
    const double landing_com_z = plan.landingComHeight() + settings_.extension;
    const double drop = std::max(0.0, s.com_position[2] - landing_com_z);
    Eigen::Vector3d v_touchdown = vec(s.com_velocity);
    v_touchdown.z() = -std::sqrt(v_touchdown.z() * v_touchdown.z() - 2.0 * drive_.gravity().z() * drop);
    Eigen::Vector3d ahead = Eigen::Vector3d::Zero();
    ahead.head<2>() = LandingPhase::landingStop(landing_.settings(), v_touchdown);
    ahead.z() = -settings_.extension;
    for (int f = 0; f < feet; ++f) {
      goal.segment<3>(3 * f) = drive_.legIk(f, counter * (plan.stance_feet.col(f) + level.transpose() * ahead));
    }
  }
  drive_.q_ref() = blend_from_ + a * (goal - blend_from_);
  clearance_.apply(s, plan);
  drive_.qd_ref().setZero();
  drive_.jointTorques(s, kp(), false, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), torque);
}

}  // namespace pronk::guided_jump
