// Running the `pronk` executable the way a user does, for the CLI tests.
#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace pronk_test {

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
};

// Runs a shell command line as it is: its exit status and output (stdout and stderr).
inline Outcome shell(const std::string& command_line) {
  Outcome out;
  FILE* pipe = popen((command_line + " 2>&1").c_str(), "r");
  if (!pipe) return out;
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) out.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

// Runs `pronk ARGS` and returns its exit status and output.
inline Outcome pronk(const std::string& args) { return shell(std::string(PRONK_EXE) + " " + args); }

#ifdef PRONK_MPIEXEC
// `mpirun` for two ranks as a test runs it: as root in a container, two ranks
// whatever the cores, and shared memory without the single-copy mechanism that
// a container's ptrace rules may forbid.
inline std::string mpirunTwo() {
  return std::string(PRONK_MPIEXEC) +
         " -np 2 --allow-run-as-root --oversubscribe --mca btl_vader_single_copy_mechanism none " + PRONK_EXE;
}
#endif

inline std::string source(const std::string& relative) { return std::string(PRONK_SOURCE_DIR) + "/" + relative; }
inline std::string cliScenario(const std::string& name) {
  return std::string(PRONK_CLI_TEST_DIR) + "/scenarios/" + name;
}

}  // namespace pronk_test
