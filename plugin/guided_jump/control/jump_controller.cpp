#include "control/jump_controller.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "control/invalid_argument.h"
#include "control/robot_state.h"

namespace pronk::guided_jump {

namespace {
constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);
}  // namespace

const char* jumpPhaseName(JumpPhase phase) {
  switch (phase) {
    case JumpPhase::kHold: return "hold";
    case JumpPhase::kStand: return "stand";
    case JumpPhase::kThrust: return "thrust";
    case JumpPhase::kExplosive: return "explosive";
    case JumpPhase::kFlight: return "flight";
    case JumpPhase::kDescend: return "descend";
    case JumpPhase::kLanding: return "landing";
  }
  return "unknown";
}

const std::vector<pronk_param_decl>& JumpSettings::parameters() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d = HoldSettings::parameters();
    d.push_back({kDeclSize, "start_delay", PRONK_PARAM_REAL, 0, 0.0, 60.0, 0, "0.2", "s",
                 "standing time before the thrust"});
    for (const auto* phase : {&ThrustSettings::parameters(), &FlightSettings::parameters(),
                              &LandingSettings::parameters()}) {
      d.insert(d.end(), phase->begin(), phase->end());
    }
    return d;
  }();
  return decls;
}

void JumpSettings::read(const ParamReader& read, JumpSettings* s) {
  s->hold = HoldSettings::read(read);
  s->start_delay = read.real("start_delay");
  s->thrust = ThrustSettings::read(read);
  s->flight = FlightSettings::read(read);
  s->landing = LandingSettings::read(read);
}

JumpController::JumpController(const pronk_host_api* host, const JumpSettings& settings)
    : host_(host),
      settings_(settings),
      hold_(host, settings.hold),
      drive_(host, settings.hold, hold_.jointCount(), hold_.footCount(), settings.legs),
      thrust_(drive_, settings.thrust),
      landing_(drive_, settings.landing),
      flight_(drive_, settings.flight, landing_) {
  if (!(settings.flight.kp_division >= 1.0) || !std::isfinite(settings.flight.kp_division)) {
    throw InvalidArgument("the flight's Kp division must be >= 1");
  }
  if (!(settings.start_delay >= 0.0) || !std::isfinite(settings.start_delay)) {
    throw InvalidArgument("start_delay must be >= 0");
  }
  if (!settings.action.empty()) {
    if (settings.action.size() != static_cast<size_t>(jump::kActionSize)) {
      throw InvalidArgument("parameter 'action' needs " + std::to_string(jump::kActionSize) +
                            " numbers (T_th r_p theta_p r_v theta_v k d roll pitch yaw roll_rate pitch_rate "
                            "yaw_rate) or none, got " +
                            std::to_string(settings.action.size()));
    }
    jump::ActionVector v{};
    std::copy(settings.action.begin(), settings.action.end(), v.begin());
    action_ = jump::fromVector(v);
    if (!(action_.thrust_duration_s > 0)) throw InvalidArgument("action: the thrust duration must be > 0");
    if (!(action_.liftoff_speed_mps > 0)) throw InvalidArgument("action: the lift-off speed must be > 0");
    if (!(action_.speed_ratio >= 1.0)) throw InvalidArgument("action: k must be >= 1");
    if (!(action_.explosive_distance_m >= 0.0)) throw InvalidArgument("action: d must be >= 0");
    // Built once here so that the method's own checks refuse a bad action at create().
    try {
      jump::ThrustPlan check(action_, 0.0, Eigen::Vector3d(0, 0, 0.3), Eigen::Vector3d::Zero());
      jump::OrientationTrajectory o(Eigen::Vector3d::Zero(), action_, check.duration());
    } catch (const std::invalid_argument& e) {
      throw InvalidArgument(std::string("action: ") + e.what());
    }
    has_action_ = true;
  }
  if (!std::isfinite(settings.azimuth)) throw InvalidArgument("the jump azimuth is not finite");
}

void JumpController::enter(JumpPhase phase, double time, const std::string& detail) {
  phase_ = phase;
  phase_start_ = time;
  if (host_->emit_event) {
    const std::string name = std::string("phase:") + jumpPhaseName(phase);
    host_->emit_event(host_->host, time, name.c_str(), detail.c_str());
  }
}

void JumpController::reset(const pronk_robot_state& state) {
  hold_.reset(state);  // checks the state, emits "hold"
  reset_time_ = state.time;
  phase_start_ = state.time;
  landing_.reset();
  plan_.reset();
  phase_ = has_action_ ? JumpPhase::kStand : JumpPhase::kHold;
}

void JumpController::holdStance(const pronk_robot_state& s, double* torque) {
  hold_.compute(s, torque);
  drive_.setCommandedTorque(torque);
}

