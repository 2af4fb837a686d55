#include <filesystem>
#include <cstdlib>

#include "commands.h"

namespace pronk::cli {

std::string dataDirectory() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("PRONK_DATA_DIR"); env && *env) return env;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "pronk";
    if (fs::exists(installed / "scenarios", ec)) return installed.string();
  }
  return PRONK_SOURCE_DIR;  // running from a build tree
}

}  // namespace pronk::cli
