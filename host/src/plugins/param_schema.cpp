// A factory's declared parameters checked against what a scenario sets: names,
// types, ranges and vector lengths, with defaults filled in.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <sstream>

#include "pronk/plugin_registry.h"

namespace pronk {

struct ResolvedParams::Storage {
  std::deque<std::string> names, values;  // a deque never moves its elements
  std::vector<pronk_param_value> view;
};

ResolvedParams::ResolvedParams() : storage_(std::make_unique<Storage>()) {}

ResolvedParams::ResolvedParams(const ResolvedParams& other) : ResolvedParams() {
  if (!other.storage_) return;
  for (size_t i = 0; i < other.storage_->names.size(); ++i) add(other.storage_->names[i], other.storage_->values[i]);
}

ResolvedParams::ResolvedParams(ResolvedParams&& other) noexcept = default;

ResolvedParams& ResolvedParams::operator=(ResolvedParams other) noexcept {
  storage_.swap(other.storage_);
  return *this;
}

ResolvedParams::~ResolvedParams() = default;

const pronk_param_value* ResolvedParams::data() const {
  return storage_ && !storage_->view.empty() ? storage_->view.data() : nullptr;
}

int32_t ResolvedParams::size() const { return storage_ ? static_cast<int32_t>(storage_->view.size()) : 0; }

const std::string* ResolvedParams::find(const std::string& name) const {
  if (!storage_) return nullptr;
  for (size_t i = 0; i < storage_->names.size(); ++i) {
    if (storage_->names[i] == name) return &storage_->values[i];
  }
  return nullptr;
}

void ResolvedParams::add(const std::string& name, const std::string& value) {
  if (!storage_) storage_ = std::make_unique<Storage>();
  storage_->names.push_back(name);
  storage_->values.push_back(value);
  storage_->view.push_back({storage_->names.back().c_str(), storage_->values.back().c_str()});
}

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

bool hasRange(const pronk_param_decl& d) { return d.min_value <= d.max_value; }

std::string rangeText(const pronk_param_decl& d) {
  std::string r = "[" + number(d.min_value) + ", " + number(d.max_value) + "]";
  if (d.unit && *d.unit) r += std::string(" ") + d.unit;
  return r;
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && isSpace(s[b])) ++b;
  while (e > b && isSpace(s[e - 1])) --e;
  return s.substr(b, e - b);
}

// The whole of `text` as a finite decimal number, the scenario attributes' rule
// (std::from_chars, general format: strtod would also take hex, "0x1.8p0").
bool parseReal(const std::string& text, double* out) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin < end && *begin == '+') ++begin;  // from_chars takes no '+'
  if (begin == end) return false;
  double v = 0;
  const auto [stop, error] = std::from_chars(begin, end, v, std::chars_format::general);
  if (error != std::errc() || stop != end || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

bool parseInteger(const std::string& text, long long* out) {
  if (text.empty()) return false;
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end != text.c_str() + text.size() || errno == ERANGE) return false;
  *out = v;
  return true;
}

}  // namespace

std::string checkParamValue(const pronk_param_decl& decl, const std::string& raw) {
  const std::string text = trim(raw);
  switch (decl.type) {
    case PRONK_PARAM_STRING:
      return "";
    case PRONK_PARAM_REAL: {
      double v = 0;
      if (!parseReal(text, &v)) return "'" + raw + "' is not a number";
      if (hasRange(decl) && (v < decl.min_value || v > decl.max_value)) {
        return number(v) + " is out of range " + rangeText(decl);
      }
      return "";
    }
    case PRONK_PARAM_INT: {
      long long v = 0;
      if (!parseInteger(text, &v)) {
        double r = 0;
        return parseReal(text, &r) ? "'" + raw + "' is not an integer" : "'" + raw + "' is not a number";
      }
      if (hasRange(decl) && (static_cast<double>(v) < decl.min_value || static_cast<double>(v) > decl.max_value)) {
        return std::to_string(v) + " is out of range " + rangeText(decl);
      }
      return "";
    }
    case PRONK_PARAM_VECTOR: {
      std::istringstream in(text);
      std::string item;
      std::vector<double> values;
      while (in >> item) {
        double v = 0;
        if (!parseReal(item, &v)) return "'" + item + "' (element " + std::to_string(values.size() + 1) + ") is not a number";
        values.push_back(v);
      }
      if (decl.vector_size > 0 && values.size() != decl.vector_size) {
        return "needs " + std::to_string(decl.vector_size) + " numbers, got " + std::to_string(values.size()) + " ('" +
               raw + "')";
      }
      for (size_t i = 0; i < values.size(); ++i) {
        if (hasRange(decl) && (values[i] < decl.min_value || values[i] > decl.max_value)) {
          return "element " + std::to_string(i + 1) + " (" + number(values[i]) + ") is out of range " + rangeText(decl);
        }
      }
      return "";
    }
    default:
      return "parameter type " + std::to_string(decl.type) + " is unknown";
  }
}

