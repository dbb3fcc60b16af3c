// Tests of the simulator's wire output: a scenario written into an LCM log
// (library + transport's LogWriter, and the real birotor-sim program) decodes
// on every channel with the wire types, gives the same bytes for the same
// seed, refuses a bad scenario file, closes its log cleanly on SIGTERM, and
// with --loop repeats the scenario with time continuing.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <thread>
#include <vector>

#include "birotor/controller_status_t.hpp"
#include "birotor/estimator_learned_n_t.hpp"
#include "params/scenario_yaml.h"
#include "simulator/simulator.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "tests/simulator/test_support.h"
#include "transport/channels.h"
#include "transport/lcm_codec.h"
#include "transport/log_io.h"
#include "transport/message_conversion.h"

namespace birotor {
namespace {

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "sim_log_test_" + std::to_string(::getpid()) + "_" + name;
}

std::string ReadBytes(const std::string& path) { return ReadFileBytes(path); }

// True if event decodes as Message (and, with check_stamp, carries the event's stamp).
template <typename Message>
bool DecodesAs(const LogEvent& event, bool check_stamp = false) {
  Message m;
  if (DecodeMessage(event.data.data(), event.data.size(), &m) != DecodeError::kNone) return false;
  return !check_stamp || m.utime == event.timestamp_us;
}

// Decodes every event with the type of its channel; returns events per channel.
std::map<std::string, int> DecodeLog(const std::string& path, int* decode_failures, bool* truncated) {
  LogReader reader;
  std::string error;
  EXPECT_TRUE(reader.Open(path, &error)) << error;
  const ChannelNames c = MakeChannelNames();
  std::map<std::string, int> counts;
  LogEvent event;
  *decode_failures = 0;
  while (reader.Next(&event)) {
    const std::string& channel = event.channel;
    const bool decoded = channel == c.strain                ? DecodesAs<strain_t>(event, true)
                         : channel == c.motor               ? DecodesAs<motor_t>(event)
                         : channel == c.imu                 ? DecodesAs<imu_t>(event)
                         : channel == c.pose                ? DecodesAs<pose_t>(event)
                         : channel == c.loadcell            ? DecodesAs<loadcell_t>(event)
                         : channel == c.truth               ? DecodesAs<truth_t>(event)
                         : channel == c.force               ? DecodesAs<force_estimate_t>(event)
                         : channel == c.motor_command       ? DecodesAs<motor_command_t>(event, true)
                         : channel == c.setpoint            ? DecodesAs<setpoint_t>(event, true)
                         : channel == c.estimator_status    ? DecodesAs<estimator_status_t>(event)
                         : channel == c.estimator_learned_n ? DecodesAs<estimator_learned_n_t>(event)
                         : channel == c.controller_status   ? DecodesAs<controller_status_t>(event)
                                                            : false;  // a channel the simulator does not write
    if (!decoded) ++*decode_failures;
    ++counts[event.channel];
  }
  *truncated = reader.TruncatedTail();
  return counts;
}

TEST(SimLogTest, EveryChannelDecodesWithTheWireTypes) {
  const std::string path = TempPath("all_channels.lcm");
  {
    Simulator sim(LoadScenario(ScenarioPath("hover"), {"scenario.duration_s=1", "sensors.loadcell.enabled=true"}));
    LogWriter writer;
    std::string error;
    ASSERT_TRUE(writer.Open(path, &error)) << error;
    LogSink log_sink(&writer);
    WireSampleSink sink(MakeChannelNames(), &log_sink);
    sim.Run(&sink);
    ASSERT_TRUE(writer.Close());
  }
  int failures = 0;
  bool truncated = true;
  const std::map<std::string, int> counts = DecodeLog(path, &failures, &truncated);
  EXPECT_EQ(failures, 0);
  EXPECT_FALSE(truncated);
  EXPECT_EQ(counts.at("BIROTOR_STRAIN"), 1000);
  EXPECT_EQ(counts.at("BIROTOR_MOTOR"), 500);
  EXPECT_EQ(counts.at("BIROTOR_IMU"), 1000);
  EXPECT_EQ(counts.at("BIROTOR_POSE"), 100);
  EXPECT_EQ(counts.at("BIROTOR_LOADCELL"), 1000);
  EXPECT_EQ(counts.at("BIROTOR_TRUTH"), 1000);
  std::remove(path.c_str());
}

// Runs birotor-sim with args; returns its exit status, stderr in *err.
int RunSim(const std::string& args, std::string* err) {
  return RunProgram(BIROTOR_SIM_PATH, args, TempPath("stderr.txt"), err);
}

TEST(SimLogTest, SameSeedGivesAByteIdenticalLog) {
  const std::string a = TempPath("a.lcm"), b = TempPath("b.lcm"), c = TempPath("c.lcm");
  const std::string scenario = "--scenario " + ScenarioPath("hover") + " --set scenario.duration_s=2" +
                               " --set faults.strain_spike_probability=0.05 --log-level warn --output ";
  ASSERT_EQ(RunSim(scenario + a, nullptr), 0);
  ASSERT_EQ(RunSim(scenario + b, nullptr), 0);
  ASSERT_EQ(RunSim(scenario + c + " --set scenario.seed=7", nullptr), 0);
  const std::string bytes_a = ReadBytes(a);
  EXPECT_GT(bytes_a.size(), 100000u);
  EXPECT_TRUE(bytes_a == ReadBytes(b));
  EXPECT_FALSE(bytes_a == ReadBytes(c));
  int failures = 0;
  bool truncated = true;
  DecodeLog(a, &failures, &truncated);
  EXPECT_EQ(failures, 0);
  EXPECT_FALSE(truncated);
  for (const std::string& path : {a, b, c}) std::remove(path.c_str());
}

TEST(SimLogTest, ClosedLoopLogHasEveryChannelAndIsByteIdenticalForTheSameSeed) {
  const std::string a = TempPath("closed_a.lcm"), b = TempPath("closed_b.lcm");
  const std::string args = "--scenario " + ScenarioPath("hover") +
                           " --set scenario.duration_s=1 --controller force_feedback --log-level warn --output ";
  ASSERT_EQ(RunSim(args + a, nullptr), 0);
  ASSERT_EQ(RunSim(args + b, nullptr), 0);
  EXPECT_EQ(ReadBytes(a), ReadBytes(b));
  int decode_failures = 0;
  bool truncated = false;
  std::map<std::string, int> counts = DecodeLog(a, &decode_failures, &truncated);
  EXPECT_EQ(decode_failures, 0);
  EXPECT_FALSE(truncated);
  const ChannelNames c = MakeChannelNames();
  // 1 s: MOTOR_COMMAND at 500 Hz, one FORCE per strain sample (1 kHz).
  EXPECT_EQ(counts[c.motor_command], 500);
  EXPECT_EQ(counts[c.force], 1000);
  EXPECT_EQ(counts[c.strain], 1000);
  EXPECT_EQ(counts[c.motor], 500);
  EXPECT_EQ(counts[c.setpoint], 100);  // the trajectory at 100 Hz (ClosedLoopOptions)
  EXPECT_EQ(counts[c.truth], 1000);
  // The nodes' status at 5 Hz on the vehicle clock (the lock-step loop writes them as the nodes do).
  EXPECT_GE(counts[c.estimator_status], 4);
  EXPECT_EQ(counts[c.estimator_learned_n], counts[c.estimator_status]);  // one with each status
  EXPECT_GE(counts[c.controller_status], 4);
  std::remove(a.c_str());
  std::remove(b.c_str());
}

TEST(SimLogTest, ClosedLoopNeedsAnOutputLog) {
  std::string err;
  EXPECT_EQ(RunSim("--scenario " + ScenarioPath("hover") + " --controller nominal", &err), 2);
  EXPECT_NE(err.find("birotor-sim: error: --controller"), std::string::npos) << err;
}

// A live external controller flies on the wall clock: a simulator paced
// faster than it is refused before anything is published.
TEST(SimLogTest, ExternalControllerNeedsRealTime) {
  std::string err;
  EXPECT_EQ(RunSim("--scenario " + ScenarioPath("hover") + " --external-controller --speed 4", &err), 2);
  EXPECT_NE(err.find("birotor-sim: error: --external-controller is live and real time"), std::string::npos) << err;
}

TEST(SimLogTest, BadScenarioFileExitsNonZeroWithOneLineNamingFileAndKey) {
  const std::string path = TempPath("bad_scenario.yaml");
  std::ofstream(path) << "scenario:\n  duration_s: 5\nfaults:\n  strain_nan_times_s: [7]\n";
  std::string err;
  EXPECT_NE(RunSim("--scenario " + path + " --output " + TempPath("never.lcm"), &err), 0);
  EXPECT_NE(err.find(path), std::string::npos) << err;
  EXPECT_NE(err.find("faults.strain_nan_times_s"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  std::remove(path.c_str());
}

TEST(SimLogTest, SigtermClosesTheLogWithEveryEventComplete) {
  const std::string path = TempPath("interrupted.lcm");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // A bench run of 5 simulated minutes (seconds of CPU) that the signal cuts short.
    const std::string scenario = ScenarioPath("bench");
    ::execl(BIROTOR_SIM_PATH, BIROTOR_SIM_PATH, "--scenario", scenario.c_str(), "--set", "scenario.duration_s=300",
            "--output", path.c_str(), "--log-level", "error", nullptr);
    ::_exit(127);
  }
  // Signal once the log has data (the handlers are installed before it is opened).
  auto log_bytes = [&path] {
    std::error_code no_file;
    const uintmax_t size = std::filesystem::file_size(path, no_file);
    return no_file ? uintmax_t{0} : size;
  };
  for (int i = 0; i < 1000 && log_bytes() < 100000; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  int failures = 0;
  bool truncated = true;
  const std::map<std::string, int> counts = DecodeLog(path, &failures, &truncated);
  EXPECT_FALSE(truncated);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(counts.count("BIROTOR_STRAIN"), 0u);
  std::remove(path.c_str());
}

TEST(SimLogTest, LoopRepeatsTheScenarioWithTimeContinuing) {
  // Live mode at 10x real time into LCM's log-file provider (the live
  // publishing path, recorded): runs of 0.25 s until SIGTERM after 0.6 s.
  const std::string path = TempPath("loop.lcm");
  const std::string url = "file://" + path + "?mode=w";
  const std::string scenario = ScenarioPath("hover");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::execl(BIROTOR_SIM_PATH, BIROTOR_SIM_PATH, "--scenario", scenario.c_str(), "--set", "scenario.duration_s=0.25",
            "--loop", "--speed", "10", "--lcm-url", url.c_str(), "--log-level", "error", "--unsigned", "POSE", nullptr);
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(600));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);

  LogReader reader;
  std::string error;
  ASSERT_TRUE(reader.Open(path, &error)) << error;
  LogEvent event;
  std::vector<int64_t> utimes;
  while (reader.Next(&event)) {
    if (event.channel != "BIROTOR_STRAIN") continue;
    strain_t m;
    ASSERT_EQ(DecodeMessage(event.data.data(), event.data.size(), &m), DecodeError::kNone);
    utimes.push_back(m.utime);
  }
  // 0.6 s at 10x is about 6 s of simulated time: at least 3 runs of 250
  // samples, whatever the load on the machine.
  ASSERT_GT(utimes.size(), 750u);
  EXPECT_EQ(utimes.front(), 0);
  for (size_t i = 1; i < utimes.size(); ++i) {
    ASSERT_EQ(utimes[i] - utimes[i - 1], 1000) << "strain sample " << i << " (1 kHz: 1000 us apart across runs)";
  }
  std::remove(path.c_str());
}

TEST(SimLogTest, UnknownOptionIsNamedEvenWithoutTheRequiredScenario) {
  std::string err;
  EXPECT_EQ(RunSim("--bogus-option", &err), 2);
  EXPECT_EQ(err.rfind("birotor-sim: error: ", 0), 0u) << err;
  EXPECT_NE(err.find("--bogus-option"), std::string::npos) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace birotor
