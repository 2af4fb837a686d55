// replaceFile and readFile.
#include "file_replace.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pronk/error.h"
#include "pronk/file_io.h"

namespace pronk::learning_files {

void replaceFile(const std::string& path, const std::string& text, const std::string& what) {
  replaceFileAtomically(path, text, what);
}

std::string readFile(const std::string& path, const std::string& what) { return readInputFile(path, what); }

}  // namespace pronk::learning_files
