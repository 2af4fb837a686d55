// The files of a training run besides the policy: train_log.csv (one row per
// iteration, every figure) and the checkpoint (JSON), both replaced
// atomically; and a reader of checkpoints whose errors name the key.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "pronk/rng.h"
#include "pronk/training.h"

namespace pronk::training_files {

constexpr const char* kCheckpointFormat = "pronk-train-checkpoint";
constexpr int kCheckpointVersion = 1;

// The log's columns, and a row's values in their order (NaN as null).
// The columns end with penalty_sum_mean and one penalty_NAME per penalty of
// the environment (`penalties`, the names of TrainingIteration::penalty_names).
std::vector<std::string> logColumns(const std::vector<std::string>& penalties);
std::vector<nlohmann::json> logValues(const TrainingIteration& row);
// The last validated row of a log, as far as its validation goes.
std::optional<TrainingIteration> lastValidation(const std::vector<std::vector<nlohmann::json>>& rows,
                                                const std::vector<std::string>& penalties);
// Whether a row holds a validation, and the row given `figures` as its validation.
bool rowValidated(const std::vector<nlohmann::json>& row, const std::vector<std::string>& penalties);
void setRowValidation(std::vector<nlohmann::json>& row, const JumpSetFigures& figures,
                      const std::vector<std::string>& penalties);
// Writes the CSV: the header, then one line per row (null as "nan").
void writeLog(const std::string& path, const std::vector<std::vector<nlohmann::json>>& rows,
              const std::vector<std::string>& penalties);

nlohmann::json rngJson(const Rng& rng);  // the four state words, 16 hex digits each

// `text` written beside `path` and renamed over it. Throws Error naming `what`.
void writeText(const std::string& path, const std::string& text, const std::string& what);
void writeJson(const std::string& path, const nlohmann::json& doc, const std::string& what);
// Throws InputError "PATH: ..." for a file that cannot be read or is not JSON.
nlohmann::json readJson(const std::string& path, const std::string& what);

// Reading a checkpoint: every problem is an InputError "PATH: KEY: message".
class JsonReader {
 public:
  explicit JsonReader(std::string path) : path_(std::move(path)) {}
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  const nlohmann::json& at(const nlohmann::json& object, const char* key) const;
  std::string string(const nlohmann::json& object, const char* key) const;
  long long integer(const nlohmann::json& object, const char* key) const;
  double number(const nlohmann::json& object, const char* key) const;
  Rng::State rng(const nlohmann::json& object, const char* key) const;

 private:
  std::string path_;
};

}  // namespace pronk::training_files
