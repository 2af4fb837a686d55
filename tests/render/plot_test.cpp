// Evaluation figures through gnuplot: which figures a set gets, PNGs of the
// stated size beside their scripts, and gnuplot's own message when it fails.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "pronk/error.h"
#include "render/plot/evaluation_plots.h"
#include "render/plot/gnuplot.h"
#include "render/plot/training_plots.h"

namespace {

namespace fs = std::filesystem;
using pronk::JumpRow;
namespace plot = pronk::render::plot;

std::string outDir(const std::string& name) {
  const fs::path dir = fs::path(PRONK_RENDER_OUT_DIR) / ("plot_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

// Width and height from a PNG's IHDR chunk; {0, 0} for a file that is no PNG.
std::pair<int, int> pngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char h[24] = {};
  in.read(reinterpret_cast<char*>(h), sizeof h);
  if (!in || h[1] != 'P' || h[2] != 'N' || h[3] != 'G') return {0, 0};
  auto be = [&](int at) { return (h[at] << 24) | (h[at + 1] << 16) | (h[at + 2] << 8) | h[at + 3]; };
  return {be(16), be(20)};
}

// A set over the flat region: error growing with distance, failures far out.
std::vector<JumpRow> flatRegion(size_t n) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-0.6, 1.2), y(-0.6, 0.6);
  std::vector<JumpRow> rows;
  for (size_t i = 0; i < n; ++i) {
    JumpRow r;
    r.index = i;
    r.target_x = x(rng), r.target_y = y(rng);
    const double d = std::hypot(r.target_x, r.target_y);
    r.status = d > 1.1 ? "failed" : (i % 17 == 0 ? "rejected" : "ok");
    if (r.status == "ok") {
      r.landed_x = r.target_x * (1 - 0.15 * d), r.landed_y = r.target_y;
      r.error_xy = r.error = std::abs(r.target_x) * 0.15 * d, r.error_yaw_deg = 1, r.standing = true;
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(EvaluationPlots, EachSetGetsTheFiguresOfWhatItVaries) {
  EXPECT_EQ(plot::figuresFor(flatRegion(100)), (std::vector<std::string>{"region_map", "distance"}));
  std::vector<JumpRow> twists;
  for (int i = 0; i < 9; ++i) {
    JumpRow r;
    r.target_yaw = (-90 + 22.5 * i) * M_PI / 180, r.status = "ok", r.error_yaw_deg = 0.5 * i;
    twists.push_back(r);
  }
  EXPECT_EQ(plot::figuresFor(twists), (std::vector<std::string>{"twist_yaw"}));
  std::vector<JumpRow> heights = flatRegion(40);
  for (size_t i = 0; i < heights.size(); ++i) heights[i].target_z = 0.1 * (i % 5) - 0.2;
  EXPECT_EQ(plot::figuresFor(heights), (std::vector<std::string>{"heights"}));
  EXPECT_TRUE(plot::figuresFor(flatRegion(3)).empty());  // too few to show anything
}

TEST(EvaluationPlots, WritesEachFigureAsAPngBesideItsScript) {
  const std::string dir = outDir("figures");
  std::vector<JumpRow> rows = flatRegion(300);
  const plot::PlotContext context{"go1", "test_policy", "synthetic / region", 0.2};
  const std::vector<std::string> pngs = plot::plotEvaluationSet(rows, context, dir);
  ASSERT_EQ(pngs.size(), 2u);
  EXPECT_EQ(pngSize(dir + "/region_map.png"), (std::pair<int, int>{1100, 820}));
  EXPECT_EQ(pngSize(dir + "/distance.png"), (std::pair<int, int>{1300, 640}));
  // The script names the robot, the policy and the jumps, and renders again by itself.
  std::ifstream in(dir + "/region_map.gp");
  const std::string script((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(script.find("go1, policy test_policy"), std::string::npos);
  EXPECT_NE(script.find("(300 jumps, synthetic / region)"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir + "/region_map.log"));  // a clean run leaves no log

  // Every jump within 0.5-1.5 cm: no 0.2 m contour anywhere. The legend says so, and
  // gnuplot is not handed an empty line to draw (it would warn into a log).
  std::vector<JumpRow> accurate = flatRegion(300);
  for (JumpRow& r : accurate) {
    r.status = "ok";
    r.error_xy = r.error = 0.005 + 0.01 * double(r.index % 7) / 6;
  }
  const std::string adir = outDir("accurate");
  ASSERT_EQ(plot::plotEvaluationSet(accurate, context, adir).size(), 2u);
  EXPECT_EQ(pngSize(adir + "/region_map.png"), (std::pair<int, int>{1100, 820}));
  EXPECT_FALSE(fs::exists(adir + "/region_map.log"));
  std::ifstream accurate_in(adir + "/region_map.gp");
  const std::string accurate_script((std::istreambuf_iterator<char>(accurate_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(accurate_script.find("0.2 m contour: none"), std::string::npos);

  std::vector<JumpRow> heights = flatRegion(60);
  for (size_t i = 0; i < heights.size(); ++i) heights[i].target_z = 0.1 * (i % 5) - 0.2;
  const std::string hdir = outDir("heights");
  EXPECT_EQ(plot::plotEvaluationSet(heights, context, hdir).size(), 1u);
  EXPECT_EQ(pngSize(hdir + "/heights.png"), (std::pair<int, int>{1400, 600}));
}

TEST(Gnuplot, QuotesTextAndReportsItsOwnErrorNamingTheScript) {
  EXPECT_EQ(plot::quoted("a \"b\" \\ c"), "\"a \\\"b\\\" \\\\ c\"");
  const std::string dir = outDir("broken");
  plot::GnuplotScript g(dir + "/broken.png", 200, 100);
  g.line("plot $nothing_defined using 1:2");
  try {
    plot::render(g, dir + "/broken.gp");
    FAIL() << "a broken script rendered";
  } catch (const pronk::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(dir + "/broken.gp: gnuplot failed"), std::string::npos) << what;
    EXPECT_NE(what.find("nothing_defined"), std::string::npos) << what;  // gnuplot's own words
  }
  EXPECT_FALSE(fs::exists(dir + "/broken.png"));
}

// A train_log.csv with the columns the curves read (a real log has more).
std::string writeLog(const std::string& dir, const std::string& bad_cell = "") {
  const std::string path = dir + "/train_log.csv";
  std::ofstream out(path);
  out << "iteration,jumps,reward_mean,batch_error_mean_m,batch_within_0.2m,validation_error_median_m,"
         "validation_error_mean_m,validation_within_0.2m\n";
  for (int i = 0; i <= 6; ++i) {
    const bool validated = i % 2 == 0;
    out << i << "," << 256 * i << "," << (i == 0 ? std::string("nan") : std::to_string(0.2 + 0.02 * i)) << ","
        << 0.1 - 0.005 * i << "," << 0.7 + 0.01 * i << ",";
    if (validated) out << 0.05 - 0.002 * i << "," << 0.08 - 0.003 * i << "," << 0.76 + 0.01 * i << "\n";
    else out << (i == 3 && !bad_cell.empty() ? bad_cell : "nan") << ",nan,nan\n";
  }
  return path;
}

TEST(TrainingCurves, PlotsALogAgainstSimulatedJumps) {
  const std::string dir = outDir("training");
  const plot::TrainingLog log = plot::readTrainingLog(writeLog(dir));
  EXPECT_EQ(log.rows.size(), 7u);
  EXPECT_TRUE(std::isnan(log.column("reward_mean")[0]));
  plot::plotTrainingCurves(log, "go1", "tiny_policy", dir + "/train_curves.png");
  EXPECT_EQ(pngSize(dir + "/train_curves.png"), (std::pair<int, int>{1100, 1100}));
  std::ifstream in(dir + "/train_curves.gp");
  const std::string script((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(script.find("go1, policy tiny_policy: training curves over 1536 simulated jumps"), std::string::npos);
  // pronk's own jumps fill the width: a linear axis to the last one; the paper's
  // millions of jumps are said in the title, not drawn.
  EXPECT_NE(script.find("set xrange [0:1566.72"), std::string::npos) << script.substr(0, 800);
  EXPECT_EQ(script.find("logscale"), std::string::npos);
  EXPECT_NE(script.find("the paper's run: 50/80/90/95 %"), std::string::npos);
}

TEST(TrainingCurves, ABrokenLogIsNamedAtItsLine) {
  const std::string dir = outDir("training_bad");
  try {
    plot::readTrainingLog(writeLog(dir, "abc"));
    FAIL() << "a log with a word for a number was read";
  } catch (const pronk::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("train_log.csv:5: validation_error_median_m: \"abc\""), std::string::npos)
        << e.what();
  }
  const std::string empty = dir + "/empty.csv";
  std::ofstream(empty) << "";
  EXPECT_THROW(plot::readTrainingLog(empty), pronk::InputError);
}

}  // namespace
