// Ballistics: the flight phase of the paper ("Method Overview", "Physical
// feasibility check"). Once the feet leave the ground the whole-body centre of
// mass (CoM) moves under gravity alone:
//   c(t) = c_lo + v_lo t + g t^2 / 2,   v(t) = v_lo + g t,   t >= 0 since lift-off.
// This file holds that motion, the events it predicts (apex, landing on a
// horizontal surface, the paper's heuristic apex and touchdown instants), its
// inverse used by the planner (the lift-off velocity that reaches a target, and
// the paper's hyperbola of such velocities), and the landing's stopping offset.
// The check that rejects a lift-off state before the jump runs is the safety
// filter's (safety_filter.h).
//
// Frame: any frame whose z axis points up (the jump frame of docs/method.md, or
// the world). "Height" always means the z coordinate. Units: m, s, m/s.
// The equations as implemented: docs/method-ballistics-ik-reward.md.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>

namespace pronk::jump {

// (0, 0, -9.81) m/s^2.
Eigen::Vector3d standardGravity();

// A CoM state at lift-off: position (m) and velocity (m/s).
struct FlightState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// The ballistic flight that starts at `lift_off`. Times are seconds since lift-off.
// Gravity may be any vector with a downward z component (g_z < 0); the
// constructor throws std::invalid_argument naming the value otherwise, or when
// an input is not finite.
class BallisticFlight {
 public:
  explicit BallisticFlight(const FlightState& lift_off, const Eigen::Vector3d& gravity = standardGravity());

  const FlightState& liftOff() const { return lift_off_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }

  Eigen::Vector3d position(double t) const;  // c(t)
  Eigen::Vector3d velocity(double t) const;  // v(t)
  FlightState state(double t) const;

  // Apex: the highest point of the flight for t >= 0. With an upward lift-off
  // velocity it is where v_z = 0, t_apex = v_z / |g_z| (the paper's T_f,up), at
  // height z_lo + v_z^2 / (2 |g_z|). With v_z <= 0 the CoM only descends, so the
  // apex is the lift-off point itself (t_apex = 0).
  double apexTime() const;
  double apexHeight() const;
  Eigen::Vector3d apexPoint() const;

  // The time at which the CoM comes down through the horizontal plane
  // z = surface_height: the later root of z(t) = surface_height, provided it
  // is >= 0. std::nullopt when the plane lies above the apex (the CoM never
  // gets there); a plane at or below the lift-off height is always reached.
  // A plane exactly at the apex height gives the apex time.
  std::optional<double> landingTime(double surface_height) const;
  std::optional<Eigen::Vector3d> landingPoint(double surface_height) const;
  std::optional<FlightState> landingState(double surface_height) const;

 private:
  FlightState lift_off_;
  Eigen::Vector3d gravity_;
  double g_down_;  // |g_z| > 0
};

// The paper's heuristic event times ("Experiments with the real quadruped"):
// instead of detecting apex and touchdown from contact sensors, predict them
// from the lift-off state with the ballistic equations. Both return the time on
// the caller's clock: lift_off_time + the flight time.
//   apex:      lift_off_time + max(v_z, 0) / |g_z|
//   touchdown: lift_off_time + landingTime(touchdown_com_height), where
//              touchdown_com_height is the CoM height at which the feet touch
//              (landing surface height + the CoM height of the landing posture);
//              std::nullopt when the CoM never comes down to that height.
double heuristicApexTime(double lift_off_time, const FlightState& lift_off,
                         const Eigen::Vector3d& gravity = standardGravity());
std::optional<double> heuristicTouchdownTime(double lift_off_time, const FlightState& lift_off,
                                             double touchdown_com_height,
                                             const Eigen::Vector3d& gravity = standardGravity());

// A lift-off velocity that takes the CoM from a lift-off point to a target point.
struct LiftOffVelocity {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s
  double flight_time = 0.0;                            // s, lift-off to the target
  // True when the CoM reaches the target on the way down (v_z(T) <= 0), as a
  // landing needs; false when it passes through the target while still rising.
  bool arrives_descending = false;
};

// (a) Fixed flight time T > 0: v = (c_tg - c_lo - g T^2 / 2) / T (exact for any
// gravity vector). Throws std::invalid_argument when T <= 0 or an input is not finite.
LiftOffVelocity liftOffVelocityForFlightTime(const Eigen::Vector3d& lift_off_position, const Eigen::Vector3d& target,
                                             double flight_time, const Eigen::Vector3d& gravity = standardGravity());

// (b) Fixed horizontal speed s > 0 along the line from the lift-off point to
// the target: T = |dxy| / s, then (a). std::nullopt when the target lies
// straight above or below the lift-off point (|dxy| < 1e-12 m: no horizontal
// speed reaches it). Needs gravity along -z (no horizontal component); throws
// std::invalid_argument otherwise, or when s <= 0.
std::optional<LiftOffVelocity> liftOffVelocityForHorizontalSpeed(const Eigen::Vector3d& lift_off_position,
                                                                 const Eigen::Vector3d& target, double horizontal_speed,
                                                                 const Eigen::Vector3d& gravity = standardGravity());

// The paper's hyperbola: every lift-off velocity that reaches `target` from
// `lift_off_position`. The flight stays in the vertical plane through both
// points; with u the horizontal unit vector from lift-off to target, h = |dxy|
// the horizontal distance, dz = z_tg - z_lo and g = |g_z|, a horizontal speed
// s > 0 along u needs the vertical speed
//   v_z(s) = dz s / h + g h / (2 s)          (flight time T = h / s),
// a hyperbola in the (s, v_z) plane. Members can be picked by
//   - horizontal speed s in (0, inf)                            (atHorizontalSpeed),
//   - flight time T in (0, inf), s = h / T                       (atFlightTime),
//   - elevation theta of v above the horizontal, in (atan(dz/h), pi/2):
//       s^2 = g h / (2 (tan(theta) - dz / h))                     (atElevation),
//   - least speed |v|: theta* = pi/4 + atan2(dz, h) / 2,
//       |v|^2 = g (dz + sqrt(h^2 + dz^2))                        (leastSpeed).
// Needs h >= 1e-9 m (a vertical jump has only v = (0, 0, v_z)) and gravity
// along -z; the constructor throws std::invalid_argument otherwise.
class LiftOffHyperbola {
 public:
  LiftOffHyperbola(const Eigen::Vector3d& lift_off_position, const Eigen::Vector3d& target,
                   const Eigen::Vector3d& gravity = standardGravity());

