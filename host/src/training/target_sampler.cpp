// The targets training draws: uniform in the <training> region, and the fixed
// validation set (pronk/training.h).
#include <cmath>
#include <functional>
#include <utility>

#include "pronk/error.h"
#include "pronk/training.h"
#include "training_streams.h"

namespace pronk {

namespace {

double uniform(Rng& rng, const TrainingRange& range) { return range.min + (range.max - range.min) * rng.uniform(); }

}  // namespace

TargetSampler::TargetSampler(const TrainingSpec& spec) : spec_(spec) {}

void TargetSampler::placeEdges(std::function<bool(const EpisodeCase&)> fits) { fits_ = std::move(fits); }

TargetSpec TargetSampler::draw(Rng& rng) const {
  for (int attempt = 0; attempt < kMaxDraws; ++attempt) {
    TargetSpec t;
    t.x = uniform(rng, spec_.x);
    t.y = uniform(rng, spec_.y);
    t.z = uniform(rng, spec_.z);
    // One more draw only with a flat share, so that a region without one keeps
    // its seeds' targets.
    if (spec_.flat_share > 0 && rng.uniform() < spec_.flat_share) t.z = 0;
    t.yaw = uniform(rng, spec_.yaw);
    t.where = spec_.region_where;
    if (t.z == 0 || std::hypot(t.x, t.y) >= kLeastStepDistance) return t;
  }
  throw InputError(spec_.region_where, "<region>: no target with a height lies >= " +
                                           std::to_string(kLeastStepDistance) +
                                           " m from the start in 10000 draws; widen x or y");
}

std::vector<EpisodeCase> TargetSampler::cases(Rng& rng, int n, const std::string& prefix) const {
  std::vector<EpisodeCase> out;
  out.reserve(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    EpisodeCase c;
    c.label = prefix + " #" + std::to_string(i);
    for (int attempt = 0;; ++attempt) {
      if (attempt == kMaxDraws) {
        throw InputError(spec_.region_where, "<region>: no target of it leaves room for a step platform's edge "
                                             "between the two stances in " + std::to_string(kMaxDraws) +
                                             " draws; widen x or y");
      }
      c.target = draw(rng);
      c.target.name = c.label;
      if (!fits_) break;
      c.assignments = {{"terrain.edge", rng.uniform()}};
      if (fits_(c)) break;
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<EpisodeCase> validationCases(const TrainingSpec& spec, const TargetSampler& sampler) {
  Rng rng(training_streams::validationSeed(spec.validation_seed));
  return sampler.cases(rng, spec.validation_count, "validation");
}

}  // namespace pronk
