// What training keeps of one finished jump, in a form that crosses processes:
// under `mpirun` every rank runs a share of a batch and rank 0 learns from all
// of it, so a case's result travels as JSON text, every number to the last bit
// (NaN as null).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "pronk/report.h"
#include "pronk/rollout.h"

namespace pronk {

// What the exploring policy of one case drew, written by the worker that runs
// the case (each case by one worker) and read after the rollout.
struct CaseDraw {
  bool ran = false;
  Eigen::VectorXd residual;  // the sampled network action (PPO's Gaussian sample)
  Eigen::VectorXd prior;     // the environment's prior_action for the case (residual policies)
  // An aim correction's aim offset as taken: the sample, or 0 where the prior
  // had no feasible action for the aim and planned for the task itself.
  Eigen::VectorXd aim_taken;
};

struct CaseResult {
  size_t index = 0;
  std::optional<JumpOutcome> outcome;  // none when the case could not be set up
  std::vector<double> observation;
  double reward = 0;
  std::vector<double> action;  // the action the environment took
  CaseDraw draw;               // empty where no exploring policy drew one (validation)
  // The environment's penalty metrics (the reward's terms), in the order of the
  // names asked for; NaN where the jump reported none (a refused jump's).
  std::vector<double> penalties;
};

// The report's judgement and what the learner needs, from a record (and the
// draw its policy left for it, if any).
CaseResult caseResultOf(const EpisodeRecord& record, const CaseDraw* draw,
                        const std::vector<std::string>& penalty_names);

nlohmann::json toJson(const CaseResult& result);
// Throws Error for a document that is not one.
CaseResult caseResultFromJson(const nlohmann::json& j);

}  // namespace pronk
