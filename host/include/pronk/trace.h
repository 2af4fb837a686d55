// What an episode leaves behind: a sample per control tick and named events.
// Reports, metrics and videos are computed from traces, never from the live
// simulation.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace pronk {

struct TraceSample {
  double time = 0;
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();
  Eigen::Vector4d base_quaternion{1, 0, 0, 0};  // w, x, y, z
  Eigen::Vector3d base_linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_position = Eigen::Vector3d::Zero();
  Eigen::Vector3d com_velocity = Eigen::Vector3d::Zero();
  Eigen::VectorXd q, qd, torque;
  std::vector<Eigen::Vector3d> foot_position, foot_force;
  std::vector<uint8_t> foot_in_contact;
  std::vector<Eigen::Isometry3d> body_poses;  // every body, for rendering (optional)
};

struct TraceEvent {
  double time = 0;
  std::string name;    // "lift_off", "touchdown", "phase:flight", "failure" ...
  std::string detail;
};

// A named number an episode reports (a reward term, a planned time ...).
struct TraceMetric {
  std::string name;
  double value = 0;
};

struct Trace {
  std::vector<std::string> joint_names;
  std::vector<std::string> foot_links;
  std::vector<TraceSample> samples;
  std::vector<TraceEvent> events;
  std::vector<TraceMetric> metrics;  // in the order first reported

  // Sets a metric; a later value of the same name replaces the earlier one.
  void setMetric(const std::string& name, double value) {
    for (TraceMetric& m : metrics) {
      if (m.name == name) {
        m.value = value;
        return;
      }
    }
    metrics.push_back({name, value});
  }
  // The metric's value, or nullptr.
  const double* findMetric(const std::string& name) const {
    for (const TraceMetric& m : metrics)
      if (m.name == name) return &m.value;
    return nullptr;
  }

  void addEvent(double time, std::string name, std::string detail = {}) {
    events.push_back({time, std::move(name), std::move(detail)});
  }
  // First event with this name, or nullptr.
  const TraceEvent* findEvent(const std::string& name) const {
    for (const TraceEvent& e : events)
      if (e.name == name) return &e;
    return nullptr;
  }
};

// Writes the trace as CSV (one row per sample) to `path`. Throws Error when the
// file cannot be written.
void writeTraceCsv(const Trace& trace, const std::string& path);

// Reads a CSV written by writeTraceCsv back (samples only: no body poses, no
// events). Throws InputError("file:line: ...") for a malformed file.
Trace readTraceCsv(const std::string& path);

// Adds the whole robot's `lift_off` (all feet off) and `touchdown` (a foot back
// on) events from the samples' contact flags, as the episode runner does.
void addContactEvents(Trace& trace);

}  // namespace pronk
