// Policy files (docs/policy-format.md): JSON text <-> MlpPolicy. Reading is
// strict: every key is known, typed and shaped, and every problem is an
// InputError at the line where the offending key is written.
#include <algorithm>
#include <climits>

#include <openssl/evp.h>

#include "file_replace.h"
#include "json_text.h"
#include "policy_checks.h"
#include "pronk/error.h"
#include "pronk/policy.h"

namespace pronk {

namespace {

using nlohmann::json;
using policy_file::JsonPath;
using policy_file::Problem;

constexpr const char* kFormat = "pronk-policy";
constexpr int kVersion = 1;          // a policy whose network output is the action
constexpr int kResidualVersion = 2;  // and one with a prior (a residual)
constexpr int kChecksumVersion = 3;  // either, with its checksum: what pronk writes, the newest this reader knows
constexpr const char* kChecksumKind = "sha256:";

// The checksum of a policy document: SHA-256 of its compact text with sorted
// keys (nlohmann's dump()) and without the checksum itself, as "sha256:" + hex.
std::string checksumOf(nlohmann::json doc) {
  doc.erase("checksum");
  const std::string text = doc.dump();
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(text.data(), text.size(), digest, &size, EVP_sha256(), nullptr) != 1) {
    throw Error("policy: OpenSSL could not compute a SHA-256");
  }
  static const char* hex = "0123456789abcdef";
  std::string out = kChecksumKind;
  for (unsigned int i = 0; i < size; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

// A JSON value as a message shows it: its type, and short scalars themselves.
std::string describe(const json& v) {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s.size() <= 40) return "string " + json(s).dump();
    // Cut before a UTF-8 character, not inside one: dump() throws on half a character.
    std::size_t cut = 40;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;
    return "string " + json(s.substr(0, cut)).dump() + "...";
  }
  if (v.is_number() || v.is_boolean()) return std::string(v.type_name()) + " " + v.dump();
  return v.type_name();
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

class PolicyReader {
 public:
  PolicyReader(const std::string& text, const std::string& name)
      : text_(text), name_(name), layout_(text, kMaxNesting) {}
  static constexpr int kMaxNesting = 64;  // a policy's own structure is 4 deep; provenance is free-form

  MlpPolicy read() {
    const json doc = parse();
    checkNoDuplicateKeys();
    const JsonPath root;
    if (!doc.is_object()) fail(root, "a policy file is a JSON object, this is " + describe(doc));

    const int version = checkFormatAndVersion(doc);
    std::vector<std::string> keys = {"format", "version", "description", "provenance", "observation_size",
                                     "action_size", "observation_normalization", "layers", "action_log_std"};
    if (version >= kResidualVersion) keys.insert(keys.begin() + 4, "prior");
    if (version >= kChecksumVersion) keys.push_back("checksum");
    checkKeys(doc, root, keys);
    if (version >= kChecksumVersion) checkChecksum(doc);

    const int observation_size = positiveInt(required(doc, root, "observation_size"), root.key("observation_size"));
    const int action_size = positiveInt(required(doc, root, "action_size"), root.key("action_size"));

    MlpPolicy policy(readLayers(required(doc, root, "layers"), root.key("layers")));
    if (policy.observationSize() != observation_size) {
      fail(root.key("observation_size"), std::to_string(observation_size) + ", but layers[0].weights has " +
                                             policy_file::counted(policy.observationSize(), "column") + " (inputs)");
    }
    if (policy.actionSize() != action_size) {
      const std::string last = "layers[" + std::to_string(policy.layers().size() - 1) + "].weights";
      fail(root.key("action_size"), std::to_string(action_size) + ", but " + last + " has " +
                                        policy_file::counted(policy.actionSize(), "row") + " (outputs)");
    }

    if (doc.contains("observation_normalization")) {
      const JsonPath at = root.key("observation_normalization");
      const json& n = doc["observation_normalization"];
      if (!n.is_object()) fail(at, "expected an object with mean and std, got " + describe(n));
      checkKeys(n, at, {"mean", "std"});
      Eigen::VectorXd mean = vector(required(n, at, "mean"), at.key("mean"));
      Eigen::VectorXd std = vector(required(n, at, "std"), at.key("std"));
      failIf(policy_file::normalizationProblem(mean, std, observation_size));
      policy.setObservationNormalization(std::move(mean), std::move(std));
    }
    if (doc.contains("action_log_std")) {
      Eigen::VectorXd log_std = vector(doc["action_log_std"], root.key("action_log_std"));
      failIf(policy_file::logStdProblem(log_std, action_size));
      policy.setActionLogStd(std::move(log_std));
    }
    if (doc.contains("description")) {
      const json& d = doc["description"];
      if (!d.is_string()) fail(root.key("description"), "expected a string, got " + describe(d));
      policy.setDescription(d.get<std::string>());
    }
    if (doc.contains("provenance")) {
      const json& p = doc["provenance"];
      if (!p.is_object()) fail(root.key("provenance"), "expected an object, got " + describe(p));
      policy.setProvenance(p);
    }
    if (doc.contains("prior")) policy.setPrior(readPrior(doc["prior"], root.key("prior")));
    return policy;
  }

