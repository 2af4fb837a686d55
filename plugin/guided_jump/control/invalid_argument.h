// A caller mistake (a bad parameter, an action the method refuses, a call out
// of order): the C boundary (abi/abi_boundary.h) turns it into
// PRONK_ERROR_INVALID_ARGUMENT and its message.
#pragma once

#include <stdexcept>

namespace pronk::guided_jump {

class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace pronk::guided_jump
