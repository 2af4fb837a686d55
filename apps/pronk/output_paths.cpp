#include "output_paths.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include "commands.h"
#include "pronk/file_io.h"

namespace pronk::cli {

namespace fs = std::filesystem;

namespace {

std::string kindOf(const fs::file_status& s) {
  switch (s.type()) {
    case fs::file_type::directory: return "a directory";
    case fs::file_type::block:
    case fs::file_type::character: return "a device";
    case fs::file_type::fifo: return "a pipe";
    case fs::file_type::socket: return "a socket";
    default: return "not a regular file";
  }
}

}  // namespace

void checkOutputFile(const std::string& path, const std::string& flag) {
  if (replaceable(path)) return;  // what every writer takes (pronk/file_io.h)
  std::error_code ec;
  const fs::file_status there = fs::symlink_status(path, ec);
  throw UsageError(flag + " " + path + ": " + kindOf(there) + " is there; pronk writes a regular file and will not "
                   "replace it: give a file name");
}

void checkWritableFile(const std::string& path, const std::string& flag) {
  checkOutputFile(path, flag);
  std::error_code ec;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);
  if (ec) throw UsageError(flag + " " + path + ": cannot create its folder: " + ec.message());
  const bool existed = fs::exists(fs::symlink_status(path, ec));
  std::ofstream probe(path, std::ios::app);
  if (!probe) throw UsageError(flag + " " + path + ": cannot write the file");
  probe.close();
  if (!existed) fs::remove(path, ec);
}

void checkOutputDirectory(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  const fs::file_status there = fs::status(dir, ec);
  if (ec || !fs::exists(there) || fs::is_directory(there)) return;
  throw UsageError(flag + " " + dir + ": " +
                   (fs::is_regular_file(there) ? std::string("a file") : kindOf(there)) +
                   " is there; pronk writes a folder: give a folder name");
}

void checkNotAnInput(const std::string& output, const std::string& flag, const std::vector<NamedInput>& inputs) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(output, ec))) return;  // nothing there: no input to destroy
  for (const NamedInput& in : inputs) {
    if (in.path.empty()) continue;
    std::error_code same_ec;
    if (fs::equivalent(output, in.path, same_ec) && !same_ec) {
      throw UsageError(flag + " " + output + " is the command's own input " + in.flag + " " + in.path +
                       ": writing it would destroy it; give another " + flag);
    }
  }
}

void checkNotAmongFolderFiles(const std::string& path, const std::string& flag, const std::string& dir,
                              const std::function<bool(const std::string& name)>& taken) {
  if (path.empty() || dir.empty()) return;
  std::error_code ec;
  const fs::path p = fs::weakly_canonical(fs::absolute(path), ec);
  const fs::path d = fs::weakly_canonical(fs::absolute(dir), ec);
  if (ec || p.parent_path() != d || !taken(p.filename().string())) return;
  throw UsageError(flag + " " + path + ": the command writes its own " + p.filename().string() + " in " + dir +
                   ": give the file another name");
}

}  // namespace pronk::cli
