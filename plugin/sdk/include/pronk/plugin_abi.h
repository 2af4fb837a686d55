/*
 * pronk plugin ABI (C, stable across compilers and C++ standard libraries).
 *
 * A plugin is a shared library exporting exactly one entry point,
 * `pronk_plugin_query`. The host passes the ABI version it speaks; the plugin
 * rejects a different major version and answers with the highest minor it
 * supports that is not above the host's (Vulkan-style negotiation). It fills a
 * manifest naming its factories. Factories come in two kinds:
 *   - controller:  state -> joint torques, one call per control tick;
 *   - environment: an RL task around a controller (observation, one action per
 *                  episode, reward at the end).
 *
 * Rules that keep the ABI stable:
 *   - every struct that crosses the boundary starts with `uint32_t struct_size`
 *     set by whoever allocates it; fields are only ever appended. A reader uses
 *     the fields that fit in min(struct_size, sizeof(what it knows)) and treats
 *     the rest as zero / NULL;
 *   - an array of size-prefixed structs (pronk_factory::params) is contiguous
 *     and every entry carries the same struct_size, which is the array's stride:
 *     a reader steps by the first entry's struct_size, never by its own sizeof;
 *   - the one exception is pronk_param_value, a name/value pair frozen at two
 *     pointers: it never grows, so it carries no struct_size;
 *   - no C++ types and no exceptions cross the boundary: functions return a
 *     pronk_status and write a message into a caller-owned buffer;
 *   - strings are UTF-8, NUL-terminated, owned by whoever allocated them and
 *     valid for the lifetime stated on each field;
 *   - a function given (char* error, size_t error_size) writes, on failure, a
 *     NUL-terminated message truncated to error_size bytes (nothing when
 *     error_size is 0).
 *
 * Threads: pronk_plugin_query is called once per load. create() may be called
 * from several threads at once, and different instances may run on different
 * threads at once; one instance is only ever used by one thread at a time. So a
 * plugin keeps its mutable state in its instances, not in globals.
 *
 * Frames and units: world frame is Z-up, gravity along -z; SI units (m, s, kg,
 * rad, N, N m). Quaternions are (w, x, y, z). Joint vectors are in the
 * controller order: legs in the order of the scenario's foot list, each leg's
 * actuated joints from the trunk outwards (hip, thigh, calf for a quadruped).
 *
 * Version history:
 *   1.0  first version.
 *   1.1  PRONK_REJECTED; pronk_host_api::report_metric; pronk_environment_ops::prior_action.
 *   1.2  pronk_host_api::centroidal_momentum.
 *   1.3  pronk_factory::metrics, task_names, markers: an environment declares as data
 *        the metrics it reports, the layout of its task vector and the markers a
 *        video may draw, so that a host's tables, files and videos name none of them.
 *   1.4  prior_action may return PRONK_REJECTED after writing its best try: the
 *        environment expects act() to refuse that action (a plugin returns it only
 *        when it negotiated 1.4 or later).
 *   1.5  pronk_param_decl::platform_default: a parameter whose value, when the scenario
 *        leaves it out, is the platform's (its stance, its joint gains), so that a
 *        robot is described once, in its platform file. pronk_factory::task_mirror:
 *        an environment whose task is symmetric under the mirror across the robot's
 *        sagittal plane says how each task number changes sign.
 *   1.6  pronk_host_api::terrain_top: the terrain's top surface under a point, so
 *        that a plugin can see the boxes it stands on and jumps to.
 * A later minor version only appends fields and functions; a plugin that
 * negotiated 1.n must not read what 1.(n+1) added.
 */
#ifndef PRONK_PLUGIN_ABI_H
#define PRONK_PLUGIN_ABI_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PRONK_ABI_MAJOR 1u
#define PRONK_ABI_MINOR 6u
#define PRONK_ABI_VERSION(major, minor) ((((uint32_t)(major)) << 16) | ((uint32_t)(minor)&0xFFFFu))
#define PRONK_ABI_VERSION_MAJOR(v) (((uint32_t)(v)) >> 16)
#define PRONK_ABI_VERSION_MINOR(v) (((uint32_t)(v)) & 0xFFFFu)

/* Name of the single exported entry point, for dlsym. */
#define PRONK_PLUGIN_ENTRY_NAME "pronk_plugin_query"

#if defined(__GNUC__)
#define PRONK_PLUGIN_EXPORT __attribute__((visibility("default")))
#else
#define PRONK_PLUGIN_EXPORT
#endif

