// Files in and out, as every module needs them. In: an input file (scenario,
// URDF, policy, checkpoint) as a user may give it: only a regular file, at most
// a bound in size, so that a FIFO does not block forever and /dev/zero does
// not fill the memory. Out: a file a reader never sees half of (written beside
// it, then renamed over it), so that a full disk or a kill leaves the old file
// or the new one. Header-only: nothing but the standard library.
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

// Whether a writer may replace what is at PATH: nothing, a regular file or a
// symbolic link (the rename replaces the link, never what it points to); a
// directory, a device node, a FIFO or a socket is never replaced.
inline bool replaceable(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status there = fs::symlink_status(path, ec);
  return ec || !fs::exists(there) || fs::is_regular_file(there) || fs::is_symlink(there);
}
// Throws Error "will not replace the <what> PATH: ..." unless replaceable(PATH).
inline void checkReplaceable(const std::string& path, const std::string& what) {
  if (!replaceable(path)) {
    throw Error("will not replace the " + what + " " + path +
                ": it is not a regular file (a directory, a device or a pipe)");
  }
}

// Writes `text` to PATH.partial and renames it over PATH. Throws Error "cannot
// write the <what> PATH.partial: reason" or "cannot replace the <what> PATH:
// reason", and checkReplaceable's.
inline void replaceFileAtomically(const std::string& path, const std::string& text, const std::string& what) {
  checkReplaceable(path, what);
  const std::string partial = path + ".partial";
  checkReplaceable(partial, what);
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    if (!out) throw Error("cannot write the " + what + " " + partial + ": " + std::strerror(errno));
    out << text;
    out.close();
    if (!out) {
      std::filesystem::remove(partial);
      throw Error("cannot write the " + what + " " + partial + ": " + std::strerror(errno));
    }
  }
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (ec) {
    std::filesystem::remove(partial);
    throw Error("cannot replace the " + what + " " + path + ": " + ec.message());
  }
}

}  // namespace pronk
