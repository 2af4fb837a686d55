// Reading the parameter values the host hands to create(): by name, with the
// factory's declared defaults for any the host left out, checked against the
// declaration (a host other than pronk's may not have checked them).
#pragma once

#include <string>
#include <vector>

#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

class ParamReader {
 public:
  // Throws InvalidArgument for a value whose name is not declared.
  ParamReader(const pronk_param_value* values, int32_t value_count, const pronk_param_decl* decls,
              int32_t decl_count);

  double real(const char* name) const;
  long long integer(const char* name) const;
  std::vector<double> vector(const char* name) const;
  // The text as given (STRING parameters), or the declared default.
  std::string string(const char* name) const;

 private:
  const pronk_param_decl& decl(const char* name) const;
  std::string text(const pronk_param_decl& d) const;
  void checkRange(const pronk_param_decl& d, double v) const;

  const pronk_param_value* values_;
  int32_t value_count_;
  const pronk_param_decl* decls_;
  int32_t decl_count_;
};

}  // namespace pronk::guided_jump
