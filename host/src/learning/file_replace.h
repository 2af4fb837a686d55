// Writing a file so that a reader never sees half of it: the text goes beside
// the target (PATH.partial) and is renamed over it. Policy files and training
// checkpoints both need this.
#pragma once

#include <string>

namespace pronk::learning_files {

// Throws pronk::Error "cannot write the <what> PATH.partial: reason" or
// "cannot replace the <what> PATH: reason".
void replaceFile(const std::string& path, const std::string& text, const std::string& what);

// The whole file; throws pronk::InputError "PATH: cannot read the <what>: reason".
std::string readFile(const std::string& path, const std::string& what);

}  // namespace pronk::learning_files