typedef enum pronk_status {
  PRONK_OK = 0,
  PRONK_ERROR_INVALID_ARGUMENT = 1, /* a parameter or input is out of its domain */
  PRONK_ERROR_VERSION = 2,          /* ABI major mismatch */
  PRONK_ERROR_FAILED = 3,           /* the call could not do its work; see message */
  PRONK_ERROR_UNSUPPORTED = 4,      /* the callee does not offer this operation */
  /* 1.1: an environment's act() refuses the action before anything runs (its safety
     filter); the message says why. Not an error of the plugin: the episode is
     reported as rejected and not simulated. */
  PRONK_REJECTED = 5
} pronk_status;

typedef enum pronk_factory_kind {
  PRONK_FACTORY_CONTROLLER = 1,
  PRONK_FACTORY_ENVIRONMENT = 2
} pronk_factory_kind;

typedef enum pronk_param_type {
  PRONK_PARAM_REAL = 1,   /* one number; checked against [min_value, max_value] */
  PRONK_PARAM_INT = 2,    /* one integer; checked against [min_value, max_value] */
  PRONK_PARAM_STRING = 3, /* free text */
  PRONK_PARAM_VECTOR = 4  /* whitespace-separated numbers; `vector_size` of them (0: any) */
} pronk_param_type;

/* One declared parameter of a factory: the host checks scenario files against it. */
typedef struct pronk_param_decl {
  uint32_t struct_size;
  const char* name;          /* [a-z0-9_]+ */
  uint32_t type;             /* pronk_param_type */
  uint32_t required;         /* 1: the scenario must set it */
  double min_value;          /* REAL / INT / each VECTOR element; ignored if min > max */
  double max_value;
  uint32_t vector_size;      /* VECTOR only */
  const char* default_value; /* text form; NULL when required */
  const char* unit;          /* "m", "N m/rad", "" ... */
  const char* description;   /* one line */
  /* 1.5: NULL, or the platform property a host fills in when the scenario does not set
     the parameter, in place of default_value (which a host before 1.5 uses):
       "stance"  the platform's standing joint positions of one leg, hip outwards
                 (<initial stance>), as a VECTOR;
       "kp", "kd" the platform's joint gains (<joints>), as a REAL.
     A platform that does not give the property leaves default_value in place. */
  const char* platform_default;
} pronk_param_decl;

/* A parameter value as written in the scenario (already checked by the host).
   Frozen: no struct_size, never extended; arrays of it have stride sizeof(pronk_param_value). */
typedef struct pronk_param_value {
  const char* name;
  const char* value;
} pronk_param_value;

/* The state handed to a controller each tick (host-owned, valid during the call). */
typedef struct pronk_robot_state {
  uint32_t struct_size;
  double time;              /* s since the episode start */
  int32_t joint_count;
  const double* q;          /* joint_count, rad (m for prismatic) */
  const double* qd;         /* joint_count */
  double base_position[3];  /* trunk frame origin, world */
  double base_quaternion[4];/* trunk orientation, world, (w, x, y, z) */
  double base_linear_velocity[3];  /* world */
  double base_angular_velocity[3]; /* world */
  double com_position[3];   /* whole-body centre of mass, world */
  double com_velocity[3];
  int32_t foot_count;
  const double* foot_position; /* foot_count x 3, foot sphere centres, world */
  const double* foot_force;    /* foot_count x 3, contact force on each foot, world, N */
  const uint8_t* foot_in_contact; /* foot_count flags */
} pronk_robot_state;

/*
 * Services the host offers a plugin instance: kinematics computed by the host's
 * multibody model. Valid from create() until destroy(). `host` is opaque and
 * must be passed back unchanged. Functions that take a foot index return
 * PRONK_ERROR_INVALID_ARGUMENT when it is out of range.
 */