const std::vector<std::string>& platformPropertyNames() {
  static const std::vector<std::string> names = {"stance", "kp", "kd"};
  return names;
}

uint32_t platformPropertyType(const std::string& name) {
  return name == "stance" ? PRONK_PARAM_VECTOR : PRONK_PARAM_REAL;
}

std::optional<PlatformValue> platformValue(const PlatformSpec& platform, const std::string& name) {
  // Shortest text that reads back as the same double.
  auto text = [](double v) {
    char buffer[32];
    const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
    return std::string(buffer, r.ptr);
  };
  const SourceLocation& joints = platform.joints_where.file.empty() ? platform.where : platform.joints_where;
  if (name == "kp") return PlatformValue{text(platform.joints.kp), joints};
  if (name == "kd") return PlatformValue{text(platform.joints.kd), joints};
  if (name == "stance" && !platform.stance.empty()) {
    std::string joined;
    for (double q : platform.stance) joined += (joined.empty() ? "" : " ") + text(q);
    return PlatformValue{joined, platform.initial_where.file.empty() ? platform.where : platform.initial_where};
  }
  return std::nullopt;
}

ResolvedParams resolveParams(const pronk_factory& factory, const std::vector<ParamSetting>& settings,
                             const SourceLocation& owner, const PlatformSpec* platform) {
  const std::string who = factoryKindName(factory.kind) + " '" + factory.name + "'";
  auto declOf = [&](const std::string& name) -> const pronk_param_decl* {
    for (int32_t i = 0; i < factory.param_count; ++i) {
      if (name == factory.params[i].name) return &factory.params[i];
    }
    return nullptr;
  };

  // Every setting: a declared name, set once, with a valid value.
  for (size_t i = 0; i < settings.size(); ++i) {
    const ParamSetting& s = settings[i];
    const pronk_param_decl* decl = declOf(s.name);
    if (!decl) {
      std::string known;
      for (int32_t k = 0; k < factory.param_count; ++k) known += (k ? ", " : "") + std::string(factory.params[k].name);
      throw InputError(s.where, "unknown parameter '" + s.name + "' for " + who + "; known: " +
                                    (known.empty() ? "(none)" : known));
    }
    for (size_t j = 0; j < i; ++j) {
      if (settings[j].name == s.name) {
        throw InputError(s.where, "parameter '" + s.name + "' of " + who + " is set twice (first at " +
                                      settings[j].where.str() + ")");
      }
    }
    const std::string why = checkParamValue(*decl, s.value);
    if (!why.empty()) throw InputError(s.where, "parameter '" + s.name + "' of " + who + ": " + why);
  }

  // Every declared parameter, in declaration order.
  ResolvedParams out;
  for (int32_t i = 0; i < factory.param_count; ++i) {
    const pronk_param_decl& d = factory.params[i];
    const ParamSetting* set = nullptr;
    for (const ParamSetting& s : settings) {
      if (s.name == d.name) set = &s;
    }
    const std::optional<PlatformValue> from_platform =
        platform && d.platform_default ? platformValue(*platform, d.platform_default) : std::nullopt;
    if (set) {
      out.add(d.name, set->value);
    } else if (from_platform) {
      const std::string why = checkParamValue(d, from_platform->text);
      if (!why.empty()) {
        throw InputError(from_platform->where, "the platform's " + std::string(d.platform_default) + " '" +
                                                   from_platform->text + "' for parameter '" + d.name + "' of " +
                                                   who + ": " + why + " (set the parameter in the scenario)");
      }
      out.add(d.name, from_platform->text);
    } else if (d.required || !d.default_value) {
      std::string what = "missing required parameter '" + std::string(d.name) + "' of " + who;
      if (d.description && *d.description) what += " (" + std::string(d.description) + ")";
      throw InputError(owner, what);
    } else {
      out.add(d.name, d.default_value);
    }
  }
  return out;
}

}  // namespace pronk