 private:
  [[noreturn]] void failAt(std::size_t offset, const std::string& message) const {
    throw InputError({name_, policy_file::positionOf(text_, offset).line}, message);
  }

  // The message starts with the path of the key at fault.
  [[noreturn]] void fail(const JsonPath& path, const std::string& message) const {
    const std::string key = path.str();
    failAt(layout_.offsetOf(path), key.empty() ? message : key + ": " + message);
  }

  void failIf(const std::optional<Problem>& problem) const {
    if (problem) fail(problem->path, problem->message);
  }

  json parse() const {
    if (const auto& refusal = layout_.refusal()) {
      using Kind = policy_file::JsonLayout::Refusal::Kind;
      const std::string column = "column " + std::to_string(policy_file::positionOf(text_, refusal->offset).column);
      switch (refusal->kind) {
        case Kind::TooDeep:
        case Kind::TooLarge: failAt(refusal->offset, column + ": " + refusal->message);
        case Kind::Overflow: failAt(refusal->offset, column + ": " + refusal->message + " (beyond the range of a double)");
        case Kind::Syntax: failAt(refusal->offset, column + ": invalid JSON: " + refusal->message);
      }
    }
    return json::parse(text_);  // the layout's pass accepted it: nlohmann's parse does too
  }

  void checkNoDuplicateKeys() const {
    if (const auto& dup = layout_.duplicateKey()) {
      failAt(dup->second, dup->path.str() + ": duplicate key (first written on line " +
                              std::to_string(policy_file::positionOf(text_, dup->first).line) + ")");
    }
  }

  PolicyPrior readPrior(const json& v, const JsonPath& path) const {
    if (!v.is_object()) fail(path, "expected an object with kind and environment, got " + describe(v));
    checkKeys(v, path, {"kind", "environment"});
    PolicyPrior prior;
    const json& kind = required(v, path, "kind");
    if (kind != kPriorActionKind && kind != kAimPriorKind) {
      fail(path.key("kind"), describe(kind) + " is not a known prior (known: \"" + kPriorActionKind +
                                 "\", a residual over the environment's prior_action, and \"" + kAimPriorKind +
                                 "\", an aim correction of it)");
    }
    prior.kind = kind.get<std::string>();
    const json& environment = required(v, path, "environment");
    if (!environment.is_string() || environment.get<std::string>().empty()) {
      fail(path.key("environment"), "expected the environment's name, got " + describe(environment));
    }
    prior.environment = environment.get<std::string>();
    return prior;
  }

  // A version-3 file carries the checksum of everything else in it: a number
  // changed by hand or by a broken copy is refused, not flown.
  void checkChecksum(const json& doc) const {
    const JsonPath at = JsonPath().key("checksum");
    const json& c = required(doc, JsonPath(), "checksum");
    if (!c.is_string() || c.get<std::string>().rfind(kChecksumKind, 0) != 0) {
      fail(at, "expected a string \"" + std::string(kChecksumKind) + "<64 hex digits>\", got " + describe(c));
    }
    const std::string computed = checksumOf(doc);
    if (c.get<std::string>() != computed) {
      fail(at, c.get<std::string>() + " does not match the file's contents (" + computed +
                   "): the file was changed after it was written");
    }
  }