typedef struct pronk_host_api {
  uint32_t struct_size;
  void* host;
  int32_t (*joint_count)(void* host);
  int32_t (*foot_count)(void* host);
  /* Name of controller joint i (host-owned, valid while the instance lives), NULL if out of range. */
  const char* (*joint_name)(void* host, int32_t joint);
  /* Lower/upper position limit, velocity limit (rad/s) and effort limit (N m) of joint i.
     A limit the model does not give is +-infinity (effort: infinity or 0). Each output
     pointer may be NULL. */
  pronk_status (*joint_limits)(void* host, int32_t joint, double* lower, double* upper,
                               double* velocity, double* effort);
  double (*total_mass)(void* host);                 /* kg */
  void (*gravity)(void* host, double gravity_world[3]); /* m/s^2 */
  /* Foot sphere radius, m. */
  double (*foot_radius)(void* host, int32_t foot);
  /* Kinematics at the state of the current tick. */
  pronk_status (*foot_position_world)(void* host, int32_t foot, double position_world[3]);
  /* 3 x (6 + joint_count), row-major: d(foot velocity, world) / d(u), u = [base angular
     velocity (world), base linear velocity (world), joint velocities]. */
  pronk_status (*foot_jacobian_world)(void* host, int32_t foot, double* jacobian);
  /* Foot position in the trunk frame for given joint positions (all joint_count of them):
     forward kinematics independent of the current state. */
  pronk_status (*foot_position_base)(void* host, int32_t foot, const double* q,
                                     double position_base[3]);
  /* 3 x 3 row-major: d(foot position in trunk frame) / d(q of that foot's leg joints), for
     legs with exactly three actuated joints; PRONK_ERROR_UNSUPPORTED otherwise. `q` holds
     all joint_count joint positions, as for foot_position_base. */
  pronk_status (*leg_jacobian_base)(void* host, int32_t foot, const double* q, double* jacobian);
  /* Record a named event (phase change, lift-off ...) in the episode trace at time t. */
  void (*emit_event)(void* host, double time, const char* name, const char* detail);
  /* Log a line (level 0 info, 1 warning, 2 error). */
  void (*log)(void* host, int32_t level, const char* message);
  /* 1.1: record a named number of the episode (a reward term, a planned time ...),
     reported with the episode's results; a later value of the same name replaces
     the earlier one. Names are [a-z0-9_]+. */
  void (*report_metric)(void* host, const char* name, double value);
  /* 1.2: at the state of the current tick, the whole-body angular momentum about the
     centre of mass (world, N m s) and the whole body's rotational inertia about the
     centre of mass with the joints locked (world, kg m^2, 3 x 3 row-major). Either
     output may be NULL. I^-1 L is the body's average angular velocity: in flight L
     is constant, whatever the legs do. */
  pronk_status (*centroidal_momentum)(void* host, double angular_momentum_world[3], double inertia_world[9]);
  /* 1.6: the terrain's highest top face whose footprint holds the world point (x, y),
     as the terrain is at the current tick: its height (world z, m) and which part of
     the terrain it is (-1 the ground plane, 0 ... the terrain's boxes, in the order
     the scenario gives them, generated platforms after its own boxes). A point over
     no surface at all (no ground plane, no box) gives PRONK_ERROR_UNSUPPORTED and
     leaves both outputs as they were. Either output may be NULL. Box sides are
     vertical: the surface is a step function of (x, y). */
  pronk_status (*terrain_top)(void* host, double x, double y, double* height, int32_t* surface);
} pronk_host_api;

/* Operations on a controller instance. */
typedef struct pronk_controller_ops {
  uint32_t struct_size;
  /* Called once before the first tick of an episode (optional, may be NULL). */
  pronk_status (*reset)(void* instance, const pronk_robot_state* state, char* error, size_t error_size);
  /* One control tick: write joint_count torques (N m). */
  pronk_status (*compute)(void* instance, const pronk_robot_state* state, double* torque,
                          char* error, size_t error_size);
  void (*destroy)(void* instance);
} pronk_controller_ops;

/* Operations on an environment instance. One action drives a whole episode. */
typedef struct pronk_environment_ops {
  uint32_t struct_size;
  /* Start an episode for a task vector (for the jump: target x, y, z, yaw, roll, pitch
     relative to the start). Writes observation_size numbers. */
  pronk_status (*reset)(void* instance, const double* task, int32_t task_size, uint64_t seed,
                        const pronk_robot_state* state, double* observation,
                        char* error, size_t error_size);
  /* Apply the episode's action (action_size numbers). From 1.1 it may return
     PRONK_REJECTED (with the reason) when the action must not run. */
  pronk_status (*act)(void* instance, const double* action, char* error, size_t error_size);
  /* One control tick; sets *done = 1 to end the episode early. */
  pronk_status (*step)(void* instance, const pronk_robot_state* state, double* torque, int32_t* done,
                       char* error, size_t error_size);
  /* After the last tick: the episode's reward. */
  pronk_status (*finish)(void* instance, const pronk_robot_state* state, double* reward,
                         char* error, size_t error_size);
  void (*destroy)(void* instance);
  /* 1.1, optional (NULL: none): the environment's own analytic policy, an action
     (action_size numbers, in the same units as act() takes) for an observation
     (observation_size numbers), computed without simulating. For the jump: the
     ballistic planner. Usable as a baseline and as a learned policy's prior.
     1.4: PRONK_REJECTED (with the reason) when the environment has no action for
     the observation that act() would take; `action` then still holds its best try. */
  pronk_status (*prior_action)(void* instance, const double* observation, double* action,
                               char* error, size_t error_size);
} pronk_environment_ops;

/* 1.3: what a reported metric is, for the host to file it without knowing its name. */
typedef enum pronk_metric_kind {
  PRONK_METRIC_VALUE = 0,   /* a number of the episode */
  PRONK_METRIC_PENALTY = 1, /* a cost term of the reward */
  PRONK_METRIC_TIME = 2     /* a time of the episode, s since reset (planned or detected) */
} pronk_metric_kind;