  double horizontalDistance() const { return h_; }         // h, m
  double heightChange() const { return dz_; }              // dz, m
  const Eigen::Vector3d& direction() const { return u_; }  // u, horizontal unit vector

  // v_z on the hyperbola for a horizontal speed s > 0 (throws for s <= 0).
  double verticalSpeed(double horizontal_speed) const;

  LiftOffVelocity atHorizontalSpeed(double horizontal_speed) const;
  LiftOffVelocity atFlightTime(double flight_time) const;
  // std::nullopt when theta is not strictly between atan(dz/h) and pi/2.
  std::optional<LiftOffVelocity> atElevation(double elevation) const;
  // The same for a caller that already holds tan(elevation) (the planner's
  // fixed point needs it before, and calls this in every round).
  std::optional<LiftOffVelocity> atElevation(double elevation, double tan_elevation) const;
  LiftOffVelocity leastSpeed() const;

  // Lower bound of the admissible elevations: atan2(dz, h), rad.
  double minimumElevation() const { return min_elevation_; }

 private:
  Eigen::Vector3d lift_off_;
  Eigen::Vector3d target_;
  Eigen::Vector3d gravity_;
  Eigen::Vector3d u_;
  double h_ = 0.0;
  double dz_ = 0.0;
  double g_ = 0.0;
  double min_elevation_ = 0.0;  // computed once: both the planner and atElevation need it
};

// The landing's stopping offset: where a compliant landing brings the CoM to rest,
// horizontally, from its touchdown point. The impact's vertical impulse m |v_z|
// lets friction take up to `friction` |v_z| of the horizontal speed at once; a
// critically damped stop at natural frequency `frequency` (rad/s) carries what is
// left a distance of (speed left) / frequency further, along the horizontal
// velocity. Zero when friction takes it all. friction >= 0, frequency > 0.
Eigen::Vector2d landingStopOffset(const Eigen::Vector3d& touchdown_velocity, double friction, double frequency);

// Where the landing brings the CoM to rest, horizontally, from its touchdown
// point, for the CoM velocity at touchdown (the controller's landing:
// landingStopOffset with its gains, control/landing_phase.h).
using LandingStop = std::function<Eigen::Vector2d(const Eigen::Vector3d& touchdown_velocity)>;

// How much longer than they stand the legs touch down, so that knees that
// saturate through the stop still have the stroke to stop the fall. In the
// stance pose the knees hold the body with at most
//   a = legs tau_knee / (m lever) - g
// of deceleration (lever: the foot's horizontal distance from the knee).
// Stopping a fall from kLandingFallHeight leg lengths at a takes
// kLandingFallHeight g / a leg lengths of stroke; the stance pose gives
// kStanceStroke of them before a thigh nears the ground, and the legs touch
// down longer by the rest, at most kMaxLandingExtension leg lengths. The two
// constants put the Go1 (a = 65 m/s^2) at 0 and the Aliengo (32 m/s^2) at
// 0.11 m, each robot's measured best (docs/method.md, "Legs that touch down
// longer than they stand"). All lengths in m, effort N m, mass kg, gravity
// m/s^2 (its magnitude), all > 0.
constexpr double kLandingFallHeight = 1.44;   // leg lengths: the Go1's 0.4 m drop from 0.2 m above
constexpr double kStanceStroke = 0.22;        // leg lengths
constexpr double kMaxLandingExtension = 0.5;  // leg lengths
double landingExtension(double leg_length, double knee_lever, double knee_effort, double mass, double gravity,
                        int legs);

}  // namespace pronk::jump
