// Hindsight relabelling (docs/training.md, "Hindsight relabelling and the aim correction"): a jump
// that ended standing is a correct example for the place it reached, whatever
// its target was. The trainer keeps the newest such pairs (achieved task,
// residual that reaches it, i.e. the action taken minus the environment's
// prior_action for the achieved task) and fits the actor's mean to them.
#pragma once

#include <deque>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "pronk/report.h"
#include "pronk/scenario.h"

namespace pronk::hindsight {

// How far (m) the trunk may end from the target's height and still count as
// having landed at that height (on the step platform, or on the ground below it).
constexpr double kLevelTolerance = 0.05;
// Achieved tasks are kept when they lie within the region widened by this
// share of each range on both sides (a landing far outside teaches nothing the
// region needs).
constexpr double kRegionMargin = 0.25;

// The task (x, y, z, yaw, roll, pitch) a jump achieved: where its trunk came to
// rest in the start heading frame, the target's z, roll and pitch. Nothing for
// a jump that did not end standing at the target's level, or ended outside the
// widened region.
std::optional<std::vector<double>> achievedTask(const JumpOutcome& outcome, const TargetSpec& target,
                                                const TrainingSpec& region);

// The newest `capacity` (observation, action) pairs, oldest dropped first.
class Buffer {
 public:
  explicit Buffer(int capacity) : capacity_(capacity) {}
  void add(const std::vector<double>& observation, const Eigen::VectorXd& action);
  int size() const { return static_cast<int>(observations_.size()); }
  Eigen::MatrixXd observations() const;  // one column per pair, oldest first
  Eigen::MatrixXd actions() const;

  // Its pairs for a checkpoint; back, checked (throws pronk::Error naming the field).
  nlohmann::json toJson() const;
  void fromJson(const nlohmann::json& doc, int observation_size, int action_size);

 private:
  int capacity_;
  std::deque<std::vector<double>> observations_;
  std::deque<Eigen::VectorXd> actions_;
};

}  // namespace pronk::hindsight
