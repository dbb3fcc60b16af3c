// birotor-monitor watching a "vehicle": the real estimator daemon and the
// simulator with its TRUTH channel switched off (birotor-sim --no-truth), three
// processes on a private udpm URL (loopback, ttl=0). The monitor switches to
// its vehicle view by itself, says so, ends when FORCE stops, and writes its
// plot with nothing beside it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "tests/plot/plot_test_support.h"
#include "tests/reliability/live_harness.h"

namespace birotor::reliability {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream file(path);
  return std::string(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
}

TEST(MonitorLiveTest, VehicleViewWithoutTruthOverUdpm) {
  const std::string url = PrivateUrl(7731);
  const std::string prefix = UniquePrefix("MON_NOTRUTH_");
  TemporaryFolder folder("birotor_monitor_live_");
  const std::string png = folder.path() + "/vehicle plot.png";
  const std::string monitor_log = TempPath("monitor_live_monitor.log");
  std::remove(monitor_log.c_str());

  ChildProcess daemon, monitor, sim;
  ASSERT_TRUE(daemon.Start(DaemonCommand(url, prefix), TempPath("monitor_live_daemon.log")));
  ASSERT_TRUE(
      monitor.Start({BIROTOR_MONITOR_BIN, "--lcm-url", url, "--prefix", prefix, "--until-sim-ends", "--idle-s", "1.0",
                     "--truth-wait-s", "0.5", "--interval-s", "0.5", "--plain", "--png", png, "--label", "vehicle"},
                    monitor_log));
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let both subscribe
  std::vector<std::string> sim_command = SimCommand(url, prefix, 2.0);
  sim_command.push_back("--no-truth");
  ASSERT_TRUE(sim.Start(sim_command, TempPath("monitor_live_sim.log")));

  // 2 s of flight, 1 s of silence, the summary and the plot; generous on a loaded machine.
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !monitor.Alive(); }, 60.0)) << ReadText(monitor_log);
  EXPECT_EQ(sim.Stop(), 0);
  EXPECT_EQ(daemon.Stop(), 0);
  const std::string text = ReadText(monitor_log);
  EXPECT_NE(text.find("no " + prefix + "TRUTH within 0.5 s of the first FORCE: vehicle view"), std::string::npos)
      << text;
  EXPECT_NE(text.find("vehicle summary (vehicle, ekf; no TRUTH, so no errors)"), std::string::npos) << text;
  EXPECT_NE(text.find("received: TRUTH 0 "), std::string::npos) << text;
  EXPECT_NE(text.find("strain NIS over the run mean"), std::string::npos) << text;
  EXPECT_EQ(text.find("error:"), std::string::npos) << text;
  // 2 s of strain at 1 kHz (hover.yaml) gives 2000 FORCE; at most a third lost on a loaded machine.
  std::smatch match;
  ASSERT_TRUE(std::regex_search(text, match, std::regex("FORCE ([0-9]+) messages over"))) << text;
  EXPECT_GE(std::stoi(match[1]), 1334) << text;
  EXPECT_LE(std::stoi(match[1]), 2001) << text;
  EXPECT_NE(text.find("plot: " + png), std::string::npos) << text;
  EXPECT_EQ(ReadPngSize(png).width, 1200u);
  EXPECT_EQ(folder.Entries(), std::vector<std::string>{"vehicle plot.png"});
}

}  // namespace
}  // namespace birotor::reliability
