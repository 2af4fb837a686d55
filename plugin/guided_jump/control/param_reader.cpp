#include "control/param_reader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "control/invalid_argument.h"

namespace pronk::guided_jump {
namespace {

bool parseReal(const std::string& text, double* out) {
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (end == text.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

}  // namespace

ParamReader::ParamReader(const pronk_param_value* values, int32_t value_count, const pronk_param_decl* decls,
                         int32_t decl_count)
    : values_(values), value_count_(values ? value_count : 0), decls_(decls), decl_count_(decl_count) {
  for (int32_t i = 0; i < value_count_; ++i) {
    if (!values_[i].name || !values_[i].value) throw InvalidArgument("parameter " + std::to_string(i) + " is NULL");
    decl(values_[i].name);  // throws for an unknown name
  }
}

const pronk_param_decl& ParamReader::decl(const char* name) const {
  for (int32_t i = 0; i < decl_count_; ++i) {
    if (std::strcmp(decls_[i].name, name) == 0) return decls_[i];
  }
  throw InvalidArgument(std::string("unknown parameter '") + name + "'");
}

std::string ParamReader::text(const pronk_param_decl& d) const {
  for (int32_t i = 0; i < value_count_; ++i) {
    if (std::strcmp(values_[i].name, d.name) == 0) return values_[i].value;
  }
  return d.default_value ? d.default_value : "";
}

void ParamReader::checkRange(const pronk_param_decl& d, double v) const {
  if (d.min_value <= d.max_value && (v < d.min_value || v > d.max_value)) {
    std::ostringstream s;
    s << "parameter '" << d.name << "': " << v << " is out of range [" << d.min_value << ", " << d.max_value << "]";
    throw InvalidArgument(s.str());
  }
}

double ParamReader::real(const char* name) const {
  const pronk_param_decl& d = decl(name);
  const std::string t = text(d);
  double v = 0;
  if (!parseReal(t, &v)) throw InvalidArgument(std::string("parameter '") + name + "': '" + t + "' is not a number");
  checkRange(d, v);
  return v;
}

long long ParamReader::integer(const char* name) const {
  const pronk_param_decl& d = decl(name);
  const std::string t = text(d);
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(t.c_str(), &end, 10);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (end == t.c_str() || *end != '\0' || errno == ERANGE) {
    throw InvalidArgument(std::string("parameter '") + name + "': '" + t + "' is not an integer");
  }
  checkRange(d, static_cast<double>(v));
  return v;
}

std::vector<double> ParamReader::vector(const char* name) const {
  const pronk_param_decl& d = decl(name);
  std::istringstream in(text(d));
  std::vector<double> out;
  std::string item;
  while (in >> item) {
    double v = 0;
    if (!parseReal(item, &v)) throw InvalidArgument(std::string("parameter '") + name + "': '" + item + "' is not a number");
    checkRange(d, v);
    out.push_back(v);
  }
  if (d.vector_size > 0 && out.size() != d.vector_size) {
    throw InvalidArgument(std::string("parameter '") + name + "' needs " + std::to_string(d.vector_size) +
                          " numbers, got " + std::to_string(out.size()));
  }
  return out;
}

std::string ParamReader::string(const char* name) const { return text(decl(name)); }

}  // namespace pronk::guided_jump
