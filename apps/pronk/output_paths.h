// The files and folders a command writes, checked against what is there before
// any work starts: something other than a regular file (a directory, a device
// node, a FIFO) is never replaced, a folder flag never names a file, and no
// output is one of the command's own inputs. Each refusal is a UsageError
// naming the flag(s): exit 2.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace pronk::cli {

// A file flag's output PATH (written beside and renamed over, or created).
void checkOutputFile(const std::string& path, const std::string& flag);

// checkOutputFile, then fails now, naming the flag and the file, if the file
// cannot be written later (its folder is created).
void checkWritableFile(const std::string& path, const std::string& flag);

// A folder flag's output DIR (created when missing).
void checkOutputDirectory(const std::string& dir, const std::string& flag);

// An input the command reads, as its flag names it ("FILE", "--policy").
struct NamedInput {
  std::string path;
  std::string flag;
};

// Refused when `output` (its flag) is, or would replace, one of `inputs`: the
// same file under any name (a hard link, a symbolic link, another path).
void checkNotAnInput(const std::string& output, const std::string& flag, const std::vector<NamedInput>& inputs);

// Refused when `path` (its flag) lies in the folder `dir` under a name that the
// command writes there itself (`taken`: results.json, a trace ...).
void checkNotAmongFolderFiles(const std::string& path, const std::string& flag, const std::string& dir,
                              const std::function<bool(const std::string& name)>& taken);

}  // namespace pronk::cli
