// Issue 16, items 2, 4 and 8: the real programs (birotor-replay, -eval,
// -identify, -plot, -sim) on crafted files in a temporary folder. Every case:
// no death by signal, no hang (special and 2 GB sparse files answered within
// 2 s), no silent success (exit status 1 and one "program: error: ..." line),
// and an input is never overwritten by an output.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/transport/test_files.h"

namespace birotor {
namespace {

using test_files::HugeDataLengthLog;
using test_files::MakeTempDirectory;
using test_files::ReadBytes;
using test_files::WriteBytes;

struct ToolRun {
  bool signaled = false;  // killed by a signal (e.g. SIGSEGV: exit 139 in a shell)
  int exit_code = -1;
  double seconds = 0;
  std::string output;  // stdout and stderr
};

// Runs argv with stdout+stderr captured; kills it after timeout_s. A daemon
// is stopped with SIGINT (its clean stop) once its output holds
// interrupt_when (when not empty).
ToolRun RunTool(const std::vector<std::string>& argv, double timeout_s = 60, const std::string& interrupt_when = "") {
  const std::string capture = ::testing::TempDir() + "/hostile_files_" + std::to_string(getpid()) + ".out";
  ToolRun run;
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    const int fd = open(capture.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(fd, 1);
    dup2(fd, 2);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  bool interrupted = false;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    const double elapsed_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!interrupt_when.empty() && !interrupted) {
      std::ifstream in(capture);
      const std::string so_far((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (so_far.find(interrupt_when) != std::string::npos) {
        kill(pid, SIGINT);
        interrupted = true;
      }
    }
    if (elapsed_s > timeout_s) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    usleep(2000);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.signaled = WIFSIGNALED(status);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(capture);
  run.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::remove(capture.c_str());
  return run;
}

// The failure every case expects: exit 1 (not a signal) and the one-line
// "<program>: error: " message.
void ExpectRefused(const ToolRun& run, const std::string& program, const std::string& what) {
  EXPECT_FALSE(run.signaled) << what << "\n" << run.output;
  EXPECT_EQ(run.exit_code, 1) << what << "\n" << run.output;
  EXPECT_NE(run.output.find(program + ": error: "), std::string::npos) << what << "\n" << run.output;
}

class HostileFilesTest : public ::testing::Test {
 public:
  static std::string Path(const std::string& name) { return *dir_ + "/" + name; }

 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(MakeTempDirectory("hostile_files_test"));
    ASSERT_FALSE(dir_->empty());
    // A real 1.5 s hover log from the simulator (STRAIN, MOTOR, IMU, POSE, TRUTH).
    const ToolRun sim =
        RunTool({BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml",
                 "--set", "scenario.duration_s=1.5", "--output", Path("hover.lcm"), "--log-level", "warn"});
    ASSERT_EQ(sim.exit_code, 0) << sim.output;
    // Issue 16 item 2: 138 bytes, one header declaring 0x7fffffff data bytes.
    WriteBytes(Path("datalen.lcm"), HugeDataLengthLog());
    WriteBytes(Path("empty.lcm"), {});
    WriteBytes(Path("sparse.lcm"), {});
    ASSERT_EQ(truncate(Path("sparse.lcm").c_str(), int64_t{2} << 30), 0);
    // Half of the hover log, then as many bytes of garbage: only 50 % of the
    // file is readable events, below the 90 % minimum.
    std::vector<uint8_t> bytes = ReadBytes(Path("hover.lcm"));
    bytes.resize(bytes.size() / 2);
    bytes.resize(bytes.size() * 2, 0xAB);
    WriteBytes(Path("cut.lcm"), bytes);
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
  }
  static std::string* dir_;
};
std::string* HostileFilesTest::dir_ = nullptr;

const std::vector<std::string> kUselessLogs = {"datalen.lcm", "empty.lcm", "sparse.lcm", "/dev/zero", "cut.lcm"};

std::string LogPath(const std::string& name) { return name[0] == '/' ? name : HostileFilesTest::Path(name); }

TEST_F(HostileFilesTest, ReplayRefusesUselessLogsQuickly) {
  for (const std::string& name : kUselessLogs) {
    const ToolRun run = RunTool({BIROTOR_REPLAY_BIN, "--log", LogPath(name), "--output", Path("out.lcm")});
    ExpectRefused(run, "birotor-replay", name);
    EXPECT_LT(run.seconds, 2.0) << name;  // issue 16 target: /dev/zero, 2 GB sparse within 2 s
    EXPECT_FALSE(std::filesystem::exists(Path("out.lcm"))) << name << ": a partial output was left";
  }
}

TEST_F(HostileFilesTest, EvalIdentifyAndPlotRefuseUselessLogsQuickly) {
  for (const std::string& name : kUselessLogs) {
    const ToolRun eval = RunTool({BIROTOR_EVAL_BIN, "--log", LogPath(name)});
    ExpectRefused(eval, "birotor-eval", name);
    EXPECT_LT(eval.seconds, 2.0) << name;
    const ToolRun identify = RunTool({BIROTOR_IDENTIFY_BIN, "--log", LogPath(name), "--output", Path("v.yaml")});
    ExpectRefused(identify, "birotor-identify", name);
    EXPECT_LT(identify.seconds, 2.0) << name;
    EXPECT_FALSE(std::filesystem::exists(Path("v.yaml"))) << name;
    const ToolRun plot = RunTool({BIROTOR_PLOT_BIN, "--log", LogPath(name), "--png", Path("p.png")});
    ExpectRefused(plot, "birotor-plot", name);
    EXPECT_LT(plot.seconds, 2.0) << name;
  }
}

// Issue 16 item 4: --output equal to --log turned 800 kB into 0 bytes.
TEST_F(HostileFilesTest, OutputsNeverOverwriteTheInputThroughAnyName) {
  const std::string log = Path("hover.lcm");
  const std::vector<uint8_t> before = ReadBytes(log);
  ASSERT_EQ(link(log.c_str(), Path("hard.lcm").c_str()), 0);
  ASSERT_EQ(symlink(log.c_str(), Path("soft.lcm").c_str()), 0);
  for (const std::string& alias : {log, Path("hard.lcm"), Path("soft.lcm")}) {
    ExpectRefused(RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", alias}), "birotor-replay", alias);
    ExpectRefused(RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", Path("o.lcm"), "--csv", alias}),
                  "birotor-replay", alias);
    ExpectRefused(RunTool({BIROTOR_IDENTIFY_BIN, "--log", log, "--output", alias}), "birotor-identify", alias);
    ExpectRefused(RunTool({BIROTOR_IDENTIFY_BIN, "--log", log, "--output", Path("v.yaml"), "--report", alias}),
                  "birotor-identify", alias);
    ExpectRefused(RunTool({BIROTOR_EVAL_BIN, "--log", log, "--markdown-out", alias}), "birotor-eval", alias);
    ExpectRefused(RunTool({BIROTOR_PLOT_BIN, "--log", log, "--png", alias}), "birotor-plot", alias);
  }
  std::filesystem::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml", Path("scenario.yaml"));
  ASSERT_EQ(symlink(Path("scenario.yaml").c_str(), Path("scenario_link.lcm").c_str()), 0);
  const std::vector<uint8_t> scenario = ReadBytes(Path("scenario.yaml"));
  ExpectRefused(RunTool({BIROTOR_SIM_BIN, "--scenario", Path("scenario.yaml"), "--output", Path("scenario_link.lcm")}),
                "birotor-sim", "sim --output over its scenario");
  EXPECT_EQ(ReadBytes(Path("scenario.yaml")), scenario);
  EXPECT_EQ(ReadBytes(log), before);
  ExpectRefused(RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", Path("x.lcm"), "--csv", Path("x.lcm")}),
                "birotor-replay", "two outputs, one file");
}

// Issue 16 item 8: failed writes exited 0.
TEST_F(HostileFilesTest, FailedWritesAreErrorsAndLeaveNoPartialFile) {
  const std::string log = Path("hover.lcm");
  ToolRun run = RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", Path("replayed.lcm"), "--csv", "/dev/full"});
  ExpectRefused(run, "birotor-replay", "--csv /dev/full");
  EXPECT_NE(run.output.find("No space left on device"), std::string::npos) << run.output;
  EXPECT_FALSE(std::filesystem::exists(Path("replayed.lcm")));
  ExpectRefused(RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", "/dev/full"}), "birotor-replay", "/dev/full");
  ExpectRefused(RunTool({BIROTOR_EVAL_BIN, "--log", log, "--markdown-out", "/dev/full"}), "birotor-eval",
                "--markdown-out /dev/full");
  ExpectRefused(RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", "/nonexistent/out.lcm"}), "birotor-replay",
                "missing folder");
  ExpectRefused(
      RunTool({BIROTOR_IDENTIFY_BIN, "--log", log, "--output", Path("v.yaml"), "--report", "/nonexistent/r.md"}),
      "birotor-identify", "--report /nonexistent/r.md");
  ExpectRefused(
      RunTool({BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml", "--set",
               "scenario.duration_s=0.5", "--output", "/dev/full"}),
      "birotor-sim", "sim --output /dev/full");
  // The replay itself works and leaves exactly its outputs.
  run = RunTool({BIROTOR_REPLAY_BIN, "--log", log, "--output", Path("replayed.lcm"), "--csv", Path("replayed.csv")});
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(Path("replayed.lcm")));
  EXPECT_TRUE(std::filesystem::exists(Path("replayed.csv")));
  for (const auto& entry : std::filesystem::directory_iterator(*dir_)) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path() << " left behind";
  }
}

// Issue 16 item 8: a zero-length channel name mid-log stopped the replay at
// 3000 of 7200 events with exit 0. Now the bad event is skipped and counted,
// every other event is replayed, and the damage is reported.
TEST_F(HostileFilesTest, ZeroLengthChannelMidLogIsSkippedAndReported) {
  std::vector<uint8_t> bytes = ReadBytes(Path("hover.lcm"));
  // Find an event boundary near 30 % of the file: the offset of a sync word.
  size_t at = bytes.size() * 3 / 10;
  while (!(bytes[at] == 0xED && bytes[at + 1] == 0xA1 && bytes[at + 2] == 0xDA && bytes[at + 3] == 0x01)) ++at;
  std::vector<uint8_t> bad = test_files::LogEventHeader(9999, 1000, 0, 4);
  bad.insert(bad.end(), {1, 2, 3, 4});
  bytes.insert(bytes.begin() + static_cast<std::ptrdiff_t>(at), bad.begin(), bad.end());
  WriteBytes(Path("zero_channel.lcm"), bytes);

  const ToolRun intact = RunTool({BIROTOR_REPLAY_BIN, "--log", Path("hover.lcm"), "--output", Path("a.lcm")});
  const ToolRun damaged = RunTool({BIROTOR_REPLAY_BIN, "--log", Path("zero_channel.lcm"), "--output", Path("b.lcm")});
  ASSERT_EQ(intact.exit_code, 0) << intact.output;
  ASSERT_EQ(damaged.exit_code, 0) << damaged.output;
  EXPECT_NE(damaged.output.find("damaged log: 1 corrupt event headers, 32 bytes skipped"), std::string::npos)
      << damaged.output;
  EXPECT_EQ(ReadBytes(Path("a.lcm")), ReadBytes(Path("b.lcm")));  // every good event replayed
}

// Issue 23 item 7: --update-params with a pre-planted FILE.bak (a link to a
// victim or a device, a FIFO) wrote through it or hung; a FIFO as the
// parameter file hung. Each is refused before the fit in one line, a hang
// being the run's time-out (exit -1), and nothing is written.
TEST_F(HostileFilesTest, UpdateParamsRefusesPlantedBackupsAndSpecialFiles) {
  const std::string params = Path("update.yaml");
  std::filesystem::copy_file(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", params,
                             std::filesystem::copy_options::overwrite_existing);
  const std::vector<uint8_t> original = ReadBytes(params);
  const std::string victim = Path("victim.txt");
  WriteBytes(victim, {'o', 'k'});
  const std::string backup = params + ".bak";
  auto identify = [&](const std::string& file) {
    return RunTool({BIROTOR_IDENTIFY_BIN, "--log", Path("hover.lcm"), "--update-params", file}, 20);
  };
  for (const std::string& target : {victim, std::string("/dev/null")}) {
    ASSERT_EQ(symlink(target.c_str(), backup.c_str()), 0);
    const ToolRun run = identify(params);
    ExpectRefused(run, "birotor-identify", "FILE.bak -> " + target);
    EXPECT_NE(run.output.find("is a symbolic link"), std::string::npos) << run.output;
    ASSERT_EQ(unlink(backup.c_str()), 0);
  }
  ASSERT_EQ(mkfifo(backup.c_str(), 0600), 0);
  ExpectRefused(identify(params), "birotor-identify", "FILE.bak a FIFO");
  ASSERT_EQ(unlink(backup.c_str()), 0);
  const std::string fifo = Path("fifo.yaml");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ExpectRefused(identify(fifo), "birotor-identify", "--update-params a FIFO");
  EXPECT_EQ(ReadBytes(victim), std::vector<uint8_t>({'o', 'k'}));
  EXPECT_EQ(ReadBytes(params), original);
}

// Issue 23 item 6 on the daemon itself: a FIFO as state_file hung the
// start-up (no status), /dev/zero grew it to 1 GB, and the parameter file as
// state_file was replaced at stop. Each is refused at start (the daemon runs
// on the parameter file's offsets) and left alone at stop, which says so and
// exits 1; a hang would be the run's time-out (exit -1, no stop line).
TEST_F(HostileFilesTest, EstimatorNeverReadsNorReplacesAStateFileThatIsNotOne) {
  const std::string fifo = Path("gauge.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const std::string params_copy = Path("state_is_params.yaml");
  std::string reference;
  {
    std::ifstream in(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
    reference.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t at = reference.find("state_file: \"\"");
  ASSERT_NE(at, std::string::npos);
  // The state file is used only with a readable site key (issue 37 item 4).
  const std::string site_key = Path("site.key");
  std::ofstream(site_key, std::ios::binary) << std::string(32, '\x3c');
  ASSERT_EQ(chmod(site_key.c_str(), 0600), 0);
  for (const std::string& state : {fifo, std::string("/dev/zero"), params_copy}) {
    std::string text = reference;
    text.replace(at, 14, "state_file: \"" + state + "\"");
    const std::string params = Path("estimator_state.yaml");
    std::ofstream(params) << text;
    if (state == params_copy) std::ofstream(params_copy) << text;
    // Stopped once running (its "lcm memq://: in ..." line follows the state file).
    const ToolRun run = RunTool(
        {BIROTOR_ESTIMATOR_BIN, "--params", params, "--lcm-url", "memq://", "--site-key", site_key}, 30, "lcm memq://");
    ExpectRefused(run, "birotor-estimator", "state_file " + state);
    EXPECT_NE(run.output.find("gauge state file refused: " + state), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("stopped:"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("not overwritten"), std::string::npos) << run.output;
    if (state == params_copy) {
      std::ifstream in(params_copy);
      EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), text);
    }
  }
  struct stat info {};
  ASSERT_EQ(lstat(fifo.c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
}

}  // namespace
}  // namespace birotor

namespace birotor {
namespace {

// Issue 37 item 4 on the daemon: without a usable site key (a world-writable
// key file, or none) the state file is neither restored nor written, and the
// start says why, once; the run itself goes on and stops cleanly (exit 0).
// Without a usable key the estimator does not start (it authenticates POSE
// and FORCE); a site that lets both through unsigned runs it, without the
// state file.
TEST_F(HostileFilesTest, EstimatorWithoutAUsableSiteKeyRefusesToStartOrRunsUnsignedWithoutTheStateFile) {
  std::string text;
  {
    std::ifstream in(std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml");
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t at = text.find("state_file: \"\"");
  ASSERT_NE(at, std::string::npos);
  const std::string state = Path("unkeyed_gauge_state");
  text.replace(at, 14, "state_file: \"" + state + "\"");
  const std::string params = Path("estimator_unkeyed.yaml");
  std::ofstream(params) << text;
  const std::string open_key = Path("open_site.key");
  std::ofstream(open_key, std::ios::binary) << std::string(32, '\x3c');
  ASSERT_EQ(chmod(open_key.c_str(), 0666), 0);
  for (const std::string& key : {open_key, Path("absent_site.key")}) {
    unlink(state.c_str());
    const ToolRun refused =
        RunTool({BIROTOR_ESTIMATOR_BIN, "--params", params, "--lcm-url", "memq://", "--site-key", key}, 30, "");
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_NE(refused.output.find("birotor-estimator: error: site key " + key + ": "), std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("it authenticates POSE, FORCE"), std::string::npos) << refused.output;
    const ToolRun run = RunTool({BIROTOR_ESTIMATOR_BIN, "--params", params, "--lcm-url", "memq://", "--site-key", key,
                                 "--unsigned", "POSE,FORCE"},
                                30, "lcm memq://");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    const std::string warning = "gauge state file " + state + " is not authenticated (site key " + key + ": ";
    EXPECT_NE(run.output.find(warning), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("stopped:"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(state)) << key;
    if (key == open_key) {
      EXPECT_NE(run.output.find("writable by its group or by others (mode 0666"), std::string::npos) << run.output;
    }
  }
}

}  // namespace
}  // namespace birotor