  // The file's version: 1, 2 or 3.
  int checkFormatAndVersion(const json& doc) const {
    const JsonPath format = JsonPath().key("format");
    if (!doc.contains("format")) {
      fail(format, "missing; a policy file says \"format\": \"" + std::string(kFormat) + "\"");
    }
    if (doc["format"] != kFormat) {
      fail(format, describe(doc["format"]) + " is not \"" + kFormat + "\": not a pronk policy file");
    }
    const JsonPath version = JsonPath().key("version");
    const json& v = required(doc, JsonPath(), "version");
    if (!v.is_number_integer()) fail(version, "expected an integer, got " + describe(v));
    if (!(v >= kVersion && v <= kChecksumVersion)) {
      fail(version, v.dump() + " is not supported; this pronk reads versions " + std::to_string(kVersion) + " to " +
                        std::to_string(kChecksumVersion));
    }
    return v.get<int>();
  }

  // Unknown keys are errors (a misspelt optional key would otherwise be
  // ignored); the first one written is reported.
  void checkKeys(const json& object, const JsonPath& path, const std::vector<std::string>& known) const {
    std::optional<std::pair<std::size_t, std::string>> first;
    for (const auto& item : object.items()) {
      if (std::find(known.begin(), known.end(), item.key()) != known.end()) continue;
      const std::size_t offset = layout_.offsetOf(path.key(item.key()));
      if (!first || offset < first->first) first = {offset, item.key()};
    }
    if (first) fail(path.key(first->second), "unknown key (known keys here: " + joined(known) + ")");
  }

  const json& required(const json& object, const JsonPath& path, const char* key) const {
    const auto it = object.find(key);
    if (it == object.end()) fail(path.key(key), "missing");
    return *it;
  }

  int positiveInt(const json& v, const JsonPath& path) const {
    if (!v.is_number_integer() || v.get<long long>() <= 0 || v.get<long long>() > INT_MAX) {
      fail(path, "expected a positive integer, got " + describe(v));
    }
    return v.get<int>();
  }

  double number(const json& v, const JsonPath& path) const {
    if (!v.is_number()) fail(path, "expected a number, got " + describe(v));
    return v.get<double>();
  }

  Eigen::VectorXd vector(const json& v, const JsonPath& path) const {
    if (!v.is_array()) fail(path, "expected an array of numbers, got " + describe(v));
    Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
    for (std::size_t i = 0; i < v.size(); ++i) out[static_cast<Eigen::Index>(i)] = number(v[i], path.index(i));
    return out;
  }

  // An array of rows, all as long as the first.
  Eigen::MatrixXd matrix(const json& v, const JsonPath& path) const {
    if (!v.is_array()) fail(path, "expected an array of rows, got " + describe(v));
    Eigen::MatrixXd out;
    for (std::size_t r = 0; r < v.size(); ++r) {
      const json& row = v[r];
      if (!row.is_array()) fail(path.index(r), "expected a row (an array of numbers), got " + describe(row));
      if (r == 0) out.resize(static_cast<Eigen::Index>(v.size()), static_cast<Eigen::Index>(row.size()));
      if (static_cast<Eigen::Index>(row.size()) != out.cols()) {
        fail(path.index(r), policy_file::counted(static_cast<long long>(row.size()), "column") + ", expected " +
                                std::to_string(out.cols()) + " as in row 0");
      }
      for (std::size_t c = 0; c < row.size(); ++c) {
        out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = number(row[c], path.index(r).index(c));
      }
    }
    return out;
  }

  std::vector<MlpLayer> readLayers(const json& v, const JsonPath& path) const {
    if (!v.is_array()) fail(path, "expected an array of layers, got " + describe(v));
    std::vector<MlpLayer> layers;
    for (std::size_t l = 0; l < v.size(); ++l) {
      const JsonPath at = path.index(l);
      const json& layer = v[l];
      if (!layer.is_object()) fail(at, "expected a layer object, got " + describe(layer));
      checkKeys(layer, at, {"weights", "bias", "activation"});
      MlpLayer out;
      out.weights = matrix(required(layer, at, "weights"), at.key("weights"));
      out.bias = vector(required(layer, at, "bias"), at.key("bias"));
      const json& a = required(layer, at, "activation");
      const std::string names = joined({activationName(Activation::Tanh), activationName(Activation::Relu),
                                        activationName(Activation::Elu), activationName(Activation::Linear)});
      if (!a.is_string()) fail(at.key("activation"), "expected one of " + names + ", got " + describe(a));
      const auto activation = activationFromName(a.get<std::string>());
      if (!activation) fail(at.key("activation"), "unknown activation " + a.dump() + " (known: " + names + ")");
      out.activation = *activation;
      layers.push_back(std::move(out));
    }
    failIf(policy_file::layersProblem(layers));
    return layers;
  }

