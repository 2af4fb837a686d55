// train_log.csv and the training checkpoint's reading and writing
// (training_files.h).
#include "training_files.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pronk/error.h"
#include "pronk/file_io.h"
#include "pronk/json_budget.h"

namespace pronk::training_files {

namespace {

using nlohmann::json;

json value(double v) { return std::isfinite(v) ? json(v) : json(); }

}  // namespace

std::vector<std::string> logColumns(const std::vector<std::string>& penalties) {
  std::vector<std::string> columns = {
      "iteration", "iterations", "jumps",
      "batch_jumps", "batch_landed", "batch_failed", "batch_rejected", "batch_setup_errors",
      "batch_error_median_m", "batch_error_mean_m", "batch_within_0.2m",
      "reward_mean", "reward_std",
      "validated", "validation_jumps", "validation_landed", "validation_failed", "validation_rejected",
      "validation_error_median_m", "validation_error_mean_m", "validation_within_0.2m",
      "critic_warmup_loss", "hindsight_pairs", "hindsight_added", "hindsight_loss", "oversampled", "policy_loss", "value_loss", "entropy", "kl", "clip_fraction",
      "learning_rate", "std_mean", "value_mean", "actor_gradient_norm", "critic_gradient_norm",
      "rollout_s", "update_s", "validation_s", "jumps_per_s", "wall_s", "eta_s", "penalty_sum_mean"};
  for (const std::string& p : penalties) columns.push_back("penalty_" + p);
  return columns;
}

std::vector<json> logValues(const TrainingIteration& r) {
  const JumpSetFigures& b = r.batch;
  const JumpSetFigures& v = r.validation;
  std::vector<json> values = {r.iteration, r.iterations, r.jumps,
          b.jumps, b.landed, b.failed, b.rejected, b.setup_errors,
          value(b.error_median), value(b.error_mean), value(b.within_02),
          value(r.reward_mean), value(r.reward_std),
          r.validated ? 1 : 0, v.jumps, v.landed, v.failed, v.rejected,
          value(v.error_median), value(v.error_mean), value(v.within_02),
          value(r.critic_warmup_loss), value(r.hindsight_pairs), value(r.hindsight_added), value(r.hindsight_loss),
          value(r.oversampled), value(r.policy_loss), value(r.value_loss), value(r.entropy), value(r.kl),
          value(r.clip_fraction), value(r.learning_rate), value(r.std_mean), value(r.value_mean),
          value(r.actor_gradient_norm), value(r.critic_gradient_norm),
          value(r.rollout_s), value(r.update_s), value(r.validation_s), value(r.jumps_per_s), value(r.wall_s),
          value(r.eta_s), value(r.penalty_sum_mean)};
  for (double p : r.penalty_means) values.push_back(value(p));
  return values;
}

bool rowValidated(const std::vector<json>& row, const std::vector<std::string>& penalties) {
  const std::vector<std::string> columns = logColumns(penalties);
  const size_t at = static_cast<size_t>(std::find(columns.begin(), columns.end(), "validated") - columns.begin());
  return row.size() == columns.size() && row[at].is_number() && row[at].get<double>() == 1;
}

std::optional<TrainingIteration> lastValidation(const std::vector<std::vector<json>>& rows,
                                                const std::vector<std::string>& penalties) {
  const std::vector<std::string> columns = logColumns(penalties);
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  const auto number = [](const json& v) { return v.is_number() ? v.get<double>() : std::nan(""); };
  for (auto row = rows.rbegin(); row != rows.rend(); ++row) {
    if (!rowValidated(*row, penalties)) continue;
    TrainingIteration r;
    r.iteration = static_cast<int>(number((*row)[column("iteration")]));
    r.validated = true;
    JumpSetFigures& v = r.validation;
    v.jumps = static_cast<int>(number((*row)[column("validation_jumps")]));
    v.landed = static_cast<int>(number((*row)[column("validation_landed")]));
    v.failed = static_cast<int>(number((*row)[column("validation_failed")]));
    v.rejected = static_cast<int>(number((*row)[column("validation_rejected")]));
    v.error_median = number((*row)[column("validation_error_median_m")]);
    v.error_mean = number((*row)[column("validation_error_mean_m")]);
    v.within_02 = number((*row)[column("validation_within_0.2m")]);
    return r;
  }
  return std::nullopt;
}

void setRowValidation(std::vector<json>& row, const JumpSetFigures& v, const std::vector<std::string>& penalties) {
  const std::vector<std::string> columns = logColumns(penalties);
  if (row.size() != columns.size()) throw Error("setRowValidation: a row of " + std::to_string(row.size()) + " values");
  const auto set = [&](const std::string& name, json value) {
    row[static_cast<size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin())] = std::move(value);
  };
  set("validated", 1);
  set("validation_jumps", v.jumps);
  set("validation_landed", v.landed);
  set("validation_failed", v.failed);
  set("validation_rejected", v.rejected);
  set("validation_error_median_m", value(v.error_median));
  set("validation_error_mean_m", value(v.error_mean));
  set("validation_within_0.2m", value(v.within_02));
}

