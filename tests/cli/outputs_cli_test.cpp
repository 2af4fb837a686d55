// What pronk writes and what it reads, against what a user (or an unlucky one)
// gives it: device nodes, pipes and folders where a file goes, an output that is
// the command's own input, a file-size limit, inputs that would take without
// bound, signals and a closed stdout (docs/errors.md). Device nodes are made with mknod in a private folder,
// never under /dev.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include "pronk_command.h"

namespace {

namespace fs = std::filesystem;
using pronk_test::Outcome;
using pronk_test::pronk;
using pronk_test::shell;
using pronk_test::source;

std::string freshDir(const std::string& name) {
  const std::string dir = std::string(PRONK_CLI_OUT_DIR) + "/" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A copy of a shipped scenario whose includes name the shipped files, so that
// the copy may be written over by a test without touching the tree.
std::string scenarioCopy(const std::string& dir, const std::string& shipped) {
  const std::string folder = fs::path(source("scenarios/" + shipped)).parent_path().string();
  const std::string text =
      std::regex_replace(readText(source("scenarios/" + shipped)), std::regex("file=\"([^/\"][^\"]*)\""),
                         "file=\"" + folder + "/$1\"");
  const std::string path = dir + "/" + fs::path(shipped).filename().string();
  std::ofstream(path) << text;
  return path;
}

bool isCharacterDevice(const std::string& path) {
  struct stat st{};
  return lstat(path.c_str(), &st) == 0 && S_ISCHR(st.st_mode);
}

void expectRefused(const Outcome& o, const std::string& flag_and_path) {
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("pronk: " + flag_and_path), std::string::npos) << o.output;
}

TEST(Outputs, ADeviceAPipeOrAFolderWhereAFileGoesIsRefusedAndLeftAsItWas) {
  const std::string dir = freshDir("outputs_nodes");
  const std::string node = dir + "/null";
  if (mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0) GTEST_SKIP() << "mknod needs root";
  const std::string fifo = dir + "/fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string folder = dir + "/folder";
  fs::create_directories(folder);
  const std::string stand = source("scenarios/go1/stand.xml");
  const std::string log = dir + "/p.train_log.csv";
  std::ofstream(log) << "iteration\n";

  expectRefused(pronk("train " + source("scenarios/train/go1_omni.xml") + " --out " + node), "--out " + node);
  expectRefused(pronk("run " + stand + " --duration 0.05 --video " + node), "--video " + node);
  expectRefused(pronk("run " + stand + " --duration 0.05 --out " + node), "--out " + node);
  expectRefused(pronk("render " + stand + " --duration 0.05 -o " + fifo), "-o " + fifo);
  expectRefused(pronk("render " + stand + " --duration 0.05 -o " + folder), "-o " + folder);
  expectRefused(pronk("check " + source("scenarios/eval/go1_flat_64.xml") + " --junit " + node), "--junit " + node);
  expectRefused(pronk("plot " + log + " --out " + node), "--out " + node);
  expectRefused(pronk("eval " + source("scenarios/go1/forward.xml") + " --out " + node), "--out " + node);
  EXPECT_TRUE(isCharacterDevice(node));
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_TRUE(fs::is_directory(folder));

  // The files beside a policy count as much as the policy.
  const std::string beside = dir + "/p.checkpoint.json";
  ASSERT_EQ(mknod(beside.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  expectRefused(pronk("train " + source("scenarios/train/go1_omni.xml") + " --out " + dir + "/p.json"),
                "--out's checkpoint " + beside);
  EXPECT_TRUE(isCharacterDevice(beside));
  EXPECT_FALSE(fs::exists(dir + "/p.json"));
}

TEST(Outputs, AnOutputThatIsTheCommandsOwnInputIsRefusedNamingBoth) {
  const std::string dir = freshDir("outputs_inputs");
  const std::string stand = scenarioCopy(dir, "go1/stand.xml");
  const std::string forward = scenarioCopy(dir, "go1/forward.xml");
  const std::string log = dir + "/p.train_log.csv";
  std::ofstream(log) << "iteration\n";
  const std::string junit_source = scenarioCopy(dir, "eval/go1_flat_64.xml");
  const std::string stand_text = readText(stand);

  const Outcome train = pronk("train " + stand + " --out " + stand);
  expectRefused(train, "--out " + stand + " is the command's own input FILE " + stand);
  expectRefused(pronk("run " + stand + " --duration 0.05 --video " + stand), "--video " + stand);
  expectRefused(pronk("render " + stand + " --duration 0.05 -o " + stand), "-o " + stand);
  expectRefused(pronk("check " + junit_source + " --junit " + junit_source), "--junit " + junit_source);
  expectRefused(pronk("plot " + log + " --out " + log), "--out " + log);
  // Under another name: a hard link is the same file.
  const std::string link = dir + "/stand_link.xml";
  fs::create_hard_link(stand, link);
  expectRefused(pronk("run " + stand + " --duration 0.05 --video " + link), "--video " + link);
  EXPECT_EQ(readText(stand), stand_text);
  EXPECT_EQ(readText(log), "iteration\n");

  // A trace rendered into its own file, and a video named as a run's own results.
  const std::string run_dir = dir + "/run";
  ASSERT_EQ(pronk("run " + stand + " --duration 0.05 --out " + run_dir).status, 0);
  const std::string trace = run_dir + "/trace.csv";
  const std::string trace_text = readText(trace);
  expectRefused(pronk("render " + stand + " --trace " + trace + " -o " + trace), "-o " + trace);
  EXPECT_EQ(readText(trace), trace_text);
  const Outcome collides = pronk("run " + forward + " --policy ballistic --out " + run_dir + " --video " + run_dir +
                                 "/results.json");
  expectRefused(collides, "--video " + run_dir + "/results.json");
  EXPECT_NE(collides.output.find("the command writes its own results.json"), std::string::npos) << collides.output;
}

TEST(Outputs, AVideoPastAFileSizeLimitIsAnErrorAndLeavesNoFile) {
  // 16 blocks of 512 bytes: the first frames fit, the 22 kB video does not.
  const std::string dir = freshDir("outputs_file_size");
  const std::string video = dir + "/stand.mp4";
  const Outcome o = shell("ulimit -f 16; " + std::string(PRONK_EXE) + " render " + source("scenarios/go1/stand.xml") +
                          " --duration 2 --size 640x360 -o " + video);
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(video + ": writing the "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(no video written)"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(video));
  EXPECT_FALSE(fs::exists(video + ".partial"));
}

TEST(Outputs, AVideoThatFailsMidRunKeepsEveryJumpsResultsAndSaysTheRunIsIncomplete) {
  // 500 kB: the 40 jumps' results (about 240 kB) fit, their video does not.
  const std::string dir = freshDir("outputs_mid_run");
  const Outcome o = shell("ulimit -f 1000; " + std::string(PRONK_EXE) + " run " + source("scenarios/go1/region.xml") +
                          " --policy ballistic --sweep region --out " + dir + "/out --video " + dir + "/all.mp4");
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find("pronk: " + dir + "/all.mp4: writing "), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("every finished jump's results are written"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir + "/all.mp4"));
  EXPECT_FALSE(fs::exists(dir + "/all.mp4.partial"));
  nlohmann::json results;
  std::ifstream(dir + "/out/results.json") >> results;
  EXPECT_EQ(results["jumps"].size(), 40u);
  EXPECT_EQ(results["run"]["complete"], false);
  EXPECT_NE(results["run"]["write_failure"].get<std::string>().find("all.mp4"), std::string::npos);
}

TEST(Outputs, CheckpointsThatAreNotFilesOrWouldTakeWithoutBoundAreRefusedAtOnce) {
  const std::string dir = freshDir("outputs_resume");
  const std::string fifo = dir + "/fifo.json";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string train = "train " + source("scenarios/train/go1_omni.xml") + " --out " + dir + "/p.json --resume ";
  for (const std::string& resume : {fifo, std::string("/dev/zero")}) {
    const Outcome o = shell("timeout 60 " + std::string(PRONK_EXE) + " " + train + resume);
    EXPECT_EQ(o.status, 3) << o.output;
    EXPECT_NE(o.output.find(resume + ": the training checkpoint is not a regular file"), std::string::npos)
        << o.output;
  }
  // 2 MB of empty arrays: 30 times its size as a document; refused, not read.
  const std::string nested = dir + "/nested.json";
  {
    std::ofstream out(nested);
    out << "[[]";
    for (int i = 0; i < 700000; ++i) out << ",[]";
    out << "]";
  }
  const Outcome o = pronk(train + nested);
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find(nested + ": holds more values than its size allows"), std::string::npos) << o.output;
  const Outcome policy = pronk("run " + source("scenarios/go1/forward.xml") + " --policy " + nested);
  EXPECT_EQ(policy.status, 3) << policy.output;
  EXPECT_NE(policy.output.find("holds more values than its size allows"), std::string::npos) << policy.output;
}

TEST(Outputs, APluginDeclaringSizesBeyondAnyRobotIsRefusedWhenLoaded) {
  const Outcome o = pronk("plugins --plugin " + std::string(PRONK_FIXTURE_HUGE_SIZES));
  EXPECT_EQ(o.status, 3) << o.output;
  EXPECT_NE(o.output.find("environment 'fixture_huge' declares observation size 2147483647"), std::string::npos)
      << o.output;
}

TEST(Plugins, AFaultOrAnExitInsideAPluginNamesThePluginTheFactoryAndTheCall) {
  const std::string plugin = PRONK_FIXTURE_CRASHING;
  const std::string stand = source("scenarios/go1/stand.xml") + " --duration 0.05 --plugin " + plugin;
  const Outcome fault = pronk("run " + stand + " --controller fixture_segfault");
  EXPECT_NE(fault.status, 0) << fault.output;
  EXPECT_NE(fault.output.find("pronk: fatal signal 11 (Segmentation fault) in plugin " + plugin +
                              ", fixture_segfault's compute()"),
            std::string::npos)
      << fault.output;
  const Outcome exited = pronk("run " + stand + " --controller fixture_exit");
  EXPECT_EQ(exited.status, 7) << exited.output;
  EXPECT_NE(exited.output.find("pronk: exit() was called in plugin " + plugin + ", fixture_exit's create()"),
            std::string::npos)
      << exited.output;
}

TEST(Plugins, ABrokenLibraryInAPluginDirectoryStopsOnlyWhatNeedsIt) {
  const std::string dir = freshDir("plugins_broken");
  std::ofstream(dir + "/broken.so") << "not a library\n";
  const std::string env = "PRONK_PLUGIN_PATH=" + dir + " ";
  const Outcome stand = shell(env + PRONK_EXE + " run " + source("scenarios/go1/stand.xml") + " --duration 0.05");
  EXPECT_EQ(stand.status, 0) << stand.output;
  const Outcome jump = shell(env + PRONK_EXE + " run " + source("scenarios/go1/forward.xml") + " --policy ballistic");
  EXPECT_EQ(jump.status, 0) << jump.output;
  const Outcome missing = shell(env + PRONK_EXE + " run " + source("scenarios/go1/stand.xml") +
                                " --duration 0.05 --controller nowhere");
  EXPECT_EQ(missing.status, 3) << missing.output;
  EXPECT_NE(missing.output.find("; not loaded: " + dir + "/broken.so (cannot load plugin"), std::string::npos)
      << missing.output;
  const Outcome listed = shell(env + PRONK_EXE + " plugins");
  EXPECT_EQ(listed.status, 3) << listed.output;
  EXPECT_NE(listed.output.find("guided_jump"), std::string::npos) << listed.output;
  EXPECT_NE(listed.output.find("pronk: not loaded: " + dir + "/broken.so: "), std::string::npos) << listed.output;
}

// Starts `args` in the background, sends `signal` after `seconds`, and returns
// its exit status (the shell's `wait`).
int statusAfterSignal(const std::string& args, const std::string& log, const std::string& signal, int seconds) {
  const Outcome o = shell("sh -c '" + std::string(PRONK_EXE) + " " + args + " > " + log + " 2>&1 & pid=$!; sleep " +
                          std::to_string(seconds) + "; kill -" + signal + " $pid; wait $pid; echo status=$?'");
  const size_t at = o.output.find("status=");
  return at == std::string::npos ? -1 : std::atoi(o.output.c_str() + at + 7);
}

nlohmann::json readJson(const std::string& path) {
  nlohmann::json j;
  std::ifstream in(path);
  if (in) in >> j;
  return j;
}

TEST(Signals, AControllerRunStoppedByASignalWritesItsResultsAsOfThen) {
  const std::string dir = freshDir("signals_controller");
  const int status = statusAfterSignal("run " + source("scenarios/go1/stand.xml") + " --duration 3600 --out " + dir +
                                           "/out",
                                       dir + "/log.txt", "INT", 2);
  EXPECT_EQ(status, 130) << readText(dir + "/log.txt");
  const nlohmann::json j = readJson(dir + "/out/results.json");
  ASSERT_TRUE(j.is_object()) << readText(dir + "/log.txt");
  EXPECT_EQ(j["run"]["complete"], false);
  EXPECT_EQ(j["run"]["stopped_by_signal"], 2);
  EXPECT_GT(j["simulated_s"].get<double>(), 0.0);
  EXPECT_LT(j["simulated_s"].get<double>(), 3600.0);
  EXPECT_TRUE(fs::exists(dir + "/out/trace.csv"));
}

TEST(Signals, RenderStoppedByASignalClosesAPlayableVideoOfWhatWasSimulated) {
  const std::string dir = freshDir("signals_render");
  const std::string video = dir + "/stand.mp4";
  const int status = statusAfterSignal("render " + source("scenarios/go1/stand.xml") +
                                           " --duration 3600 --size 320x240 -o " + video,
                                       dir + "/log.txt", "TERM", 2);
  const std::string log = readText(dir + "/log.txt");
  EXPECT_EQ(status, 143) << log;
  EXPECT_NE(log.find("the video holds what was simulated"), std::string::npos) << log;
  EXPECT_TRUE(std::regex_search(log, std::regex("video " + video + ": [1-9][0-9]* frames"))) << log;
  EXPECT_GT(fs::file_size(video), 1000u);
  EXPECT_FALSE(fs::exists(video + ".partial"));
}

TEST(Signals, AClosedStdoutOrAHangupStopsASweepKeepingWhatFinished) {
  const std::string dir = freshDir("signals_sweep");
  const std::string sweep = "run " + source("scenarios/go1/region.xml") + " --policy ballistic --sweep region --jobs 1";
  // `| head -n 3`: the fourth line's write finds the pipe closed (SIGPIPE).
  shell(std::string(PRONK_EXE) + " " + sweep + " --out " + dir + "/piped | head -n 3");
  const nlohmann::json piped = readJson(dir + "/piped/results.json");
  ASSERT_TRUE(piped.is_object());
  EXPECT_EQ(piped["run"]["stopped_by_signal"], 13);
  EXPECT_EQ(piped["run"]["complete"], false);
  EXPECT_LT(piped["jumps"].size(), 40u);

  const int status = statusAfterSignal(sweep + " --out " + dir + "/hung_up", dir + "/log.txt", "HUP", 2);
  EXPECT_EQ(status, 129) << readText(dir + "/log.txt");
  const nlohmann::json hung_up = readJson(dir + "/hung_up/results.json");
  ASSERT_TRUE(hung_up.is_object()) << readText(dir + "/log.txt");
  EXPECT_EQ(hung_up["run"]["stopped_by_signal"], 1);
  EXPECT_GT(hung_up["jumps"].size(), 0u);
  EXPECT_LT(hung_up["jumps"].size(), 40u);
}

}  // namespace