  const std::string& text_;
  const std::string& name_;
  const policy_file::JsonLayout layout_;  // where each key is written, and what the text's parse refuses
};

// Pretty JSON whose flat arrays stay on one line: a weight row per line, so
// the file is readable and a line number points at a row.
template <class Json>
void writeValue(std::string& out, const Json& v, int indent) {
  const std::string inner(static_cast<std::size_t>(indent + 2), ' ');
  const std::string outer(static_cast<std::size_t>(indent), ' ');
  const bool nested = std::any_of(v.begin(), v.end(), [](const Json& e) { return e.is_structured(); });
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      out += first ? "" : ",\n";
      first = false;
      out += inner + Json(it.key()).dump() + ": ";
      writeValue(out, it.value(), indent + 2);
    }
    out += "\n" + outer + "}";
  } else if (v.is_array() && nested) {
    out += "[\n";
    for (std::size_t i = 0; i < v.size(); ++i) {
      out += (i ? ",\n" : "") + inner;
      writeValue(out, v[i], indent + 2);
    }
    out += "\n" + outer + "]";
  } else {
    out += v.dump();  // nlohmann writes doubles with the shortest text that reads back exactly
  }
}

nlohmann::ordered_json toJson(const Eigen::VectorXd& v) {
  auto out = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

}  // namespace

MlpPolicy parsePolicy(const std::string& text, const std::string& name) { return PolicyReader(text, name).read(); }

MlpPolicy loadPolicy(const std::string& path) {
  return parsePolicy(learning_files::readFile(path, "policy file"), path);
}

std::string policyToJson(const MlpPolicy& policy) {
  nlohmann::ordered_json doc;
  doc["format"] = kFormat;
  doc["version"] = kChecksumVersion;
  if (!policy.description().empty()) doc["description"] = policy.description();
  if (!policy.provenance().empty()) doc["provenance"] = nlohmann::ordered_json(policy.provenance());
  if (policy.prior()) {
    doc["prior"]["kind"] = policy.prior()->kind;
    doc["prior"]["environment"] = policy.prior()->environment;
  }
  doc["observation_size"] = policy.observationSize();
  doc["action_size"] = policy.actionSize();
  if (policy.hasObservationNormalization()) {
    doc["observation_normalization"]["mean"] = toJson(policy.observationMean());
    doc["observation_normalization"]["std"] = toJson(policy.observationStd());
  }
  auto& layers = doc["layers"] = nlohmann::ordered_json::array();
  for (const MlpLayer& layer : policy.layers()) {
    nlohmann::ordered_json l;
    l["activation"] = activationName(layer.activation);
    auto& rows = l["weights"] = nlohmann::ordered_json::array();
    for (Eigen::Index r = 0; r < layer.weights.rows(); ++r) rows.push_back(toJson(layer.weights.row(r).transpose()));
    l["bias"] = toJson(layer.bias);
    layers.push_back(std::move(l));
  }
  if (policy.hasActionLogStd()) doc["action_log_std"] = toJson(policy.actionLogStd());

  std::string out;
  try {
    // Over the numbers as the file's text gives them back (a reader parses them).
    doc["checksum"] = checksumOf(nlohmann::json::parse(doc.dump()));
    writeValue(out, doc, 0);
  } catch (const nlohmann::json::exception& e) {  // e.g. a description that is not UTF-8
    throw Error("policy: cannot be written as JSON: " + policy_file::nlohmannDetail(e.what()));
  }
  return out + "\n";
}

void savePolicy(const MlpPolicy& policy, const std::string& path) {
  learning_files::replaceFile(path, policyToJson(policy), "policy file");
}

}  // namespace pronk
