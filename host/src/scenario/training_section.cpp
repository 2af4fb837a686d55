// <training>: what `pronk train` does with a scenario: the task region targets
// are drawn from, the iterations and batch size, the networks, PPO's settings,
// the validation set and the guidance switches (docs/scenario-format.md).
#include <cmath>

#include "sections.h"

namespace pronk::scenario_file {

using tinyxml2::XMLElement;

namespace {

constexpr std::int64_t kMaxIterations = 1'000'000;
constexpr std::int64_t kMaxJumps = 1'000'000;    // per iteration
constexpr std::int64_t kMaxLayerWidth = 4096;
constexpr std::size_t kMaxLayers = 16;
// A task region within what a legged robot can jump (m), far beyond the paper's.
constexpr double kMaxReach = 10.0;
constexpr double kMaxRise = 5.0;

// "min max": two numbers (angles in the file's unit), min <= max.
// Within [-bound, bound] (rad for an angle).
TrainingRange readRange(ElementReader& r, const char* name, bool angle, double bound) {
  if (!r.has(name)) return {};
  const std::vector<double> v = angle ? r.angles(name) : r.numbers(name);
  if (v.size() != 2) {
    r.fail(std::string(name) + " takes two numbers, min and max (got " + std::to_string(v.size()) + ")");
  }
  const double shown = angle ? 1 / r.angleScale() : 1;  // messages in the file's unit
  for (double x : v) {
    if (!(std::abs(x) <= bound)) {
      r.fail(std::string(name) + ": " + formatNumber(x * shown) + " is beyond +-" + formatNumber(bound * shown) +
             (angle ? "" : " m"));
    }
  }
  if (v[1] < v[0]) {
    r.fail(std::string(name) + ": max (" + formatNumber(v[1] * shown) + ") must be >= min (" +
           formatNumber(v[0] * shown) + ")");
  }
  return {v[0], v[1]};
}

std::vector<int> readLayerSizes(ElementReader& r, const char* name, const std::vector<int>& fallback) {
  if (!r.has(name)) return fallback;
  const std::vector<double> v = r.numbers(name);
  if (v.empty()) r.fail(std::string(name) + " needs at least one hidden layer size");
  if (v.size() > kMaxLayers) r.fail(std::string(name) + ": at most " + std::to_string(kMaxLayers) + " hidden layers");
  std::vector<int> sizes;
  for (double d : v) {
    if (d != std::floor(d) || d < 1 || d > static_cast<double>(kMaxLayerWidth)) {
      r.fail(std::string(name) + ": layer sizes are integers in [1, " + std::to_string(kMaxLayerWidth) + "] (got " +
             formatNumber(d) + ")");
    }
    sizes.push_back(static_cast<int>(d));
  }
  return sizes;
}

void readRegion(const XMLElement& e, const SourceFile& file, TrainingSpec& t) {
  ElementReader r(e, file);
  t.region_where = r.where();
  t.x = readRange(r, "x", false, kMaxReach);
  t.y = readRange(r, "y", false, kMaxReach);
  t.z = readRange(r, "z", false, kMaxRise);
  t.yaw = readRange(r, "yaw", true, M_PI);
  t.flat_share = r.number("flat_share", t.flat_share, Range::closed(0, 1));
  if (t.flat_share > 0 && t.z.min == 0 && t.z.max == 0) {
    r.fail("flat_share " + formatNumber(t.flat_share) + " needs a z range: every target of this region is flat");
  }
  r.rejectUnknownAttributes();
  r.children({});
}

void readNetworks(const XMLElement& e, const SourceFile& file, TrainingSpec& t) {
  ElementReader r(e, file);
  t.actor_hidden_sizes = readLayerSizes(r, "actor", t.actor_hidden_sizes);
  t.critic_hidden_sizes = readLayerSizes(r, "critic", t.critic_hidden_sizes);
  r.rejectUnknownAttributes();
  r.children({});
}

void readPpo(const XMLElement& e, const SourceFile& file, TrainingSpec& t) {
  ElementReader r(e, file);
  t.epochs = static_cast<int>(r.integer("epochs", t.epochs, 1, 1000));
  t.minibatches = static_cast<int>(r.integer("minibatches", t.minibatches, 1, 100000));
  // Far beyond what trains, short of what overflows: (0, 1] for rates and the
  // clip, [1e-6, 10] for the raw action's std.
  const Range rate{0, 1, true, false};
  t.learning_rate = r.number("learning_rate", t.learning_rate, rate);
  t.clip = r.number("clip", t.clip, rate);
  t.entropy_coefficient = r.number("entropy_coefficient", t.entropy_coefficient, Range::closed(0, 1));
  t.desired_kl = r.number("desired_kl", t.desired_kl, rate);
  t.initial_std = r.number("initial_std", t.initial_std, Range::closed(1e-6, 10));
  t.ppo_actor = r.boolean("actor", t.ppo_actor);
  r.rejectUnknownAttributes();
  r.children({});
}

void readValidation(const XMLElement& e, const SourceFile& file, TrainingSpec& t) {
  ElementReader r(e, file);
  t.validation_count = static_cast<int>(r.integer("count", t.validation_count, 0, kMaxJumps));
  t.validation_seed = static_cast<unsigned long>(r.integer("seed", static_cast<std::int64_t>(t.validation_seed), 0,
                                                           4294967295LL));
  t.validate_every = static_cast<int>(r.integer("every", t.validate_every, 1, kMaxIterations));
  r.rejectUnknownAttributes();
  r.children({});
}

void readGuidance(const XMLElement& e, const SourceFile& file, TrainingSpec& t) {
  ElementReader r(e, file);
  t.residual = r.boolean("residual", t.residual);
  t.aim = r.boolean("aim", t.aim);
  t.critic_warmup = r.boolean("critic_warmup", t.critic_warmup);
  t.critic_warmup_epochs = static_cast<int>(r.integer("critic_warmup_epochs", t.critic_warmup_epochs, 1, 10000));
  t.hindsight = r.boolean("hindsight", t.hindsight);
  t.hindsight_epochs = static_cast<int>(r.integer("hindsight_epochs", t.hindsight_epochs, 1, 10000));
  t.hindsight_samples = static_cast<int>(r.integer("hindsight_samples", t.hindsight_samples, 1, kMaxJumps));
  t.hindsight_minibatch = static_cast<int>(r.integer("hindsight_minibatch", t.hindsight_minibatch, 1, kMaxJumps));
  t.hindsight_learning_rate = r.number("hindsight_learning_rate", t.hindsight_learning_rate, Range{0, 1, true, false});
  t.hindsight_prior_step = r.number("hindsight_prior_step", t.hindsight_prior_step, Range{0, 100, true, false});
  t.mirror = r.boolean("mirror", t.mirror);
  t.oversample = r.number("oversample", t.oversample, Range::closed(0.0, 0.9));
  r.rejectUnknownAttributes();
  r.children({});
  if (t.aim && t.residual) {
    r.fail("aim=\"true\" and residual=\"true\": the policy is either an aim correction of the prior or a "
           "residual over it; write residual=\"false\" with aim=\"true\"");
  }
  if (t.mirror && !(t.aim && t.hindsight)) {
    r.fail("mirror=\"true\" adds the mirror image of each hindsight pair of an aim correction: it needs "
           "aim=\"true\" and hindsight=\"true\"");
  }
}

}  // namespace

TrainingSpec readTraining(const XMLElement& e, const SourceFile& file) {
  ElementReader r(e, file);
  TrainingSpec t;
  t.where = r.where();
  t.iterations = static_cast<int>(r.integer("iterations", t.iterations, 1, kMaxIterations));
  t.jumps_per_iteration = static_cast<int>(r.integer("jumps_per_iteration", t.jumps_per_iteration, 1, kMaxJumps));
  t.seed = static_cast<unsigned long>(r.integer("seed", static_cast<std::int64_t>(t.seed), 0, 4294967295LL));
  t.checkpoint_every = static_cast<int>(r.integer("checkpoint_every", t.checkpoint_every, 1, kMaxIterations));
  r.rejectUnknownAttributes();
  const auto kids = r.children({"region", "networks", "ppo", "validation", "guidance"});
  for (const char* name : {"region", "networks", "ppo", "validation", "guidance"}) r.rejectRepeated(kids, name);
  bool region = false;
  for (const XMLElement* k : kids) {
    const std::string name = k->Name();
    if (name == "region") {
      readRegion(*k, file, t);
      region = true;
    } else if (name == "networks") {
      readNetworks(*k, file, t);
    } else if (name == "ppo") {
      readPpo(*k, file, t);
    } else if (name == "validation") {
      readValidation(*k, file, t);
    } else if (name == "guidance") {
      readGuidance(*k, file, t);
    }
  }
  if (!region) r.fail("missing child <region> (the x, y, z and yaw ranges targets are drawn from)");
  if (t.jumps_per_iteration < t.minibatches) {
    r.fail("jumps_per_iteration (" + std::to_string(t.jumps_per_iteration) + ") must be >= the <ppo> minibatches (" +
           std::to_string(t.minibatches) + ")");
  }
  return t;
}

}  // namespace pronk::scenario_file
