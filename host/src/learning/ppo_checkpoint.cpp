// PpoLearner checkpoints: all of a learner's state as JSON, read back into a
// learner that continues bit for bit. Doubles are written with nlohmann's
// shortest round-trip text, Rng words as 16 hex digits (JSON readers other
// than nlohmann may not keep 64-bit integers).
#include <cinttypes>
#include <cstdio>
#include <string>

#include "file_replace.h"
#include "json_text.h"
#include "pronk/error.h"
#include "pronk/ppo.h"

namespace pronk {

namespace {

using nlohmann::json;

constexpr const char* kFormat = "pronk-ppo-checkpoint";
constexpr int kVersion = 1;

json vectorJson(const Eigen::VectorXd& v) { return json(std::vector<double>(v.data(), v.data() + v.size())); }

const char* schemeName(MlpInit::Scheme scheme) {
  return scheme == MlpInit::Scheme::Orthogonal ? "orthogonal" : "scaled_uniform";
}

json initJson(const MlpInit& init) {
  return {{"scheme", schemeName(init.scheme)},
          {"hidden_gain", init.hidden_gain},
          {"output_gain", init.output_gain},
          {"zero_last_layer", init.zero_last_layer}};
}

json configJson(const PpoConfig& c) {
  return {{"actor_hidden_sizes", c.actor_hidden_sizes},
          {"critic_hidden_sizes", c.critic_hidden_sizes},
          {"activation", activationName(c.activation)},
          {"actor_init", initJson(c.actor_init)},
          {"critic_init", initJson(c.critic_init)},
          {"initial_std", c.initial_std},
          {"loss",
           {{"clip", c.loss.clip},
            {"value_loss_coefficient", c.loss.value_loss_coefficient},
            {"clip_value_loss", c.loss.clip_value_loss},
            {"entropy_coefficient", c.loss.entropy_coefficient}}},
          {"epochs", c.epochs},
          {"minibatches", c.minibatches},
          {"normalize_advantages", c.normalize_advantages},
          {"update_actor", c.update_actor},
          {"learning_rate", c.learning_rate},
          {"adaptive_learning_rate", c.adaptive_learning_rate},
          {"desired_kl", c.desired_kl},
          {"min_learning_rate", c.min_learning_rate},
          {"max_learning_rate", c.max_learning_rate},
          {"max_gradient_norm", c.max_gradient_norm},
          {"adam", {{"beta1", c.adam.beta1}, {"beta2", c.adam.beta2}, {"epsilon", c.adam.epsilon}}}};
}

json networkJson(const Mlp& mlp) {
  json layers = json::array();
  for (const MlpLayer& layer : mlp.layers()) {
    layers.push_back({{"activation", activationName(layer.activation)},
                      {"inputs", layer.weights.cols()},
                      {"outputs", layer.weights.rows()}});
  }
  return {{"layers", layers}, {"parameters", vectorJson(mlp.parameters())}};
}

json adamJson(const Adam& adam) {
  return {{"first_moment", vectorJson(adam.state().first_moment)},
          {"second_moment", vectorJson(adam.state().second_moment)},
          {"step", adam.state().step}};
}

std::string hexWord(std::uint64_t word) {
  char text[17];
  std::snprintf(text, sizeof text, "%016" PRIx64, word);
  return text;
}

// Reading: every problem names its key, "checkpoint: actor.parameters: ...".
class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& message) const {
    throw Error(name_ + ": " + path + ": " + message);
  }

