// The declaration tables of controller `guided_jump` and environment `jump`:
// the phases' own parameters (control/: each phase declares its own), then each
// factory's.
#include "abi/jump_params.h"

#include "control/jump_controller.h"

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
    const std::vector<pronk_param_decl> own = {
        {kDeclSize, "duration", PRONK_PARAM_REAL, 0, 0.01, 60.0, 0, "1.5", "s", "episode length, from reset"},
        // Empty: derived from the robot (action_mapping.h, scaledActionRanges).
        {kDeclSize, "action_min", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
         "lower ends of the 13 action ranges (T_th r_p theta_p r_v theta_v k d roll pitch yaw and rates; "
         "s, m, rad, m/s, rad, 1, m, rad, rad/s); empty: the paper's Go1 table with r_p and d scaled by the "
         "robot's leg length (thigh + calf) over the Go1's 0.426 m"},
        {kDeclSize, "action_max", PRONK_PARAM_VECTOR, 0, 1.0, -1.0, 0, "", "SI",
         "upper ends of the 13 action ranges; empty: derived as action_min"},
        {kDeclSize, "raw_limit", PRONK_PARAM_REAL, 0, 0.01, 100.0, 0, "5", "",
         "raw policy outputs are clipped to +-this before the affine map"},
        {kDeclSize, "friction_coefficient", PRONK_PARAM_REAL, 0, 0.0, 10.0, 0, "0.8", "",
         "mu of the reward's friction-cone term"},
        {kDeclSize, "workspace_z", PRONK_PARAM_VECTOR, 0, -10.0, 10.0, 0, "", "m",
         "trunk height band (2 numbers) of the reward's workspace term; empty: the paper's Go1 band 0.15 0.40 "
         "scaled by the robot's leg length over the Go1's 0.426 m (the paper's Aliengo: 0.20 0.60)"},
        {kDeclSize, "error_scale", PRONK_PARAM_REAL, 0, 0.001, 10.0, 0, "0.1", "m",
         "sigma_e of the landing reward exp(-e / sigma_e)"},
        {kDeclSize, "workspace_check", PRONK_PARAM_INT, 0, 0.0, 1.0, 0, "1", "",
         "safety filter and planner: 1 keeps every stance foot reachable on the thrust path"},
        {kDeclSize, "knee_clearance", PRONK_PARAM_REAL, 0, -1.0, 1.0, 0, "0.01", "m",
         "safety filter and planner (with workspace_check): every knee stays this far above its stance foot's "
         "centre on the thrust path (-1: off)"},
        {kDeclSize, "max_speed_shortfall", PRONK_PARAM_REAL, 0, 0.0, 10.0, 0, "0.1", "m/s",
         "safety filter and planner: the lift-off speed the motors are predicted to miss by at most (the "
         "torque check, under the 'motor' model)"},
        {kDeclSize, "sideways_roll_rate_gain", PRONK_PARAM_REAL, 0, -10.0, 10.0, 0, "1.5", "1/m",
         "planner: lift-off roll rate (rad/s) per m/s of lift-off velocity across the trunk, clamped into the "
         "roll rate range (0: none)"},
    };
    d.insert(d.end(), own.begin(), own.end());
    return d;
  }();
  return decls;
}

}  // namespace pronk::guided_jump
