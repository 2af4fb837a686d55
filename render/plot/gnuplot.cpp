// Running gnuplot on a script file (render/plot/gnuplot.h).
#include "render/plot/gnuplot.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "pronk/error.h"
#include "pronk/file_io.h"

extern char** environ;

namespace pronk::render::plot {
namespace {

namespace fs = std::filesystem;

std::string numberText(double v) {
  if (!std::isfinite(v)) return "NaN";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + '"';
}

GnuplotScript::GnuplotScript(const std::string& png, int width, int height) : png_(png) {
  text_ = "# Written by pronk; render again with: gnuplot " + fs::path(png).stem().string() + ".gp\n";
  text_ += "set terminal pngcairo size " + std::to_string(width) + "," + std::to_string(height) +
           " font \"DejaVu Sans,11\" noenhanced\n";
  // The PNG beside the script, wherever gnuplot is started from.
  text_ += "set output " + quoted(fs::path(png).filename().string()) + "\n";
}

GnuplotScript& GnuplotScript::line(const std::string& text) {
  text_ += text + "\n";
  return *this;
}

GnuplotScript& GnuplotScript::data(const std::string& name, const std::vector<std::vector<double>>& rows) {
  text_ += "$" + name + " << EOD\n";
  for (const std::vector<double>& row : rows) {
    for (size_t i = 0; i < row.size(); ++i) text_ += (i ? " " : "") + numberText(row[i]);
    text_ += "\n";
  }
  text_ += "EOD\n";
  return *this;
}

void render(const GnuplotScript& script, const std::string& script_path) {
  replaceFileAtomically(script_path, script.text(), "plot script");
  const fs::path dir = fs::absolute(fs::path(script_path)).parent_path();
  const std::string log = (dir / (fs::path(script_path).stem().string() + ".log")).string();
  const std::string png = (dir / fs::path(script.png()).filename()).string();
  checkReplaceable(png, "plot");
  checkReplaceable(log, "plot log");
  std::error_code ec;
  fs::remove(png, ec);

  // gnuplot runs in the script's directory (the PNG is named relative to it),
  // its stdout and stderr into NAME.log, stdin from /dev/null so that it never
  // waits for a terminal.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  const std::string name = fs::path(script_path).filename().string();
  char* argv[] = {const_cast<char*>("gnuplot"), const_cast<char*>(name.c_str()), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    throw Error("plot " + script_path + ": cannot run gnuplot (" + std::strerror(spawned) +
                "): install Debian's gnuplot-nox (scripts/setup.sh does)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string message;
  {
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    message = text.str();
  }
  const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (!ok && WIFEXITED(status) && WEXITSTATUS(status) == 127) {
    throw Error("plot " + script_path + ": gnuplot not found: install Debian's gnuplot-nox (scripts/setup.sh does)");
  }
  if (!ok || !fs::exists(png, ec) || fs::file_size(png, ec) == 0) {
    fs::remove(png, ec);  // gnuplot opens the output before it fails: no empty PNG is left
    throw Error("plot " + script_path + ": gnuplot failed" + (message.empty() ? std::string() : ":\n" + message));
  }
  // A clean run leaves no log; warnings stay beside the script.
  if (message.empty()) fs::remove(log, ec);
}

}  // namespace pronk::render::plot