  const json& at(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) fail(path, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) fail(join(path, key), "missing");
    return *it;
  }

  double number(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_number()) fail(join(path, key), "expected a number");
    return v.get<double>();
  }

  long long integer(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_number_integer()) fail(join(path, key), "expected an integer");
    return v.get<long long>();
  }

  bool boolean(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_boolean()) fail(join(path, key), "expected true or false");
    return v.get<bool>();
  }

  std::string string(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_string()) fail(join(path, key), "expected a string");
    return v.get<std::string>();
  }

  Eigen::VectorXd vector(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_array()) fail(join(path, key), "expected an array of numbers");
    Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_number()) fail(join(path, key) + "[" + std::to_string(i) + "]", "expected a number");
      out[static_cast<Eigen::Index>(i)] = v[i].get<double>();
    }
    return out;
  }

  std::vector<int> sizes(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    if (!v.is_array()) fail(join(path, key), "expected an array of integers");
    std::vector<int> out;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_number_integer()) fail(join(path, key) + "[" + std::to_string(i) + "]", "expected an integer");
      out.push_back(v[i].get<int>());
    }
    return out;
  }

  Activation activation(const json& object, const std::string& path, const char* key) const {
    const std::string name = string(object, path, key);
    const auto a = activationFromName(name);
    if (!a) fail(join(path, key), "unknown activation \"" + name + "\"");
    return *a;
  }

  MlpInit init(const json& object, const std::string& path, const char* key) const {
    const json& v = at(object, path, key);
    const std::string p = join(path, key);
    MlpInit init;
    const std::string scheme = string(v, p, "scheme");
    if (scheme == schemeName(MlpInit::Scheme::Orthogonal)) {
      init.scheme = MlpInit::Scheme::Orthogonal;
    } else if (scheme != schemeName(MlpInit::Scheme::ScaledUniform)) {
      fail(join(p, "scheme"), "unknown scheme \"" + scheme + "\"");
    }
    init.hidden_gain = number(v, p, "hidden_gain");
    init.output_gain = number(v, p, "output_gain");
    init.zero_last_layer = boolean(v, p, "zero_last_layer");
    return init;
  }

  PpoConfig config(const json& doc) const {
    const json& v = at(doc, "", "config");
    const std::string p = "config";
    PpoConfig c;
    c.actor_hidden_sizes = sizes(v, p, "actor_hidden_sizes");
    c.critic_hidden_sizes = sizes(v, p, "critic_hidden_sizes");
    c.activation = activation(v, p, "activation");
    c.actor_init = init(v, p, "actor_init");
    c.critic_init = init(v, p, "critic_init");
    c.initial_std = number(v, p, "initial_std");
    const json& loss = at(v, p, "loss");
    c.loss.clip = number(loss, "config.loss", "clip");
    c.loss.value_loss_coefficient = number(loss, "config.loss", "value_loss_coefficient");
    c.loss.clip_value_loss = boolean(loss, "config.loss", "clip_value_loss");
    c.loss.entropy_coefficient = number(loss, "config.loss", "entropy_coefficient");
    c.epochs = static_cast<int>(integer(v, p, "epochs"));
    c.minibatches = static_cast<int>(integer(v, p, "minibatches"));
    c.normalize_advantages = boolean(v, p, "normalize_advantages");
    if (v.contains("update_actor")) c.update_actor = boolean(v, p, "update_actor");  // since hindsight
    c.learning_rate = number(v, p, "learning_rate");
    c.adaptive_learning_rate = boolean(v, p, "adaptive_learning_rate");
    c.desired_kl = number(v, p, "desired_kl");
    c.min_learning_rate = number(v, p, "min_learning_rate");
    c.max_learning_rate = number(v, p, "max_learning_rate");
    c.max_gradient_norm = number(v, p, "max_gradient_norm");
    const json& adam = at(v, p, "adam");
    c.adam.beta1 = number(adam, "config.adam", "beta1");
    c.adam.beta2 = number(adam, "config.adam", "beta2");
    c.adam.epsilon = number(adam, "config.adam", "epsilon");
    return c;
  }

  Mlp network(const json& doc, const char* key) const {
    const json& v = at(doc, "", key);
    const json& layers = at(v, key, "layers");
    const std::string p = std::string(key) + ".layers";
    if (!layers.is_array() || layers.empty()) fail(p, "expected a non-empty array of layers");
    std::vector<MlpLayer> out;
    for (std::size_t l = 0; l < layers.size(); ++l) {
      const std::string at_l = p + "[" + std::to_string(l) + "]";
      const long long inputs = integer(layers[l], at_l, "inputs"), outputs = integer(layers[l], at_l, "outputs");
      if (inputs <= 0 || outputs <= 0) fail(at_l, "inputs and outputs must be > 0");
      out.push_back(MlpLayer{Eigen::MatrixXd::Zero(outputs, inputs), Eigen::VectorXd::Zero(outputs),
                             activation(layers[l], at_l, "activation")});
    }
    Mlp mlp = [&] {
      try {
        return Mlp(std::move(out));
      } catch (const Error& e) {
        fail(p, e.what());
      }
    }();
    const Eigen::VectorXd parameters = vector(v, key, "parameters");
    if (parameters.size() != mlp.parameterCount()) {
      fail(std::string(key) + ".parameters", std::to_string(parameters.size()) + " values, expected " +
                                                 std::to_string(mlp.parameterCount()) + " (the layers' weights and biases)");
    }
    if (!parameters.allFinite()) fail(std::string(key) + ".parameters", "a value is not finite");
    mlp.setParameters(parameters);
    return mlp;
  }

  Adam::State adam(const json& doc, const char* key) const {
    const json& v = at(doc, "", key);
    Adam::State s;
    s.first_moment = vector(v, key, "first_moment");
    s.second_moment = vector(v, key, "second_moment");
    s.step = integer(v, key, "step");
    return s;
  }

  Rng::State rng(const json& doc) const {
    const json& v = at(doc, "", "rng");
    if (!v.is_array() || v.size() != 4) fail("rng", "expected 4 words, each 16 hex digits");
    Rng::State s{};
    for (std::size_t i = 0; i < 4; ++i) {
      const std::string path = "rng[" + std::to_string(i) + "]";
      if (!v[i].is_string() || v[i].get<std::string>().size() != 16) fail(path, "expected 16 hex digits");
      const std::string word = v[i].get<std::string>();
      std::size_t used = 0;
      try {
        s[i] = std::stoull(word, &used, 16);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != word.size()) fail(path, "\"" + word + "\" is not 16 hex digits");
    }
    return s;
  }

 private:
  static std::string join(const std::string& path, const char* key) { return path.empty() ? key : path + "." + key; }
  std::string name_;
};

}  // namespace

