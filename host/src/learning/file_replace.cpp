// replaceFile and readFile.
#include "file_replace.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pronk/error.h"
#include "pronk/input_file.h"

namespace pronk::learning_files {

void replaceFile(const std::string& path, const std::string& text, const std::string& what) {
  const std::string partial = path + ".partial";
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

std::string readFile(const std::string& path, const std::string& what) { return readInputFile(path, what); }

}  // namespace pronk::learning_files
