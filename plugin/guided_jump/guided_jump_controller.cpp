// Controller `guided_jump`. For now it holds the stance (hold_controller.h);
// the jump's phases (thrust, flight, landing) come with the jump method.
#include <new>

#include "abi_boundary.h"
#include "factories.h"
#include "hold_controller.h"
#include "plugin_params.h"

namespace pronk::guided_jump {
namespace {

constexpr int32_t kParamCount = sizeof(kHoldParamDecls) / sizeof(kHoldParamDecls[0]);

HoldController* self(void* instance) { return static_cast<HoldController*>(instance); }

pronk_status create(const pronk_host_api* host, const pronk_param_value* params, int32_t param_count,
                    void** instance, char* error, size_t error_size) {
  return guarded(error, error_size, [&] {
    if (!instance) throw InvalidArgument("no instance pointer");
    *instance = nullptr;
    const ParamReader read(params, param_count, kHoldParamDecls, kParamCount);
    *instance = new HoldController(host, readHoldSettings(read));
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
    "guided jump controller; for now holds the stance: joint PD + gravity compensation over the feet in contact",
    kParamCount,
    kHoldParamDecls,
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
