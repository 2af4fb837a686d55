// Controller `guided_jump`: with no `action` it holds the stance (control/hold_controller.h);
// with an action it jumps: stand, thrust, explosive, flight, descend, landing
// (control/jump_phases.h).
#include <array>
#include <new>

#include "abi/abi_boundary.h"
#include "abi/factories.h"
#include "abi/plugin_params.h"
#include "control/hold_controller.h"
#include "control/jump_phases.h"

namespace pronk::guided_jump {
namespace {

constexpr int32_t kHoldParamCount = sizeof(kHoldParamDecls) / sizeof(kHoldParamDecls[0]);
constexpr int32_t kParamCount = kHoldParamCount + 6;

// The stance controller's parameters, then the jump's. The action is a vector of
// any size so that its default can be empty ("no action: hold the stance");
// create() accepts 0 or 13 numbers.
std::array<pronk_param_decl, kParamCount> makeParamDecls() {
  std::array<pronk_param_decl, kParamCount> d{};
  for (int32_t i = 0; i < kHoldParamCount; ++i) d[i] = kHoldParamDecls[i];
  d[kHoldParamCount + 0] = {sizeof(pronk_param_decl), "action", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
                            "empty: hold the stance; or the 13 physical jump parameters T_th r_p theta_p r_v theta_v "
                            "k d roll pitch yaw roll_rate pitch_rate yaw_rate (s, m, rad, m/s, rad, 1, m, rad, rad/s)"};
  d[kHoldParamCount + 1] = {sizeof(pronk_param_decl), "start_delay", PRONK_PARAM_REAL, 0, 0.0, 60.0, 0, "0.2", "s",
                            "standing time before the thrust"};
  d[kHoldParamCount + 2] = {sizeof(pronk_param_decl), "feedforward", PRONK_PARAM_STRING, 0, 1.0, -1.0, 0, "gravity", "",
                            kFeedforwardDoc};
  d[kHoldParamCount + 3] = {sizeof(pronk_param_decl), "flight_kp_division", PRONK_PARAM_REAL, 0, 1.0, 100.0, 0, "3", "",
                            "Kp is divided by this from lift-off to touchdown"};
  d[kHoldParamCount + 4] = {sizeof(pronk_param_decl), "landing_height", PRONK_PARAM_REAL, 0, -5.0, 5.0, 0, "0", "m",
                            "the landing surface's height above the take-off surface (when the legs extend)"};
  d[kHoldParamCount + 5] = {sizeof(pronk_param_decl), "momentum_gain", PRONK_PARAM_REAL, 0, 0.0, 100.0, 0, "0", "1/s",
                            "thrust: the trunk turns against the touchdown attitude error the whole-body angular "
                            "momentum predicts, at this rate per rad/s (0: off, the paper's)"};
  return d;
}

const std::array<pronk_param_decl, kParamCount> kParamDecls = makeParamDecls();

JumpController* self(void* instance) { return static_cast<JumpController*>(instance); }

JumpSettings readJumpSettings(const ParamReader& read) {
  JumpSettings s;
  s.hold = readHoldSettings(read);
  s.action = read.vector("action");
  s.start_delay = read.real("start_delay");
  s.feedforward = feedforwardFromName(read.string("feedforward"));
  s.flight_kp_division = read.real("flight_kp_division");
  s.landing_height = read.real("landing_height");
  s.momentum_gain = read.real("momentum_gain");
  return s;
}

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const ParamReader read(params, param_count, kParamDecls.data(), kParamCount);
    *instance = new JumpController(host, readJumpSettings(read));
  });
}

pronk_status reset(void* instance, const pronk_robot_state* state, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance || !state) throw InvalidArgument("reset() needs an instance and a state");
    self(instance)->reset(*state);
  });
}

pronk_status compute(void* instance, const pronk_robot_state* state, double* torque, char* error,
                     size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance || !state) throw InvalidArgument("compute() needs an instance and a state");
    self(instance)->compute(*state, torque);
  });
}

void destroy(void* instance) { delete self(instance); }

const pronk_controller_ops kOps = {sizeof(pronk_controller_ops), reset, compute, destroy};

const pronk_factory kFactory = {
    sizeof(pronk_factory),
    PRONK_FACTORY_CONTROLLER,
    "guided_jump",
    "guided jump controller: with an action, CoM thrust along the paper's Bezier + UARM plan, flight tuck, "
    "landing; without one, stance PD + gravity compensation over the feet in contact",
    kParamCount,
    kParamDecls.data(),
    0,  // any robot with three joints per leg (checked in create)
    0,
    0,
    kControlPeriod,
    create,
    &kOps,
    nullptr,
};

}  // namespace

const pronk_factory* guidedJumpControllerFactory() { return &kFactory; }

}  // namespace pronk::guided_jump
