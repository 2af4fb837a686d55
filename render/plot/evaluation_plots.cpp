// The evaluation figures of a set (render/plot/evaluation_plots.h), each a
// gnuplot script with its data inline.
#include "render/plot/evaluation_plots.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "render/plot/gnuplot.h"

namespace pronk::render::plot {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = 180.0 / M_PI;
constexpr const char* kLandedColour = "#1a9641";  // green, as the paper's landed jumps
constexpr const char* kFailedColour = "#d7191c";  // red, as its failures
constexpr const char* kRefusedColour = "gray45";

bool isFlat(const JumpRow& r) { return std::abs(r.target_z) < 1e-6; }
double targetDistance(const JumpRow& r) { return std::hypot(r.target_x, r.target_y); }

std::string format(const char* f, double v) {
  char text[64];
  std::snprintf(text, sizeof text, f, v);
  return text;
}

std::string percent(size_t n, size_t of) { return of ? format("%.1f %%", 100.0 * n / of) : "-"; }

// The first title line every figure carries: robot, policy, jumps, set.
std::string headline(const PlotContext& c, size_t jumps, const std::string& what) {
  return c.robot + ", policy " + c.policy + ": " + what + " (" + std::to_string(jumps) + " jumps, " + c.set + ")";
}

std::string countLine(const std::vector<JumpRow>& rows, const PlotContext& c) {
  const SetSummary s = summarize(rows, c.radius);
  std::string out = percent(s.within, s.jumps) + " within " + format("%.2g", c.radius) + " m";
  if (s.landed) out += ", median " + format("%.1f", 100 * s.median) + " cm, mean " + format("%.1f", 100 * s.mean) + " cm";
  out += ", " + std::to_string(s.failed) + " failed, " + std::to_string(s.rejected) + " refused";
  return out;
}

// The style every figure shares.
void commonStyle(GnuplotScript& g) {
  g.line("set grid lc rgb \"gray80\"");
  g.line("set key outside below horizontal spacing 1.2");
  g.line("set tics out nomirror");
}

// An empty datablock would make gnuplot warn or fail: series without rows are
// left out of the plot command.
struct Series {
  std::string name, style, title;
  std::vector<std::vector<double>> rows;
};

std::string plotCommand(GnuplotScript& g, const std::vector<Series>& series, const std::string& first = "") {
  std::string command = "plot " + first;
  bool any = !first.empty();
  for (const Series& s : series) {
    if (s.rows.empty()) continue;
    g.data(s.name, s.rows);
    command += std::string(any ? ", \\\n     " : "") + "$" + s.name + " " + s.style + " title " + quoted(s.title);
    any = true;
  }
  return any ? command : "";
}

std::string regionMap(const std::vector<JumpRow>& rows, const PlotContext& c, const std::string& dir) {
  const std::string png = (fs::path(dir) / "region_map.png").string();
  GnuplotScript g(png, 1100, 820);
  commonStyle(g);
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  Series landed{"landed", "using 1:2:3 with points pt 7 ps 0.8 lc palette", "landed (colour: landing error)", {}};
  Series failed{"failed", std::string("using 1:2 with points pt 2 ps 1.0 lw 1.5 lc rgb \"") + kFailedColour + "\"", "", {}};
  Series refused{"refused", std::string("using 1:2 with points pt 6 ps 1.0 lc rgb \"") + kRefusedColour + "\"", "", {}};
  std::vector<std::vector<double>> all;  // log10 error for the contour; a failure or refusal counts as 1 m
  for (const JumpRow& r : rows) {
    x0 = std::min(x0, r.target_x), x1 = std::max(x1, r.target_x);
    y0 = std::min(y0, r.target_y), y1 = std::max(y1, r.target_y);
    const double e = r.landed() && std::isfinite(r.error) ? std::max(r.error, 1e-4) : 1.0;
    all.push_back({r.target_x, r.target_y, std::log10(std::min(e, 1.0))});
    if (r.landed()) landed.rows.push_back({r.target_x, r.target_y, std::max(r.error, 1e-4)});
    else (r.status == "rejected" ? refused : failed).rows.push_back({r.target_x, r.target_y});
  }
  failed.title = "failed (" + std::to_string(failed.rows.size()) + ")";
  refused.title = "refused by the safety filter (" + std::to_string(refused.rows.size()) + ")";
  g.line("set title " + quoted(headline(c, rows.size(), "landing error over flat targets") + "\n" + countLine(rows, c)));
  g.line("set xlabel \"target x [m] (forward)\"");
  g.line("set ylabel \"target y [m] (left)\"");
  g.line("set size ratio -1");
  g.line("set xrange [" + format("%g", x0 - 0.05) + ":" + format("%g", x1 + 0.05) + "]");
  g.line("set yrange [" + format("%g", y0 - 0.05) + ":" + format("%g", y1 + 0.05) + "]");
  g.line("set logscale cb");
  g.line("set cbrange [0.005:1]");
  g.line("set cbtics (\"0.5 cm\" 0.005, \"1 cm\" 0.01, \"2 cm\" 0.02, \"5 cm\" 0.05, \"10 cm\" 0.1, \"20 cm\" 0.2, "
         "\"50 cm\" 0.5, \"1 m\" 1)");
  g.line("set cblabel \"landing error, log scale\"");
  g.line("set palette defined (0 \"#006837\", 0.35 \"#66bd63\", 0.6 \"#fee08b\", 0.8 \"#f46d43\", 1 \"#a50026\")");
  // The contour of the accuracy threshold: log errors averaged onto a grid
  // (a Gaussian kernel of 7 cm), traced at log10(radius) into a table.
  g.data("all", all);
  g.line("set table $contour");
  g.line("unset surface");
  g.line("set contour base");
  g.line("set cntrparam levels discrete " + format("%.6g", std::log10(c.radius)));
  g.line("set dgrid3d 73,49 gauss 0.07,0.07");
  g.line("splot $all using 1:2:3 notitle");
  g.line("unset table");
  g.line("unset dgrid3d");
  g.line("unset contour");
  g.line("set surface");
  g.data("start", {{0.0, 0.0}});
  // The legend names the contour, or says that there is none: where the
  // averaged error stays under the radius everywhere (a large sample of a good
  // policy), the table holds only its two header lines, and the line is left out
  // of the plot (a macro) rather than vanishing unsaid.
  g.line("contour_title = |$contour| > 2 ? " +
         quoted(format("%.2g m contour (interpolated; failures count as 1 m)", c.radius)) + " : " +
         quoted(format("%.2g m contour: none (the interpolated error stays under it)", c.radius)));
  g.line("contour_lines = |$contour| > 2 ? '$contour using 1:2 with lines lw 2.5 lc rgb \"black\" notitle,' : ''");
  const std::string first = "@contour_lines keyentry with lines lw 2.5 lc rgb \"black\" title contour_title";
  std::string command = plotCommand(g, {landed, failed, refused}, first);
  command += ", \\\n     $start using 1:2 with points pt 9 ps 2.2 lc rgb \"blue\" title \"start\"";
  g.line(command);
  render(g, (fs::path(dir) / "region_map.gp").string());
  return png;
}

std::string distancePlot(const std::vector<JumpRow>& rows, const PlotContext& c, const std::string& dir) {
  const std::string png = (fs::path(dir) / "distance.png").string();
  GnuplotScript g(png, 1300, 640);
  commonStyle(g);
  double dmax = 0.1;
  Series fwd_ok{"forward_landed", "", "", {}}, fwd_fail{"forward_failed", "", "", {}};
  Series bwd_ok{"backward_landed", "", "", {}}, bwd_fail{"backward_failed", "", "", {}};
  size_t forward = 0, backward = 0;
  for (const JumpRow& r : rows) {
    if (r.status == "rejected") continue;
    const double target = targetDistance(r), landed = std::hypot(r.landed_x, r.landed_y);
    if (!std::isfinite(landed)) continue;
    dmax = std::max({dmax, target, landed});
    const bool is_forward = r.target_x >= 0;
    (is_forward ? forward : backward)++;
    Series& s = r.status == "failed" ? (is_forward ? fwd_fail : bwd_fail) : (is_forward ? fwd_ok : bwd_ok);
    s.rows.push_back({target, landed});
  }
  for (Series* s : {&fwd_ok, &bwd_ok}) {
    s->style = std::string("using 1:2 with points pt 7 ps 0.7 lc rgb \"") + kLandedColour + "\"";
    s->title = "landed (" + std::to_string(s->rows.size()) + ")";
  }
  for (Series* s : {&fwd_fail, &bwd_fail}) {
    s->style = std::string("using 1:2 with points pt 2 ps 0.8 lc rgb \"") + kFailedColour + "\"";
    s->title = "failed (" + std::to_string(s->rows.size()) + ")";
  }
  const std::string range = "[0:" + format("%.3g", 1.05 * dmax) + "]";
  g.line("set multiplot layout 1,2 title " +
         quoted(headline(c, rows.size(), "landed against target distance") + "\n" + countLine(rows, c) +
                "; refused jumps not shown"));
  g.line("set xlabel \"target distance [m]\"");
  g.line("set ylabel \"landed distance [m]\"");
  g.line("set xrange " + range);
  g.line("set yrange " + range);
  g.line("set size ratio -1");
  g.line("set key inside top left vertical box opaque");
  const std::string diagonal = "x with lines dt 2 lw 1.5 lc rgb \"black\" title \"landed = target\"";
  g.line("set title " + quoted("forward targets (x >= 0): " + std::to_string(forward) + " jumps"));
  g.line(plotCommand(g, {fwd_ok, fwd_fail}, diagonal));
  g.line("set title " + quoted("backward targets (x < 0): " + std::to_string(backward) + " jumps"));
  g.line(plotCommand(g, {bwd_ok, bwd_fail}, diagonal));
  g.line("unset multiplot");
  render(g, (fs::path(dir) / "distance.gp").string());
  return png;
}

std::string heightMaps(const std::vector<JumpRow>& rows, const PlotContext& c, const std::string& dir) {
  const std::string png = (fs::path(dir) / "heights.png").string();
  GnuplotScript g(png, 1400, 600);
  commonStyle(g);
  // Per (x, y) target cell (to the millimetre): the highest up-jump and the
  // lowest down-jump that landed within the radius.
  struct Cell {
    double x = 0, y = 0, up = NAN, down = NAN;
    bool tried_up = false, tried_down = false;
  };
  std::map<std::pair<long, long>, Cell> cells;
  double zmax = 0.05, zmin = -0.05;
  for (const JumpRow& r : rows) {
    Cell& cell = cells[{std::lround(r.target_x * 1000), std::lround(r.target_y * 1000)}];
    cell.x = r.target_x, cell.y = r.target_y;
    const bool good = r.landed() && r.error <= c.radius;
    if (r.target_z > 0) {
      cell.tried_up = true;
      zmax = std::max(zmax, r.target_z);
      if (good && !(r.target_z <= cell.up)) cell.up = r.target_z;
    } else if (r.target_z < 0) {
      cell.tried_down = true;
      zmin = std::min(zmin, r.target_z);
      if (good && !(r.target_z >= cell.down)) cell.down = r.target_z;
    }
  }
  Series up{"up", "using 1:2:3 with points pt 5 ps 2.6 lc palette", "highest landed (colour)", {}};
  Series up_none{"up_none", "using 1:2 with points pt 2 ps 1.4 lw 2 lc rgb \"black\"", "", {}};
  Series down{"down", "using 1:2:3 with points pt 5 ps 2.6 lc palette", "lowest landed (colour)", {}};
  Series down_none{"down_none", "using 1:2 with points pt 2 ps 1.4 lw 2 lc rgb \"black\"", "", {}};
  for (const auto& [key, cell] : cells) {
    if (cell.tried_up) (std::isfinite(cell.up) ? up.rows.push_back({cell.x, cell.y, cell.up}) : up_none.rows.push_back({cell.x, cell.y}));
    if (cell.tried_down)
      (std::isfinite(cell.down) ? down.rows.push_back({cell.x, cell.y, cell.down}) : down_none.rows.push_back({cell.x, cell.y}));
  }
  up_none.title = "no up-jump landed (" + std::to_string(up_none.rows.size()) + ")";
  down_none.title = "no down-jump landed (" + std::to_string(down_none.rows.size()) + ")";
  g.line("set multiplot layout 1,2 title " +
         quoted(headline(c, rows.size(), "height maps") + "\n" + countLine(rows, c) + "; landed = within " +
                format("%.2g", c.radius) + " m"));
  g.line("set xlabel \"target x [m] (forward)\"");
  g.line("set ylabel \"target y [m] (left)\"");
  g.line("set size ratio -1");
  g.line("set offsets 0.1, 0.1, 0.1, 0.1");
  g.line("set palette defined (0 \"#fff7bc\", 0.5 \"#fe9929\", 1 \"#662506\")");
  g.line("set title \"upward jumps: highest landing surface per target (x, y)\"");
  g.line("set cbrange [0:" + format("%.3g", zmax) + "]");
  g.line("set cblabel \"height [m]\"");
  g.line(plotCommand(g, {up, up_none}));
  g.line("set palette defined (0 \"#08306b\", 0.5 \"#6baed6\", 1 \"#f7fbff\")");
  g.line("set title \"downward jumps: lowest landing surface per target (x, y)\"");
  g.line("set cbrange [" + format("%.3g", zmin) + ":0]");
  g.line(plotCommand(g, {down, down_none}));
  g.line("unset multiplot");
  render(g, (fs::path(dir) / "heights.gp").string());
  return png;
}

std::string twistPlot(const std::vector<JumpRow>& rows, const PlotContext& c, const std::string& dir) {
  const std::string png = (fs::path(dir) / "twist_yaw.png").string();
  GnuplotScript g(png, 900, 560);
  commonStyle(g);
  std::vector<const JumpRow*> sorted;
  for (const JumpRow& r : rows) sorted.push_back(&r);
  std::sort(sorted.begin(), sorted.end(), [](const JumpRow* a, const JumpRow* b) { return a->target_yaw < b->target_yaw; });
  Series landed{"landed", "using 1:2 with linespoints pt 7 ps 0.9 lw 1.5 lc rgb \"#2b83ba\"", "", {}};
  Series failed{"failed", std::string("using 1:(0) with points pt 2 ps 1.6 lw 2 lc rgb \"") + kFailedColour + "\"", "", {}};
  double sum = 0, max = 0;
  double yaw_lo = 0, yaw_hi = 0;
  for (const JumpRow* r : sorted) {
    yaw_lo = std::min(yaw_lo, r->target_yaw * kDeg), yaw_hi = std::max(yaw_hi, r->target_yaw * kDeg);
    if (r->landed() && std::isfinite(r->error_yaw_deg)) {
      landed.rows.push_back({r->target_yaw * kDeg, r->error_yaw_deg});
      sum += r->error_yaw_deg;
      max = std::max(max, r->error_yaw_deg);
    } else if (r->status != "rejected") {
      failed.rows.push_back({r->target_yaw * kDeg});
    }
  }
  landed.title = "yaw error of a landed jump (" + std::to_string(landed.rows.size()) + ")";
  failed.title = "failed, at the target yaw (" + std::to_string(failed.rows.size()) + ")";
  const std::string stats = landed.rows.empty() ? "none landed"
                                                : "yaw error mean " + format("%.1f", sum / landed.rows.size()) +
                                                      " deg, max " + format("%.1f", max) + " deg";
  // Error against target yaw on plain axes, so that the twists' range fills the width.
  g.line("set title " + quoted(headline(c, rows.size(), "in-place twists") + "\n" + stats));
  g.line("set xlabel \"target yaw [deg] (left positive)\"");
  g.line("set ylabel \"yaw error [deg]\"");
  g.line("set xrange [" + format("%g", yaw_lo - 5) + ":" + format("%g", yaw_hi + 5) + "]");
  g.line("set xtics 30");
  g.line("set yrange [0:" + format("%.3g", std::max(0.5, 1.15 * max)) + "]");
  g.line("set grid");
  g.line("set key below");
  g.line(plotCommand(g, {landed, failed}));
  render(g, (fs::path(dir) / "twist_yaw.gp").string());
  return png;
}

}  // namespace