void writeLog(const std::string& path, const std::vector<std::vector<json>>& rows,
              const std::vector<std::string>& penalties) {
  std::string text;
  for (const std::string& c : logColumns(penalties)) text += (text.empty() ? "" : ",") + c;
  text += "\n";
  for (const std::vector<json>& row : rows) {
    for (size_t i = 0; i < row.size(); ++i) {
      if (i) text += ",";
      if (row[i].is_null()) {
        text += "nan";
      } else if (row[i].is_number_float()) {
        char number[32];
        std::snprintf(number, sizeof number, "%.9g", row[i].get<double>());
        text += number;
      } else {
        text += row[i].dump();
      }
    }
    text += "\n";
  }
  writeText(path, text, "training log");
}

json rngJson(const Rng& rng) {
  json words = json::array();
  for (std::uint64_t w : rng.state()) {
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, w);
    words.push_back(text);
  }
  return words;
}

void writeText(const std::string& path, const std::string& text, const std::string& what) {
  replaceFileAtomically(path, text, what);
}

void writeJson(const std::string& path, const json& doc, const std::string& what) {
  writeText(path, doc.dump(1) + "\n", what);
}

json readJson(const std::string& path, const std::string& what) {
  const std::string text = readInputFile(path, what);  // a regular file, bounded in size
  // Bounded in memory (JsonMemoryBudget) and depth too: the recursive copies
  // and destructors of a deep document exhaust the stack.
  constexpr int kMaxDepth = 64;
  JsonMemoryBudget budget(text.size());
  const json::parser_callback_t bounded = [&](int depth, json::parse_event_t event, json& value) {
    if (depth > kMaxDepth) throw InputError({path, 0}, "nested more than " + std::to_string(kMaxDepth) + " levels deep");
    using E = json::parse_event_t;
    const std::size_t bytes = event == E::object_start || event == E::array_start ? JsonMemoryBudget::kContainerBytes
                              : event == E::key ? JsonMemoryBudget::kKeyBytes + value.get_ref<const std::string&>().size()
                                                : JsonMemoryBudget::kScalarBytes;
    if (!budget.spend(bytes)) throw InputError({path, 0}, budget.refusal());
    return true;
  };
  try {
    return json::parse(text, bounded);
  } catch (const json::exception& e) {
    throw InputError({path, 0}, "not a " + what + " (invalid JSON: " + e.what() + ")");
  }
}

void JsonReader::fail(const std::string& key, const std::string& message) const {
  throw InputError({path_, 0}, key + ": " + message);
}

const json& JsonReader::at(const json& object, const char* key) const {
  if (!object.is_object()) fail(key, "the checkpoint is not a JSON object");
  const auto it = object.find(key);
  if (it == object.end()) fail(key, "missing");
  return *it;
}

std::string JsonReader::string(const json& object, const char* key) const {
  const json& v = at(object, key);
  if (!v.is_string()) fail(key, "expected a string");
  return v.get<std::string>();
}

long long JsonReader::integer(const json& object, const char* key) const {
  const json& v = at(object, key);
  if (!v.is_number_integer()) fail(key, "expected an integer");
  return v.get<long long>();
}

double JsonReader::number(const json& object, const char* key) const {
  const json& v = at(object, key);
  if (!v.is_number()) fail(key, "expected a number");
  return v.get<double>();
}

Rng::State JsonReader::rng(const json& object, const char* key) const {
  const json& v = at(object, key);
  if (!v.is_array() || v.size() != 4) fail(key, "expected four state words");
  Rng::State state{};
  for (size_t i = 0; i < 4; ++i) {
    if (!v[i].is_string() || v[i].get<std::string>().size() != 16) fail(key, "expected 16 hex digits per word");
    const std::string word = v[i].get<std::string>();
    char* end = nullptr;
    state[i] = std::strtoull(word.c_str(), &end, 16);
    if (end != word.c_str() + word.size()) fail(key, "expected 16 hex digits per word");
  }
  if (state == Rng::State{}) fail(key, "all zero");
  return state;
}

}  // namespace pronk::training_files
