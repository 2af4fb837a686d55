// Environment `jump`: one episode is one jump towards a target, with one action
// per episode (the paper's 13 jump parameters, reference-implementation.md s2).
//   observation (6): the target x, y, z (m), yaw, roll, pitch (rad), relative to
//                    the start, in the robot's initial heading frame;
//   action (13):     T_th, lift-off position (elevation, radius), lift-off
//                    velocity (elevation, speed), lift-off roll, pitch, yaw and
//                    their rates, UARM multiplier k and explosive distance d;
//   reward:          the paper's landing term exp(-e / sigma_e), e the horizontal
//                    distance between the CoM's start-relative displacement and
//                    the target.
// PARTIAL: the action is checked and stored but does not drive the robot yet;
// step() holds the stance with the guided_jump hold controller. The thrust,
// flight and landing phases come with the jump method.
#include <array>
#include <cmath>
#include <vector>

#include "abi_boundary.h"
#include "factories.h"
#include "hold_controller.h"
#include "landing_reward.h"
#include "plugin_params.h"

namespace pronk::guided_jump {
namespace {

constexpr int32_t kObservationSize = 6;
constexpr int32_t kActionSize = 13;

const std::vector<pronk_param_decl>& paramDecls() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d = {
        {sizeof(pronk_param_decl), "duration", PRONK_PARAM_REAL, 0, 0.01, 60.0, 0, "1.5", "s",
         "episode length: step() ends the episode at this time"},
        {sizeof(pronk_param_decl), "error_scale", PRONK_PARAM_REAL, 0, 0.001, 10.0, 0, "0.1", "m",
         "sigma_e of the landing reward exp(-e / sigma_e)"},
    };
    d.insert(d.end(), std::begin(kHoldParamDecls), std::end(kHoldParamDecls));
    return d;
  }();
  return decls;
}

class JumpEnvironment {
 public:
  JumpEnvironment(const pronk_host_api* host, const HoldSettings& hold, double duration, double error_scale)
      : hold_(host, hold), duration_(duration), error_scale_(error_scale) {}

  void reset(const double* task, int32_t task_size, const pronk_robot_state& state, double* observation) {
    if (!task || task_size != kObservationSize) {
      throw InvalidArgument("the jump task has 6 numbers (x, y, z, yaw, roll, pitch); got " + std::to_string(task_size));
    }
    if (!observation) throw InvalidArgument("no observation buffer");
    for (int i = 0; i < kObservationSize; ++i) {
      if (!std::isfinite(task[i])) throw InvalidArgument("task number " + std::to_string(i) + " is not finite");
    }
    hold_.reset(state);
    for (int i = 0; i < kObservationSize; ++i) task_[i] = observation[i] = task[i];
    com_start_ = Eigen::Vector3d(state.com_position[0], state.com_position[1], state.com_position[2]);
    start_yaw_ = yawOf(state.base_quaternion);
    has_task_ = true;
    has_action_ = false;
  }

  void act(const double* action) {
    if (!has_task_) throw InvalidArgument("act() before reset()");
    if (!action) throw InvalidArgument("no action");
    for (int i = 0; i < kActionSize; ++i) {
      if (!std::isfinite(action[i])) throw InvalidArgument("action number " + std::to_string(i) + " is not finite");
    }
    for (int i = 0; i < kActionSize; ++i) action_[i] = action[i];
    has_action_ = true;
  }

  bool step(const pronk_robot_state& state, double* torque) {
    if (!has_action_) throw InvalidArgument("step() before act(): the episode has no action");
    hold_.compute(state, torque);
    return state.time >= duration_;
  }

  double finish(const pronk_robot_state& state) {
    if (!has_task_) throw InvalidArgument("finish() before reset()");
    const Eigen::Vector3d com_end(state.com_position[0], state.com_position[1], state.com_position[2]);
    const double error = landingError(displacementInHeadingFrame(com_start_, com_end, start_yaw_),
                                      Eigen::Vector2d(task_[0], task_[1]));
    has_task_ = has_action_ = false;
    return landingReward(error, error_scale_);
  }

 private:
  HoldController hold_;
  double duration_, error_scale_;
  std::array<double, kObservationSize> task_{};
  std::array<double, kActionSize> action_{};
  bool has_task_ = false, has_action_ = false;
  Eigen::Vector3d com_start_ = Eigen::Vector3d::Zero();
  double start_yaw_ = 0;
};

JumpEnvironment* self(void* instance) { return static_cast<JumpEnvironment*>(instance); }

void need(const void* instance, const void* state) {
  if (!instance || !state) throw InvalidArgument("called without an instance or a state");
}

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const auto& decls = paramDecls();
    const ParamReader read(params, param_count, decls.data(), static_cast<int32_t>(decls.size()));
    *instance = new JumpEnvironment(host, readHoldSettings(read), read.real("duration"), read.real("error_scale"));
  });
}

pronk_status reset(void* instance, const double* task, int32_t task_size, uint64_t, const pronk_robot_state* state,
                   double* observation, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    self(instance)->reset(task, task_size, *state, observation);
  });
}

pronk_status act(void* instance, const double* action, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, action);
    self(instance)->act(action);
  });
}

pronk_status step(void* instance, const pronk_robot_state* state, double* torque, int32_t* done, char* error,
                  size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    if (!done) throw InvalidArgument("no done flag");
    *done = self(instance)->step(*state, torque) ? 1 : 0;
  });
}

pronk_status finish(void* instance, const pronk_robot_state* state, double* reward, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    need(instance, state);
    if (!reward) throw InvalidArgument("no reward pointer");
    *reward = self(instance)->finish(*state);
  });
}

void destroy(void* instance) { delete self(instance); }

const pronk_environment_ops kOps = {sizeof(pronk_environment_ops), reset, act, step, finish, destroy};

}  // namespace

const pronk_factory* jumpEnvironmentFactory() {
  static const pronk_factory factory = {
      sizeof(pronk_factory),
      PRONK_FACTORY_ENVIRONMENT,
      "jump",
      "one jump to a target per episode (6 target numbers in, 13 jump parameters, landing reward); "
      "partial: holds the stance, does not jump yet",
      static_cast<int32_t>(paramDecls().size()),
      paramDecls().data(),
      0,
      kObservationSize,
      kActionSize,
      kControlPeriod,
      create,
      nullptr,
      &kOps,
  };
  return &factory;
}

}  // namespace pronk::guided_jump
