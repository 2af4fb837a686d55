// PNG plots through gnuplot (Debian's gnuplot-nox, pngcairo terminal): a plot
// is a self-contained gnuplot script (its data inline as datablocks), kept
// beside the PNG so that a user can restyle and re-render it with
// `gnuplot NAME.gp`. gnuplot runs as a child process: a plotting failure is an
// error with gnuplot's own message, never a crash of the run that made the data.
#pragma once

#include <string>
#include <vector>

namespace pronk::render::plot {

// A script under construction. Text given to quoted() is escaped for a
// double-quoted gnuplot string; every script renders without enhanced text, so
// that names with '_' print as they are.
class GnuplotScript {
 public:
  // `png` is the output file; the script sets the pngcairo terminal and size.
  GnuplotScript(const std::string& png, int width, int height);
  GnuplotScript& line(const std::string& text);  // one command, as written
  // An inline datablock $NAME: one row per entry, numbers separated by spaces
  // (NaN is written as "NaN", which gnuplot skips).
  GnuplotScript& data(const std::string& name, const std::vector<std::vector<double>>& rows);
  const std::string& text() const { return text_; }
  const std::string& png() const { return png_; }

 private:
  std::string png_;
  std::string text_;
};

// `text` as a double-quoted gnuplot string literal.
std::string quoted(const std::string& text);

// Writes the script to `script_path` and runs gnuplot on it, which writes the
// PNG. Throws pronk::Error naming the script, with gnuplot's message, when
// gnuplot is missing, fails, or writes no PNG.
void render(const GnuplotScript& script, const std::string& script_path);

}  // namespace pronk::render::plot
