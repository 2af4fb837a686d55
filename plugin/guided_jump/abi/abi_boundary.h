// The plugin's side of the C boundary: no C++ exception leaves a function the
// host calls. Errors become a status code and a message in the host's buffer.
#pragma once

#include <cstdio>
#include <exception>
#include <stdexcept>

#include "control/invalid_argument.h"
#include "pronk/plugin_abi.h"

namespace pronk::guided_jump {

inline void writeError(char* error, size_t error_size, const char* message) {
  if (error && error_size > 0) std::snprintf(error, error_size, "%s", message ? message : "");
}

// Runs `body` (returning void) and turns any exception into a status and a message.
template <class Body>
pronk_status guarded(char* error, size_t error_size, Body&& body) noexcept {
  try {
    body();
    return PRONK_OK;
  } catch (const InvalidArgument& e) {
    writeError(error, error_size, e.what());
    return PRONK_ERROR_INVALID_ARGUMENT;
  } catch (const std::exception& e) {
    writeError(error, error_size, e.what());
    return PRONK_ERROR_FAILED;
  } catch (...) {
    writeError(error, error_size, "unknown C++ exception in the guided_jump plugin");
    return PRONK_ERROR_FAILED;
  }
}

}  // namespace pronk::guided_jump
