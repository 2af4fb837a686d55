// Scenario files: what a user writes to say which robot jumps where, on what
// terrain, under which simulation settings. This header is the in-memory form;
// scenario_file.cpp reads it from XML (format: docs/scenario-format.md).
#pragma once

#include <array>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pronk/error.h"

namespace pronk {

using Vec3 = std::array<double, 3>;

// A parameter as written in the file, for a plugin factory to check.
struct ParamSetting {
  std::string name;
  std::string value;
  SourceLocation where;
};
// Puts `setting` into `params`: it replaces the setting of the same name (value
// and location, so that an error in it points where it was set) or is appended.
void setParam(std::vector<ParamSetting>& params, const ParamSetting& setting);

struct ControllerSpec {
  std::string factory;              // e.g. "guided_jump", or the built-in "stand"
  std::string plugin;               // optional library name or path ("" = search all)
  std::vector<ParamSetting> params;
  SourceLocation where;
};

// The RL task a policy drives (`pronk run --policy`): an environment factory
// with its parameters. `policy` is the scenario's default policy: "" (none: the
// command line must name one), "ballistic" (the environment's analytic prior),
// or a policy file (resolved absolute path).
struct EnvironmentSpec {
  std::string factory;              // e.g. "jump"
  std::string plugin;               // optional library name or path ("" = search all)
  std::vector<ParamSetting> params;
  std::string policy;
  SourceLocation where;
};

// Gains and limits for the joints; per-joint overrides by exact joint name.
struct JointSettings {
  double kp = 100;        // N m/rad
  double kd = 2;          // N m s/rad
  double armature = 0;    // kg m^2, reflected rotor inertia (see docs/physics.md)
  double damping = -1;    // N m s/rad viscous joint damping; <0: keep the URDF's
  double effort_scale = 1; // multiplies the URDF effort limits
  struct Override {
    std::string joint;
    std::optional<double> kp, kd, effort, velocity;
    SourceLocation where;
  };
  std::vector<Override> overrides;
};

struct PlatformSpec {
  std::string name;
  std::string urdf;                          // resolved absolute path
  SourceLocation urdf_where;
  std::vector<std::string> package_paths;    // resolved absolute directories
  std::vector<std::string> feet;             // foot links, in controller leg order
  SourceLocation feet_where;
  // Initial pose. The joint configuration is per leg (repeated for every leg,
  // in the leg's joint order from the trunk outwards), or per joint by name.
  std::vector<double> stance;                // e.g. {0, 0.75, -1.5}
  std::map<std::string, double> joint_positions;
  std::map<std::string, SourceLocation> joint_position_where;  // same keys
  SourceLocation initial_where;              // the <initial> element (stance, pose)
  Vec3 base_position{0, 0, 0};               // m; z ignored when on_ground
  bool on_ground = true;                     // set base z so the feet touch the terrain
  double base_yaw = 0;                       // rad
  double trunk_mass_offset = 0;              // kg added to the root body (sweeps)
  // kg added to the root body that the host does not report: plugins' total_mass
  // (and the built-in controllers) keep the mass without it (the paper's MV test).
  double unreported_trunk_mass = 0;
  JointSettings joints;
  SourceLocation joints_where;               // the <joints> element
  ControllerSpec controller;
  SourceLocation where;
};

// Foot contact law. "stiction": Hunt-Crossley normal force plus an
// elasto-plastic bristle friction (docs/physics.md).
struct ContactSpec {
  std::string model = "stiction";
  double stiffness = 5e4;               // N/m, normal
  double dissipation = 0.75;            // s/m, Hunt-Crossley c
  double mu_static = 0.8;
  double mu_dynamic = 0.8;
  double tangential_stiffness = 2e4;    // N/m, bristle spring
  double tangential_damping = 252;      // N s/m, bristle damper
  // Fixed-step integrators only: the contact's springs and dampers are taken
  // implicitly over one step (each foot as its apparent mass, docs/physics.md),
  // so that steps near the control period stay stable.
  bool implicit = false;
  SourceLocation where;                 // the <contact> element (file only if absent)
};

// The longest episode any setting may ask for: one hour simulated.
inline constexpr double kMaxEpisodeSeconds = 3600;

struct SimSpec {
  double control_rate = 1000;                // Hz
  std::string integrator = "semi_explicit_euler2";  // or semi_explicit_euler, runge_kutta_merson ...
  double step = 2e-4;                        // s, fixed-step integrators
  double accuracy = 1e-3;                    // error-controlled integrators
  double flight_max_step = 5e-4;             // s, longest error-controlled step while no foot touches
  double duration = 1.5;                     // s per episode, at most kMaxEpisodeSeconds
  // An episode whose integrator needs more steps than this per simulated
  // second fails as `step_budget` (a model too stiff to simulate), not a hang.
  double max_steps_per_second = 5e5;
  Vec3 gravity{0, 0, -9.81};
  ContactSpec contact;
  SourceLocation where;
};

// A static box of terrain. Size is full extents (not half sizes), position is
// the box centre in the world, yaw about z.
struct TerrainBox {
  std::string name;
  Vec3 size{1, 1, 0.1};
  Vec3 position{0, 0, 0};
  double yaw = 0;
  std::optional<double> mu;   // overrides the contact friction on this box
  SourceLocation where;
};

enum class StepPlatforms { none, edge, apex };

// The paper's terrain for up and down jumps (reference-implementation.md,
// section 6): the robot takes off from a surface with no edge near it; at the
// apex of its flight a 2 m x 2 m platform, centred on the target and turned to
// its heading, appears with its top at the target's height, or lower, 5 cm
// under the lowest foot, when the feet do not clear the target height, so that
// no jump ever meets a platform's side. Missing the platform means falling to
// the ground 0.5 m below the start surface.
struct ApexPlatform {
  double x = 0, y = 0;     // world, m: the target
  double yaw = 0;          // rad, the target's world heading
  double top = 0;          // world z of the target's surface, m
  double floor = 0;        // world z of the ground plane once the platform appears, m
  double size = 2.0;       // m, square
  double clearance = 0.05; // m under the lowest foot's sole when the feet do not clear `top`
};

// A target pose relative to the start (x forward, y left, z up, of the
// robot's initial heading), angles in rad.
struct TargetSpec {
  std::string name;
  double x = 0, y = 0, z = 0, yaw = 0, roll = 0, pitch = 0;
  // Optional pass/fail bounds for scenario tests: a jump whose landing misses by
  // more is reported as "missed" (and `pronk run` exits with kEpisodeFailed).
  std::optional<double> tolerance_xy;   // m, horizontal landing error
  std::optional<double> tolerance_yaw;  // rad, |yaw error|
  SourceLocation where;
};

// Sweeps expand into more episodes: a grid, seeded random samples in a region,
// or variations of a parameter.
struct SweepAxis {
  std::string variable;          // target.x, target.yaw, platform.trunk_mass_offset, joints.damping ...
  std::vector<double> values;    // grid / vary: explicit values
  double min = 0, max = 0;       // random: uniform range
  SourceLocation where;
};

struct SweepSpec {
  enum class Kind { Grid, Random, Vary } kind = Kind::Grid;
  std::string name;
  std::vector<SweepAxis> axes;
  int count = 0;                 // random
  unsigned long seed = 0;        // random
  SourceLocation where;
};

struct CameraSpec {
  std::string mode = "side";     // side | follow | top | fixed
  Vec3 position{0, -2, 0.6};     // fixed
  Vec3 look_at{0.3, 0, 0.2};     // fixed
  double fovy_deg = 45;
  SourceLocation where;
};

struct RenderSpec {
  int width = 1280, height = 720;
  double fps = 30;
  double speed = 1;              // playback speed, 0.25 = slow motion
  std::string output;            // a suggested relative file name, used under --out by `--video` alone ("" = none)
  CameraSpec camera;
  SourceLocation where;
};

// <training>: what `pronk train` does with the scenario (docs/scenario-format.md,
// docs/training.md). Targets are drawn uniformly from the region; heights use
// the terrain's step_platforms. Angles in rad.
struct TrainingRange {
  double min = 0, max = 0;
};

struct TrainingSpec {
  // The task region, relative to the start as a target's x, y, z, yaw.
  TrainingRange x, y, z, yaw;
  // Share of the targets drawn flat (z = 0) in a region with heights: the flat
  // ground a height range meets only at one point gets its own samples.
  double flat_share = 0.0;
  SourceLocation region_where;
  int iterations = 100;
  int jumps_per_iteration = 256;
  unsigned long seed = 1;
  int checkpoint_every = 10;           // iterations between checkpoints (and policy files)
  // Hidden layers of the actor (the residual's MLP) and of the critic.
  std::vector<int> actor_hidden_sizes{512, 256, 128};
  std::vector<int> critic_hidden_sizes{512, 256, 128};
  // PPO (pronk/ppo.h); the rest of PpoConfig keeps its defaults.
  int epochs = 10;
  int minibatches = 4;
  double learning_rate = 1e-3;
  double clip = 0.2;
  double entropy_coefficient = 0.01;
  double desired_kl = 0.01;
  double initial_std = 0.3;            // of the Gaussian over the (residual) raw action
  // A fixed seeded target set, drawn from its own stream, that the mean policy
  // jumps every `validate_every` iterations.
  int validation_count = 100;
  unsigned long validation_seed = 1000;
  int validate_every = 10;
  // false: PPO fits the critic only and leaves the actor (and its std) to the
  // hindsight fit (<ppo actor="false">).
  bool ppo_actor = true;
  // Guidance: the planner as prior (action = prior_action + residual, the
  // residual's last layer zero at the start); the critic fitted to the first
  // batch before the first actor update; hindsight relabelling (the actor's
  // mean fitted to the newest hindsight_samples (achieved task, action) pairs,
  // hindsight_epochs passes per iteration); mirror symmetry (each hindsight pair of an
  // aim correction also enters in its mirror image, by the environment's task mirror).
  bool residual = true;
  // An aim correction instead (<guidance aim="true" residual="false">): the
  // network's output offsets the observation the prior plans for.
  bool aim = false;
  bool critic_warmup = true;
  int critic_warmup_epochs = 20;
  bool hindsight = false;
  int hindsight_epochs = 5;
  int hindsight_samples = 16384;
  int hindsight_minibatch = 256;
  double hindsight_learning_rate = 1e-3;
  // A pair is kept only when the prior at the achieved task differs from the
  // prior at the target by at most this (raw units, any action): the planner's
  // candidate search makes its action piecewise, and a residual is only
  // meaningful within the piece it was taken in.
  double hindsight_prior_step = 0.5;
  bool mirror = false;
  // Oversampling (<guidance oversample>): this share of each iteration's targets
  // is drawn again from the recent targets that failed or were refused (the
  // newest jumps_per_iteration of them); 0: none.
  double oversample = 0.0;
  SourceLocation where;
};

// <expectations>: what `pronk check` requires of a set's jumps (docs/scenario-format.md).
// Each bound set becomes one check, reported (and in JUnit, one test case) on its own.
struct ExpectSpec {
  std::string set;     // "targets" or a sweep's name; "" when `target` is set
  std::string target;  // one target of <targets> by name; "" for a whole set
  std::optional<double> max_error;         // m: every jump lands within it (a failure or refusal misses)
  std::optional<double> max_yaw_error;     // rad: every jump lands with |yaw error| within it
  std::optional<double> within, share;     // m, 0..1: at least `share` of the jumps land within `within`
  std::optional<double> max_mean_error;    // m, over the landed jumps
  std::optional<double> max_median_error;  // m, over the landed jumps
  std::optional<double> max_failed;        // 0..1: share of the jumps that fail
  std::optional<double> max_rejected;      // 0..1: share refused by the safety filter
  bool standing = false;                   // every jump lands and ends standing
  SourceLocation where;
};

// A new field goes into applyCase's copy too, unless it lists cases.
struct Scenario {
  std::string file;              // absolute path of the top-level file
  std::string name;
  int version = 1;
  PlatformSpec platform;
  SimSpec sim;
  std::vector<TerrainBox> terrain;
  double ground_height = 0;      // m, the ground plane z
  bool ground = true;            // false: no ground plane (only boxes)
  // <terrain step_platforms="...">: how a case whose target has z != 0 gets its
  // height (applyCase). "true" (edge): a box of height |z|, a landing platform
  // for up targets, a start platform for down targets. "apex": the paper's test
  // terrain, a landing platform that appears under the robot at the apex of its
  // flight (ApexPlatform).
  StepPlatforms step_platforms = StepPlatforms::none;
  std::optional<ApexPlatform> apex_platform;   // set by applyCase for an apex case
  std::optional<EnvironmentSpec> environment;  // with it, <controller> is optional
  std::vector<TargetSpec> targets;
  std::vector<SweepSpec> sweeps;
  std::optional<RenderSpec> render;
  std::optional<TrainingSpec> training;        // `pronk train`; needs an <environment>
  std::vector<ExpectSpec> expectations;        // `pronk check`; needs an <environment>
};

// The names the format accepts, kept here and nowhere else (the scenario reader
// rejects any other; docs/scenario-format.md explains each).
inline constexpr std::array<std::string_view, 6> kIntegrators{
    "semi_explicit_euler", "semi_explicit_euler2", "runge_kutta_merson",
    "runge_kutta_3",       "explicit_euler",       "verlet"};
inline constexpr std::array<std::string_view, 1> kContactModels{"stiction"};
inline constexpr std::array<std::string_view, 4> kCameraModes{"side", "follow", "top", "fixed"};

// A quantity a sweep may vary, with the SI unit its values are stored in
// ("rad" values are written in the file's angle unit and converted).
struct SweepVariable {
  std::string_view name;
  std::string_view unit;
};
inline constexpr std::array<SweepVariable, 13> kSweepVariables{{
    {"target.x", "m"},
    {"target.y", "m"},
    {"target.z", "m"},
    {"target.yaw", "rad"},
    {"target.roll", "rad"},
    {"target.pitch", "rad"},
    {"platform.trunk_mass_offset", "kg"},
    {"platform.unreported_trunk_mass", "kg"},
    {"joints.damping", "N m s/rad"},
    {"joints.kp", "N m/rad"},
    {"joints.kd", "N m s/rad"},
    {"contact.mu_static", ""},
    {"terrain.edge", ""},
}};

// One episode of a sweep (or of the target list): its target and the values it
// gives other variables.
struct EpisodeCase {
  std::string label;   // "target forward", "grid region #12" ...
  TargetSpec target;
  std::vector<std::pair<std::string, double>> assignments;  // non-target sweep variables
};

// The scenario's targets, one case each (with no targets: one case at the start pose).
std::vector<EpisodeCase> targetCases(const Scenario& scenario);
// The cases of the sweep named `name`, in their stable order (grids: last axis
// fastest; random: drawn in order from the seed with a portable generator). A
// sweep that sets no target variable runs every target of the scenario per case.
// Throws InputError naming the known sweeps for an unknown name.
std::vector<EpisodeCase> sweepCases(const Scenario& scenario, const std::string& name);
// Where the robot stands: the points of its legs that come nearest the ground
// (its feet and knees), in its trunk frame at the platform's stance
// (World::footprint()). The step platforms' edges keep clear of them.
struct Footprint {
  std::vector<Vec3> points;  // m, trunk frame
};

// The scenario with a case's non-target assignments applied and, with
// step_platforms="true", the case's platform added: a box |z| high, turned to the
// jump direction, 1.2 m wide, whose edge lies between the two stances: at least
// kStepEdgeClearance beyond every point of the start's footprint and short of
// every point of the landing's (turned to the target's heading), along the jump
// direction. The
// case's terrain.edge (0 ... 1, default 0.5) places it in that room: 0 next to
// the start feet, 1 next to the landing feet. An up target's platform runs from
// the edge to 0.6 m beyond the target; a down target's start platform from 0.8 m
// behind the start to the edge, and the robot starts on it. Two stances with no
// room between them (a target too near the start) is a NoRoomForEdge naming the
// target and the overlap: a target refused, as an infeasible jump is. With
// step_platforms="apex", apex_platform set instead (no box is added). The
// result holds no targets, sweeps, training nor expectations: a case needs none.
constexpr double kStepEdgeClearance = 0.05;  // m along the jump, from a foot's centre to the edge
class NoRoomForEdge : public InputError {
 public:
  using InputError::InputError;
};
Scenario applyCase(const Scenario& scenario, const EpisodeCase& episode, const Footprint& footprint);

// The only major version of the format this build reads.
constexpr int kScenarioFormatVersion = 1;

// Reads and validates a scenario file (and the files it includes). Throws
// InputError("file:line: message") on the first error.
Scenario loadScenario(const std::string& path);

// Reads a file meant to be included (root <scenario_part>) on its own, to check
// it: every element it holds is validated the same way, nothing is required.
Scenario loadScenarioPart(const std::string& path);
// True when the file parses and its root element is <scenario_part>.
bool isScenarioPart(const std::string& path);

}  // namespace pronk
