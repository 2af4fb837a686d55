// Hindsight relabelling: achieved tasks and the pair buffer (hindsight.h).
#include "hindsight.h"

#include <cmath>

#include "pronk/error.h"

namespace pronk::hindsight {

namespace {

bool within(double v, const TrainingRange& r) {
  const double margin = kRegionMargin * (r.max - r.min);
  return v >= r.min - margin && v <= r.max + margin;
}

}  // namespace

std::optional<std::vector<double>> achievedTask(const JumpOutcome& outcome, const TargetSpec& target,
                                                const TrainingSpec& region) {
  if (!outcome.ran || (outcome.status != "ok" && outcome.status != "missed")) return std::nullopt;
  const Landing& l = outcome.landing;
  if (!l.standing || !l.displacement.allFinite() || !std::isfinite(l.yaw)) return std::nullopt;
  if (std::abs(l.displacement.z() - target.z) > kLevelTolerance) return std::nullopt;
  if (!within(l.displacement.x(), region.x) || !within(l.displacement.y(), region.y) || !within(l.yaw, region.yaw)) {
    return std::nullopt;
  }
  return std::vector<double>{l.displacement.x(), l.displacement.y(), target.z, l.yaw, target.roll, target.pitch};
}

void Buffer::add(const std::vector<double>& observation, const Eigen::VectorXd& action) {
  observations_.push_back(observation);
  actions_.push_back(action);
  while (static_cast<int>(observations_.size()) > capacity_) {
    observations_.pop_front();
    actions_.pop_front();
  }
}

Eigen::MatrixXd Buffer::observations() const {
  Eigen::MatrixXd m(observations_.empty() ? 0 : static_cast<Eigen::Index>(observations_.front().size()), size());
  for (int j = 0; j < size(); ++j) {
    const std::vector<double>& o = observations_[static_cast<size_t>(j)];
    m.col(j) = Eigen::Map<const Eigen::VectorXd>(o.data(), static_cast<Eigen::Index>(o.size()));
  }
  return m;
}

Eigen::MatrixXd Buffer::actions() const {
  Eigen::MatrixXd m(actions_.empty() ? 0 : actions_.front().size(), size());
  for (int j = 0; j < size(); ++j) m.col(j) = actions_[static_cast<size_t>(j)];
  return m;
}

nlohmann::json Buffer::toJson() const {
  nlohmann::json observations = nlohmann::json::array(), actions = nlohmann::json::array();
  for (const std::vector<double>& o : observations_) observations.push_back(o);
  for (const Eigen::VectorXd& a : actions_) actions.push_back(std::vector<double>(a.data(), a.data() + a.size()));
  return {{"capacity", capacity_}, {"observations", observations}, {"actions", actions}};
}

void Buffer::fromJson(const nlohmann::json& doc, int observation_size, int action_size) {
  auto fail = [](const std::string& what) { throw Error("hindsight: " + what); };
  if (!doc.is_object() || !doc.contains("observations") || !doc.contains("actions")) {
    fail("expected an object with \"observations\" and \"actions\"");
  }
  const nlohmann::json& obs = doc["observations"];
  const nlohmann::json& act = doc["actions"];
  if (!obs.is_array() || !act.is_array() || obs.size() != act.size()) {
    fail("\"observations\" and \"actions\" must be arrays of the same length");
  }
  observations_.clear();
  actions_.clear();
  for (size_t j = 0; j < obs.size(); ++j) {
    const std::string at = "[" + std::to_string(j) + "]";
    if (!obs[j].is_array() || static_cast<int>(obs[j].size()) != observation_size) {
      fail("observations" + at + ": expected " + std::to_string(observation_size) + " numbers");
    }
    if (!act[j].is_array() || static_cast<int>(act[j].size()) != action_size) {
      fail("actions" + at + ": expected " + std::to_string(action_size) + " numbers");
    }
    std::vector<double> o;
    Eigen::VectorXd a(action_size);
    for (const auto& v : obs[j]) {
      if (!v.is_number()) fail("observations" + at + ": not a number");
      o.push_back(v.get<double>());
    }
    for (int i = 0; i < action_size; ++i) {
      if (!act[j][static_cast<size_t>(i)].is_number()) fail("actions" + at + ": not a number");
      a[i] = act[j][static_cast<size_t>(i)].get<double>();
    }
    add(o, a);
  }
}

}  // namespace pronk::hindsight
