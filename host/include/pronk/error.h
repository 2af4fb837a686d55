// Errors the host reports to users: one exception type carrying a message that
// already names its origin (a file and line, a flag, a body, a joint).
#pragma once

#include <stdexcept>
#include <string>

namespace pronk {

// Where something was written in an input file; line 0 = the whole file.
struct SourceLocation {
  std::string file;
  int line = 0;
  // "file:line" (or "file" when line is 0).
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An input-file error, whose message is "file:line: message".
class InputError : public Error {
 public:
  InputError(const SourceLocation& where, const std::string& message)
      : Error(where.str() + ": " + message), where_(where) {}
  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

}  // namespace pronk
