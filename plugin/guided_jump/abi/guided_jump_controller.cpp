// Controller `guided_jump`: with no `action` it holds the stance (control/hold_controller.h);
// with an action it jumps: stand, thrust, explosive, flight, descend, landing
// (control/jump_controller.h).
#include <new>
#include <vector>

#include "abi/abi_boundary.h"
#include "abi/factories.h"
#include "abi/host_leg_geometry.h"
#include "abi/jump_params.h"
#include "control/param_reader.h"
#include "control/hold_controller.h"
#include "control/jump_controller.h"

namespace pronk::guided_jump {
namespace {

JumpController* self(void* instance) { return static_cast<JumpController*>(instance); }

JumpSettings readJumpSettings(const ParamReader& read) {
  JumpSettings s;
  JumpSettings::read(read, &s);
  s.action = read.vector("action");
  s.landing_height = read.real("landing_height");
  return s;
}

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const std::vector<pronk_param_decl>& decls = controllerParamDecls();
    const ParamReader read(params, param_count, decls.data(), static_cast<int32_t>(decls.size()));
    JumpSettings settings = readJumpSettings(read);
    settings.legs = legGeometryFromHost(host, nullptr);
    *instance = new JumpController(host, settings);
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

}  // namespace

const pronk_factory* guidedJumpControllerFactory() {
  static const pronk_factory factory = {
      sizeof(pronk_factory),
      PRONK_FACTORY_CONTROLLER,
      "guided_jump",
      "guided jump controller: with an action, CoM thrust along the paper's Bezier + UARM plan, flight tuck, "
      "landing; without one, stance PD + gravity compensation over the feet in contact",
      static_cast<int32_t>(controllerParamDecls().size()),
      controllerParamDecls().data(),
      0,  // any robot with three joints per leg (checked in create)
      0,
      0,
      kControlPeriod,
      create,
      &kOps,
      nullptr,
      0, nullptr, nullptr, 0, 0, nullptr,  // 1.3 declarations: environments only
  };
  return &factory;
}

}  // namespace pronk::guided_jump
