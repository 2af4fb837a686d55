// Reading an input file (scenario, URDF, policy, checkpoint, trace) as a user
// may give it: only a regular file, at most a bound in size, so that a FIFO
// does not block forever and /dev/zero does not fill the memory. Header-only:
// every reader module uses it, and it needs nothing but the standard library.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "pronk/error.h"

namespace pronk {

inline constexpr std::uintmax_t kMaxInputFileBytes = 256ull << 20;  // 256 MiB: far beyond any real input

// Throws InputError naming `path` and `what` ("scenario file", "URDF file" ...)
// unless it is a regular file of at most `max_bytes`.
inline void checkInputFile(const std::string& path, const std::string& what,
                           std::uintmax_t max_bytes = kMaxInputFileBytes) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError({path, 0}, what + " not found");
  if (!fs::is_regular_file(status)) {
    throw InputError({path, 0}, "the " + what + " is not a regular file (a directory, a device or a pipe)");
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size > max_bytes) {
    throw InputError({path, 0}, "the " + what + " is " + std::to_string(size) + " bytes, more than the " +
                                    std::to_string(max_bytes) + " this reader accepts");
  }
}

// The whole file, after checkInputFile.
inline std::string readInputFile(const std::string& path, const std::string& what,
                                 std::uintmax_t max_bytes = kMaxInputFileBytes) {
  checkInputFile(path, what, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0}, "cannot read the " + what + ": " + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace pronk