std::vector<std::string> figuresFor(const std::vector<JumpRow>& rows) {
  std::vector<std::string> out;
  size_t flat = 0, far = 0, raised = 0, in_place = 0;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0, yaw0 = 0, yaw1 = 0;
  for (const JumpRow& r : rows) {
    if (isFlat(r)) ++flat;
    else ++raised;
    if (targetDistance(r) > 0.05) ++far;
    if (targetDistance(r) < 1e-3 && isFlat(r)) {
      ++in_place;
      yaw0 = std::min(yaw0, r.target_yaw), yaw1 = std::max(yaw1, r.target_yaw);
    }
    x0 = std::min(x0, r.target_x), x1 = std::max(x1, r.target_x);
    y0 = std::min(y0, r.target_y), y1 = std::max(y1, r.target_y);
  }
  const bool all_flat = flat == rows.size() && !rows.empty();
  if (all_flat && rows.size() >= 20 && x1 - x0 > 0.3 && y1 - y0 > 0.3) out.push_back("region_map");
  if (all_flat && far >= 10) out.push_back("distance");
  if (raised >= 10) out.push_back("heights");
  if (in_place >= 5 && (yaw1 - yaw0) * kDeg > 10) out.push_back("twist_yaw");
  return out;
}

std::vector<std::string> plotEvaluationSet(const std::vector<JumpRow>& rows, const PlotContext& context,
                                           const std::string& dir) {
  std::vector<std::string> out;
  for (const std::string& figure : figuresFor(rows)) {
    if (figure == "region_map") out.push_back(regionMap(rows, context, dir));
    if (figure == "distance") out.push_back(distancePlot(rows, context, dir));
    if (figure == "heights") out.push_back(heightMaps(rows, context, dir));
    if (figure == "twist_yaw") {
      std::vector<JumpRow> in_place;
      for (const JumpRow& r : rows)
        if (targetDistance(r) < 1e-3 && isFlat(r)) in_place.push_back(r);
      out.push_back(twistPlot(in_place, context, dir));
    }
  }
  return out;
}

}  // namespace pronk::render::plot