/* 1.3: one metric an environment reports with report_metric, declared up front. An
   array of them has the stride of its first entry's struct_size, as params. */
typedef struct pronk_metric_decl {
  uint32_t struct_size;
  const char* name;         /* [a-z0-9_]+, the name given to report_metric */
  uint32_t kind;            /* pronk_metric_kind */
  const char* unit;         /* "m", "s", "" ... */
  const char* description;  /* one line */
  /* Non-NULL: a column of the host's console table and results.csv with this header. */
  const char* column;
  /* Optional: a host event ("lift_off", "touchdown": all feet off, then a foot back on)
     or another metric shown beside this one in its column, as "this/that" (a plan
     against what happened). NULL: none. */
  const char* pairs_with;
} pronk_metric_decl;

/* 1.3: markers a video may draw over an episode, their numbers read from metrics.
   Positions and velocities are in the environment's start frame: origin on the
   ground below the robot's start, x along its initial heading, z up. */
typedef enum pronk_marker_kind {
  PRONK_MARKER_POINT = 1, /* metrics[0..2]: x, y, z (m); drawn on the surface below */
  PRONK_MARKER_ARC = 2    /* a ballistic arc under gravity: metrics[0..6] = x, y, z (m),
                             vx, vy, vz (m/s), duration (s) */
} pronk_marker_kind;

typedef struct pronk_marker_decl {
  uint32_t struct_size;
  uint32_t kind;            /* pronk_marker_kind */
  const char* label;        /* legend text, e.g. "planned flight" */
  const char* metrics[7];   /* metric names, as the kind says; unused entries NULL */
} pronk_marker_decl;

/* A named factory. Sizes are declarations the host checks before running:
   0 means "any" (decided by the robot). */
typedef struct pronk_factory {
  uint32_t struct_size;
  uint32_t kind;             /* pronk_factory_kind */
  const char* name;          /* unique in the plugin, [a-z0-9_]+ */
  const char* description;
  int32_t param_count;
  const pronk_param_decl* params; /* param_count entries, each with its own struct_size */
  int32_t joint_count;       /* actuated joints the factory works with; 0: any */
  int32_t observation_size;  /* environments */
  int32_t action_size;       /* environments */
  double control_period;     /* s; 0: any */
  /* Create an instance; params hold every declared parameter (defaults filled in). */
  pronk_status (*create)(const pronk_host_api* host, const pronk_param_value* params,
                         int32_t param_count, void** instance, char* error, size_t error_size);
  const pronk_controller_ops* controller;   /* kind == CONTROLLER */
  const pronk_environment_ops* environment; /* kind == ENVIRONMENT */
  /* 1.3, environments (all optional: 0 / NULL). */
  int32_t metric_count;
  const pronk_metric_decl* metrics;  /* metric_count entries, each with its own struct_size */
  const char* const* task_names;     /* NULL or one name per task number (e.g. "x", "yaw") */
  int32_t task_size;                 /* entries of task_names */
  int32_t marker_count;
  const pronk_marker_decl* markers;  /* marker_count entries, each with its own struct_size */
  /* 1.5, environments (optional, NULL: none). task_size numbers, each +1 or -1: the
     task of the mirror image of an episode across the robot's start x-z plane is the
     task times these (the jump: x, z and pitch keep their sign, y, yaw and roll
     change it). A learner may then add each example's mirror image (pronk train's
     mirror guidance). Declaring it says the environment, its controller and the
     robots it is meant for are left-right symmetric. */
  const double* task_mirror;
} pronk_factory;

/* Zeroed by the host, which sets struct_size; filled by the plugin, which writes only
   fields that fit in struct_size. Pointers stay valid until dlclose. */
typedef struct pronk_plugin_manifest {
  uint32_t struct_size;
  uint32_t abi_version;      /* negotiated version, written by the plugin */
  const char* plugin_name;
  const char* plugin_version;
  int32_t factory_count;
  const pronk_factory* const* factories;
} pronk_plugin_manifest;

/* The entry point. Returns PRONK_ERROR_VERSION (with a message) for a different major;
   otherwise writes manifest->abi_version = PRONK_ABI_VERSION(host major, min(own minor,
   host minor)) and the rest of the manifest. */
typedef pronk_status (*pronk_plugin_query_fn)(uint32_t host_abi_version, pronk_plugin_manifest* manifest,
                                              char* error, size_t error_size);

/* A plugin defines this function; the declaration gives it default visibility even in a
   library built with -fvisibility=hidden, and lets the compiler check its signature. */
PRONK_PLUGIN_EXPORT pronk_status pronk_plugin_query(uint32_t host_abi_version, pronk_plugin_manifest* manifest,
                                                    char* error, size_t error_size);

#ifdef __cplusplus
}
#endif

#endif /* PRONK_PLUGIN_ABI_H */
