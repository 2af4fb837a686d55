// What an environment's reported numbers mean, as it declares them (plugin ABI
// 1.3): the report files its metrics, labels its task vector and draws its
// markers from this, never from names of its own. Plain data, no dependency.
#pragma once

#include <string>
#include <vector>

namespace pronk {

struct MetricSpec {
  enum class Kind { Value, Penalty, Time };
  std::string name;         // as reported (Trace::metrics)
  Kind kind = Kind::Value;
  std::string unit, description;
  std::string column;       // header of its table and CSV column; "" = none
  std::string pairs_with;   // a host event or another metric shown beside it; "" = none
};

struct MarkerSpec {
  enum class Kind { Point, Arc };
  Kind kind = Kind::Point;
  std::string label;
  std::vector<std::string> metrics;  // Point: x y z; Arc: x y z vx vy vz duration (start frame)
};

struct EnvironmentSchema {
  std::vector<MetricSpec> metrics;     // in declaration order
  std::vector<std::string> task_names;
  std::vector<MarkerSpec> markers;
  // ABI 1.5: the sign of each task number in the episode's mirror image across
  // the robot's sagittal plane (task_names' order); empty: not symmetric.
  std::vector<double> task_mirror;

  const MetricSpec* find(const std::string& name) const {
    for (const MetricSpec& m : metrics)
      if (m.name == name) return &m;
    return nullptr;
  }
};

// The events every host episode records from foot contact (pronk/episode.h): a
// metric may pair with them.
inline const std::vector<std::string>& hostContactEvents() {
  static const std::vector<std::string> names = {"lift_off", "touchdown"};
  return names;
}

}  // namespace pronk
