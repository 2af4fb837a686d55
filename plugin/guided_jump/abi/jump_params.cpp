// The declaration tables of controller `guided_jump` and environment `jump`:
// the phases' own parameters (control/: each phase declares its own), then each
// factory's.
#include "abi/jump_params.h"

#include "control/jump_controller.h"
#include "environment/jump_environment.h"

namespace pronk::guided_jump {
namespace {

constexpr uint32_t kDeclSize = sizeof(pronk_param_decl);

}  // namespace

const std::vector<pronk_param_decl>& controllerParamDecls() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d = JumpSettings::parameters();
    // The action is a vector of any size so that its default can be empty ("no
    // action: hold the stance"); create() accepts 0 or 13 numbers.
    d.push_back({kDeclSize, "action", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
                 "empty: hold the stance; or the 13 physical jump parameters T_th r_p theta_p r_v theta_v "
                 "k d roll pitch yaw roll_rate pitch_rate yaw_rate (s, m, rad, m/s, rad, 1, m, rad, rad/s)"});
    d.push_back({kDeclSize, "landing_height", PRONK_PARAM_REAL, 0, -5.0, 5.0, 0, "0", "m",
                 "the landing surface's height above the take-off surface (when the legs extend)"});
    return d;
  }();
  return decls;
}

const std::vector<pronk_param_decl>& environmentParamDecls() {
  static const std::vector<pronk_param_decl> decls = [] {
    std::vector<pronk_param_decl> d = JumpSettings::parameters();
    const std::vector<pronk_param_decl>& own = EnvironmentSettings::parameters();
    d.insert(d.end(), own.begin(), own.end());
    return d;
  }();
  return decls;
}

}  // namespace pronk::guided_jump