nlohmann::json PpoLearner::checkpoint() const {
  json rng = json::array();
  for (std::uint64_t word : rng_.state()) rng.push_back(hexWord(word));
  return {{"format", kFormat},
          {"version", kVersion},
          {"config", configJson(config_)},
          {"observation_scaling", {{"mean", vectorJson(scaling_.mean())}, {"std", vectorJson(scaling_.std())}}},
          {"actor", networkJson(actor_.meanNetwork())},
          {"log_std", vectorJson(actor_.logStd())},
          {"critic", networkJson(critic_)},
          {"actor_adam", adamJson(actor_adam_)},
          {"critic_adam", adamJson(critic_adam_)},
          {"mean_fit_adam", adamJson(mean_fit_adam_)},
          {"learning_rate", learning_rate_},
          {"iteration", iteration_},
          {"rng", rng}};
}

PpoLearner PpoLearner::fromCheckpoint(const nlohmann::json& checkpoint) {
  const Reader r("checkpoint");
  if (!checkpoint.is_object() || !checkpoint.contains("format") || checkpoint["format"] != kFormat) {
    throw Error(std::string("checkpoint: format: not \"") + kFormat + "\": not a pronk PPO checkpoint");
  }
  if (r.integer(checkpoint, "", "version") != kVersion) {
    r.fail("version", "not supported; this pronk reads version " + std::to_string(kVersion));
  }
  try {
    const json& scaling = r.at(checkpoint, "", "observation_scaling");
    Parts parts{r.config(checkpoint),
                ObservationScaling(r.vector(scaling, "observation_scaling", "mean"),
                                   r.vector(scaling, "observation_scaling", "std")),
                GaussianPolicy(r.network(checkpoint, "actor"), r.vector(checkpoint, "", "log_std")),
                r.network(checkpoint, "critic"), Rng(0)};
    Rng::State rng = r.rng(checkpoint);
    parts.rng.setState(rng);
    PpoLearner learner(std::move(parts));
    learner.actor_adam_.setState(r.adam(checkpoint, "actor_adam"));
    learner.critic_adam_.setState(r.adam(checkpoint, "critic_adam"));
    // Written since fitMean; a checkpoint from before has a fresh one.
    if (checkpoint.contains("mean_fit_adam")) learner.mean_fit_adam_.setState(r.adam(checkpoint, "mean_fit_adam"));
    learner.learning_rate_ = r.number(checkpoint, "", "learning_rate");
    learner.iteration_ = r.integer(checkpoint, "", "iteration");
    return learner;
  } catch (const Error& e) {
    const std::string what = e.what();
    if (what.rfind("checkpoint: ", 0) == 0) throw;
    throw Error("checkpoint: " + what);  // a check of the parts themselves (sizes, config)
  }
}

void savePpoCheckpoint(const PpoLearner& learner, const std::string& path) {
  learning_files::replaceFile(path, learner.checkpoint().dump() + "\n", "checkpoint");
}

PpoLearner loadPpoCheckpoint(const std::string& path) {
  const std::string text = learning_files::readFile(path, "checkpoint");
  // A checkpoint is at most a few levels deep; deeper nesting is a damaged or
  // hostile file, refused before the recursive parse and copies.
  const policy_file::JsonLayout layout(text, 64);
  using Kind = policy_file::JsonLayout::Refusal::Kind;
  if (const auto& refusal = layout.refusal(); refusal && (refusal->kind == Kind::TooDeep || refusal->kind == Kind::TooLarge)) {
    throw InputError({path, policy_file::positionOf(text, refusal->offset).line}, refusal->message);
  }
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw InputError({path, 0}, std::string("invalid JSON: ") + e.what());
  }
  try {
    return PpoLearner::fromCheckpoint(doc);
  } catch (const Error& e) {
    throw InputError({path, 0}, e.what());
  }
}

}  // namespace pronk
