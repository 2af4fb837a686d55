// Environment `jump` across the C boundary: its callbacks, the metrics it
// declares (ABI 1.3) and its factory. The environment itself is
// environment/jump_environment.h.
#include <string>
#include <vector>

#include "abi/abi_boundary.h"
#include "abi/factories.h"
#include "abi/host_leg_geometry.h"
#include "abi/jump_params.h"
#include "control/param_reader.h"
#include "environment/jump_environment.h"

namespace pronk::guided_jump {
namespace {

JumpEnvironment* self(void* instance) { return static_cast<JumpEnvironment*>(instance); }

void need(const void* instance, const void* pointer) {
  if (!instance || !pointer) throw InvalidArgument("called without an instance or a required pointer");
}

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const std::vector<pronk_param_decl>& decls = environmentParamDecls();
    const ParamReader read(params, param_count, decls.data(), static_cast<int32_t>(decls.size()));
    const EnvironmentSettings settings = EnvironmentSettings::read(read);
    std::string why;
    std::optional<LegModels> legs = legGeometryFromHost(host, &why);
    *instance = new JumpEnvironment(host, settings, std::move(legs), why);
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
  std::string rejection;
  const pronk_status status = guarded(error, error_size, [&] {
    need(instance, action);
    try {
      self(instance)->act(action);
    } catch (const Rejected& e) {
      rejection = e.what();
    }
  });
  if (status != PRONK_OK || rejection.empty()) return status;
  writeError(error, error_size, rejection.c_str());
  return PRONK_REJECTED;
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

pronk_status priorAction(void* instance, const double* observation, double* action, char* error, size_t error_size) {
  std::string infeasible;
  const pronk_status status = guarded(error, error_size, [&] {
    need(instance, observation);
    if (!action) throw InvalidArgument("no action buffer");
    const std::vector<double> a = self(instance)->priorAction(observation, &infeasible);
    std::copy(a.begin(), a.end(), action);
  });
  // A host before 1.4 takes any status but PRONK_OK for an error.
  if (status != PRONK_OK || infeasible.empty() || negotiatedAbiMinor() < 4) return status;
  writeError(error, error_size, infeasible.c_str());
  return PRONK_REJECTED;
}

void destroy(void* instance) { delete self(instance); }

// ABI 1.3: every metric this environment reports, declared, so that the host's
// table, results files and video take them from here (docs/results-format.md).
struct MetricTable {
  std::vector<std::string> names;  // owns the generated names (action_*, cost terms)
  std::vector<pronk_metric_decl> decls;
};

const MetricTable& metricTable() {
  static const MetricTable table = [] {
    MetricTable t;
    struct Plain {
      const char* name;
      uint32_t kind;
      const char* unit;
      const char* description;
      const char* column;
      const char* pairs_with;
    };
    const Plain plain[] = {
        {"planned_lift_off_time", PRONK_METRIC_TIME, "s", "the plan's lift-off", "lift-off s", "lift_off"},
        {"planned_apex_time", PRONK_METRIC_TIME, "s", "the plan's apex", "apex s", "apex_time"},
        // Beside the controller's touchdown, not the host's first contact: a toe that
        // brushes the ground just after lift-off is a contact but not the landing.
        {"planned_touchdown_time", PRONK_METRIC_TIME, "s", "the plan's touchdown on the target's surface",
         "touchdown s", "touchdown_time"},
        {"predicted_landing_x", PRONK_METRIC_VALUE, "m", "the plan's CoM landing point, start frame", "pred. x m",
         nullptr},
        {"predicted_landing_y", PRONK_METRIC_VALUE, "m", "the plan's CoM landing point, start frame", "pred. y m",
         nullptr},
        {"predicted_landing_z", PRONK_METRIC_VALUE, "m", "the plan's landing height above the take-off surface",
         nullptr, nullptr},
        {"predicted_rest_x", PRONK_METRIC_VALUE, "m",
         "where the plan's CoM comes to rest: its landing point carried on by the landing's stop, start frame",
         nullptr, nullptr},
        {"predicted_rest_y", PRONK_METRIC_VALUE, "m",
         "where the plan's CoM comes to rest: its landing point carried on by the landing's stop, start frame",
         nullptr, nullptr},
        {"planned_lift_off_x", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_y", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_z", PRONK_METRIC_VALUE, "m", "the plan's lift-off CoM, start frame", nullptr, nullptr},
        {"planned_lift_off_vx", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_lift_off_vy", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_lift_off_vz", PRONK_METRIC_VALUE, "m/s", "the plan's lift-off CoM velocity", nullptr, nullptr},
        {"planned_flight_time", PRONK_METRIC_VALUE, "s", "the plan's flight from lift-off to the target's surface",
         nullptr, nullptr},
        {"planned_apex_height", PRONK_METRIC_VALUE, "m", "the plan's CoM apex above standing", nullptr, nullptr},
        {"action_excess", PRONK_METRIC_VALUE, "1", "raw action beyond +-5 (the clip), summed", nullptr, nullptr},
        {"predicted_speed_shortfall", PRONK_METRIC_VALUE, "m/s",
         "the safety filter's torque check: lift-off speed the motors are predicted to miss", nullptr, nullptr},
        {"running_cost", PRONK_METRIC_VALUE, "1", "the reward's running (thrust) costs, summed", nullptr, nullptr},
        {"terminal_cost", PRONK_METRIC_VALUE, "1", "the reward's lift-off and touchdown costs, summed", nullptr,
         nullptr},
        {"cost_gate", PRONK_METRIC_VALUE, "1", "exp(-C^2 / 5), the gate the costs put on the landing reward", nullptr,
         nullptr},
        {"landing_reward", PRONK_METRIC_VALUE, "1", "R_lt, the landing-target reward before the gate", nullptr,
         nullptr},
        {"reward_error_xy", PRONK_METRIC_VALUE, "m", "the reward's horizontal landing error", nullptr, nullptr},
        {"reward_error_z", PRONK_METRIC_VALUE, "m", "the reward's vertical landing error", nullptr, nullptr},
        {"lift_off_time", PRONK_METRIC_TIME, "s", "the controller's flight phase began", nullptr, nullptr},
        {"apex_time", PRONK_METRIC_TIME, "s", "the CoM's vertical velocity turned negative", nullptr, nullptr},
        {"touchdown_time", PRONK_METRIC_TIME, "s", "the controller's landing phase began", nullptr, nullptr},
        {"touchdown_roll", PRONK_METRIC_VALUE, "rad", "trunk roll at touchdown (ZYX, start frame)", nullptr, nullptr},
        {"touchdown_pitch", PRONK_METRIC_VALUE, "rad", "trunk pitch at touchdown (ZYX, start frame)", nullptr,
         nullptr},
        {"lift_off_velocity_error", PRONK_METRIC_VALUE, "m/s", "|CoM velocity at lift-off - the plan's|", nullptr,
         nullptr},
        {"lift_off_position_error", PRONK_METRIC_VALUE, "m", "|CoM at lift-off - the plan's|", nullptr, nullptr},
        {"lift_off_body_rate_x", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"lift_off_body_rate_y", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"lift_off_body_rate_z", PRONK_METRIC_VALUE, "rad/s", "the whole body's I^-1 L at lift-off, start frame",
         nullptr, nullptr},
        {"rest_time", PRONK_METRIC_TIME, "s", "after touchdown, the CoM's speed stays below 0.05 m/s from here",
         nullptr, nullptr},
    };
    // Generated names first, so that their storage does not move afterwards.
    const jump::RewardBreakdown breakdown;
    for (const jump::RewardTerm* term : breakdown.terms()) t.names.push_back(term->name);
    for (int i = 0; i < jump::kActionSize; ++i) {
      t.names.push_back(std::string("action_") + jump::actionParameterName(static_cast<jump::ActionParameter>(i)));
    }
    for (const Plain& m : plain) {
      t.decls.push_back({sizeof(pronk_metric_decl), m.name, m.kind, m.unit, m.description, m.column, m.pairs_with});
    }
    const size_t terms = breakdown.terms().size();
    for (size_t k = 0; k < terms; ++k) {
      t.decls.push_back({sizeof(pronk_metric_decl), t.names[k].c_str(), PRONK_METRIC_PENALTY, "1",
                         "a cost term of the paper's reward (weight x value)", nullptr, nullptr});
    }
    for (int i = 0; i < jump::kActionSize; ++i) {
      const auto p = static_cast<jump::ActionParameter>(i);
      t.decls.push_back({sizeof(pronk_metric_decl), t.names[terms + i].c_str(), PRONK_METRIC_VALUE,
                         jump::actionParameterUnit(p), "the mapped action parameter", nullptr, nullptr});
    }
    return t;
  }();
  return table;
}

const char* const kTaskNames[kObservationSize] = {"x", "y", "z", "yaw", "roll", "pitch"};
// The mirror image across the start's x-z plane: y, yaw and roll change sign.
const double kTaskMirror[kObservationSize] = {1, -1, 1, -1, -1, 1};

const pronk_marker_decl kMarkers[] = {
    {sizeof(pronk_marker_decl), PRONK_MARKER_ARC, "planned flight",
     {"planned_lift_off_x", "planned_lift_off_y", "planned_lift_off_z", "planned_lift_off_vx", "planned_lift_off_vy",
      "planned_lift_off_vz", "planned_flight_time"}},
    // Where the plan comes to rest, as the target marks where the trunk should.
    {sizeof(pronk_marker_decl), PRONK_MARKER_POINT, "predicted landing",
     {"predicted_rest_x", "predicted_rest_y", "predicted_landing_z", nullptr, nullptr, nullptr, nullptr}},
};

const pronk_environment_ops kOps = {sizeof(pronk_environment_ops), reset, act, step, finish, destroy, priorAction};

}  // namespace

const pronk_factory* jumpEnvironmentFactory() {
  static const pronk_factory factory = {
      sizeof(pronk_factory),
      PRONK_FACTORY_ENVIRONMENT,
      "jump",
      "one jump to a target per episode: 6 target numbers in, 13 raw jump parameters, the paper's reward; "
      "safety filter before the jump; prior_action is the analytic ballistic planner",
      static_cast<int32_t>(environmentParamDecls().size()),
      environmentParamDecls().data(),
      0,
      kObservationSize,
      jump::kActionSize,
      kControlPeriod,
      create,
      nullptr,
      &kOps,
      static_cast<int32_t>(metricTable().decls.size()),
      metricTable().decls.data(),
      kTaskNames,
      kObservationSize,
      static_cast<int32_t>(std::size(kMarkers)),
      kMarkers,
      kTaskMirror,
  };
  return &factory;
}

}  // namespace pronk::guided_jump