void JumpController::startThrust(const pronk_robot_state& s) {
  plan_ = makeJumpPlan(drive_, s, action_, settings_.azimuth, settings_.landing_height);
  thrust_.begin(s);
  for (int j = 0; j < drive_.jointCount(); ++j) drive_.q_ref()(j) = s.q[j];
  char detail[200];
  const jump::ThrustPlan& p = *plan_->thrust;
  const jump::PointState& lo = p.liftOff();
  std::snprintf(detail, sizeof detail,
                "T_th %.3f s, T_e %.3f s, lift-off CoM (%.3f, %.3f, %.3f) m, velocity (%.3f, %.3f, %.3f) m/s (start frame)",
                p.bezierDuration(), p.explosiveDuration(), lo.position.x(), lo.position.y(), lo.position.z(),
                lo.velocity.x(), lo.velocity.y(), lo.velocity.z());
  enter(JumpPhase::kThrust, s.time, detail);
}

void JumpController::compute(const pronk_robot_state& s, double* torque) {
  if (!torque) throw InvalidArgument("no torque buffer");
  if (phase_ == JumpPhase::kHold) {
    holdStance(s, torque);
    return;
  }
  const int feet = drive_.footCount();
  if (s.joint_count != drive_.jointCount() || s.foot_count != feet || !s.q || !s.qd || !s.foot_position ||
      !s.foot_in_contact) {
    hold_.compute(s, torque);  // throws with the details
    return;
  }
  bool any_contact = false;
  for (int f = 0; f < feet; ++f) any_contact = any_contact || s.foot_in_contact[f];

  if (phase_ == JumpPhase::kLanding) {
    landing_.compute(s, *plan_, s.time - phase_start_, flight_.kp(), torque);
    return;
  }
  if (phase_ == JumpPhase::kStand) {
    if (s.time - reset_time_ < settings_.start_delay - 1e-9) {
      holdStance(s, torque);
      return;
    }
    startThrust(s);
  }
  if (phase_ == JumpPhase::kThrust || phase_ == JumpPhase::kExplosive) {
    const jump::ThrustPlan& p = *plan_->thrust;
    const double t = s.time - plan_->start_time;
    if (!any_contact) {
      flight_.liftOff(s);
      char detail[360];
      const Eigen::Vector3d v = plan_->heading.transpose() * vec(s.com_velocity);
      int n = std::snprintf(detail, sizeof detail,
                            "%.3f s into the thrust (plan %.3f s); CoM velocity (%.3f, %.3f, %.3f) m/s (start frame)", t,
                            p.duration(), v.x(), v.y(), v.z());
      const std::optional<Eigen::Vector3d> w = wholeBodyRate(host_);
      if (w && n > 0 && n < static_cast<int>(sizeof detail)) {
        const Eigen::Vector3d w_S = plan_->heading.transpose() * *w;
        n += std::snprintf(detail + n, sizeof detail - n, "; whole-body rate (%.2f, %.2f, %.2f) rad/s", w_S.x(),
                           w_S.y(), w_S.z());
      }
      const Eigen::Vector3d& turn = thrust_.momentumTurn();
      if (turn.norm() > 0 && n > 0 && n < static_cast<int>(sizeof detail)) {
        const Eigen::Vector3d tilt_S = plan_->heading.transpose() * turn;
        std::snprintf(detail + n, sizeof detail - n, "; momentum turn (%.2f, %.2f, %.2f) rad", tilt_S.x(), tilt_S.y(),
                      tilt_S.z());
      }
      enter(JumpPhase::kFlight, s.time, detail);
    } else if (t > p.duration() + kLiftOffWait) {
      enter(JumpPhase::kLanding, s.time, "no lift-off: the jump is abandoned");
      phase_start_ -= LandingPhase::kLandingRamp;  // nothing to absorb: full gains at once
      landing_.abandon();
      compute(s, torque);
      return;
    } else {
      if (phase_ == JumpPhase::kThrust && t > p.bezierDuration() && p.explosiveDuration() > 0) {
        enter(JumpPhase::kExplosive, s.time);
      }
      thrust_.compute(s, *plan_, t, torque);
      return;
    }
  }
  if (phase_ == JumpPhase::kFlight || phase_ == JumpPhase::kDescend) {
    // A foot that brushes the ground while the CoM still rises (a toe that
    // scuffs just after lift-off) is not a touchdown: taken for one, the landing's
    // stop would pull the robot back to where it left and steer the whole flight
    // (docs/method.md).
    if (any_contact && s.com_velocity[2] <= 0.0) {
      landing_.touchDown(s, *plan_);
      enter(JumpPhase::kLanding, s.time);
      compute(s, torque);
      return;
    }
    // The legs stay tucked until the extension, kBlendTime long, ends kExtensionLead
    // before the predicted touchdown on the landing surface (the reference extends
    // at the apex; docs/method.md has the measured comparison).
    if (phase_ == JumpPhase::kFlight && flight_.descentDue(s, *plan_)) {
      flight_.descend(s.time - phase_start_);
      char detail[80];
      std::snprintf(detail, sizeof detail, "landing pose %.3f m below the stance feet", flight_.extension());
      enter(JumpPhase::kDescend, s.time, detail);
    }
    flight_.compute(s, *plan_, phase_ == JumpPhase::kDescend, s.time - phase_start_, torque);
  }
}

}  // namespace pronk::guided_jump
