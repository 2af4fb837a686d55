// The guided jump as a small phase machine around the stance controller
// (control/hold_controller.h); each phase is a class of its own:
//
//   stand      0 .. start_delay          HoldController: stance PD + gravity compensation
//   thrust     Bezier part of the plan   } ThrustPhase (control/thrust_phase.h): the whole-body
//   explosive  UARM part of the plan     } CoM follows the plan, the trunk the orientation plan
//   flight     from lift-off             } FlightPhase (control/flight_phase.h): tuck, then
//   descend    before the touchdown      } the landing pose
//   landing    from touchdown            LandingPhase (control/landing_phase.h)
//
// The plan (control/jump_plan.h) is made when the thrust starts. Without lift-off
// within kLiftOffWait after the plan's end the jump is abandoned and the robot
// lands (stance) in place. Every phase change is an event "phase:<name>" through
// host->emit_event.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "control/flight_phase.h"
#include "control/hold_controller.h"
#include "control/jump_plan.h"
#include "control/landing_phase.h"
#include "control/leg_drive.h"
#include "control/param_reader.h"
#include "control/thrust_phase.h"
#include "method/action_mapping.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

struct JumpSettings {
  HoldSettings hold;                 // gains, stance (= landing pose), motors
  std::vector<double> action;        // empty: hold the stance; else 13 physical numbers (ActionParameter order)
  double azimuth = 0.0;              // rad: the jump plane's direction in the start frame (from the target)
  double start_delay = 0.2;          // s of standing before the thrust
  double landing_height = 0.0;       // m: the landing surface above the take-off surface
  ThrustSettings thrust;
  FlightSettings flight;
  LandingSettings landing;
  // The analytic leg model (from the host's kinematics, abi/host_leg_geometry.h);
  // none: the IK takes Newton steps on the host's kinematics.
  std::optional<LegModels> legs;

  // The phases' own parameters, each declared by its phase, and start_delay:
  // what the controller and the environment both take.
  static const std::vector<pronk_param_decl>& parameters();
  // Reads them (hold, start_delay, thrust, flight, landing) into *settings.
  static void read(const ParamReader& read, JumpSettings* settings);
};

enum class JumpPhase { kHold, kStand, kThrust, kExplosive, kFlight, kDescend, kLanding };
const char* jumpPhaseName(JumpPhase phase);  // "hold", "stand", "thrust", ...

// The control period the controller is written for (both factories declare it), s.
constexpr double kControlPeriod = 0.001;

class JumpController {
 public:
  static constexpr double kLiftOffWait = 0.15;  // s after the plan's end before giving up on lift-off

  // Throws InvalidArgument for an action of the wrong size or one the method rejects.
  JumpController(const pronk_host_api* host, const JumpSettings& settings);

  void reset(const pronk_robot_state& state);
  void compute(const pronk_robot_state& state, double* torque);

  JumpPhase phase() const { return phase_; }
  bool jumping() const { return has_action_; }
  // From the thrust start on: the plan (start frame S) and S in the world.
  const jump::ThrustPlan* plan() const { return plan_ ? plan_->thrust.get() : nullptr; }
  const Eigen::Vector3d& startOrigin() const { return plan_->origin; }    // S origin, world
  const Eigen::Matrix3d& startHeading() const { return plan_->heading; }  // S -> world
  // The last tick's torques before the motors clamp them (what the controller asked for).
  const Eigen::VectorXd& commandedTorque() const { return drive_.commandedTorque(); }

 private:
  void enter(JumpPhase phase, double time, const std::string& detail = "");
  void startThrust(const pronk_robot_state& s);
  void holdStance(const pronk_robot_state& s, double* torque);

  const pronk_host_api* host_;
  JumpSettings settings_;
  HoldController hold_;
  LegDrive drive_;
  ThrustPhase thrust_;
  LandingPhase landing_;
  FlightPhase flight_;
  bool has_action_ = false;
  jump::JumpAction action_;

  JumpPhase phase_ = JumpPhase::kHold;
  double reset_time_ = 0;
  double phase_start_ = 0;
  std::optional<JumpPlan> plan_;
};

}  // namespace pronk::guided_jump
