// Issue 23 item 8, live on private udpm ports: the daemons survive SIGHUP,
// SIGUSR1, SIGUSR2, SIGALRM and SIGPIPE and still stop cleanly on SIGTERM;
// the estimator survives a log reader that exits (EPIPE on stderr); the
// controller runs with its standard streams closed; a prefix over LCM's
// channel limit is refused at start-up in one line; two estimators on one
// prefix flag each other.
#include <fcntl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "birotor/strain_t.hpp"
#include "tests/reliability/live_harness.h"

namespace birotor::reliability {
namespace {

std::string ReadText(const std::string& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

// Starts argv with stdin, stdout and stderr closed, or stderr on a pipe
// whose reader is closed at once (stderr_to_closed_pipe). Returns the pid.
pid_t StartDetached(const std::vector<std::string>& command, bool stderr_to_closed_pipe) {
  const std::vector<std::string> argv = WithTestSiteKey(command);
  int pipe_fds[2] = {-1, -1};
  if (stderr_to_closed_pipe && pipe(pipe_fds) != 0) return -1;
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (stderr_to_closed_pipe) {
      dup2(pipe_fds[1], 2);
      close(pipe_fds[0]);
      close(pipe_fds[1]);
    } else {
      close(0);
      close(1);
      close(2);
    }
    execv(args[0], args.data());
    _exit(127);
  }
  if (stderr_to_closed_pipe) {
    close(pipe_fds[0]);  // the reader exits: every write to stderr gets EPIPE
    close(pipe_fds[1]);
  }
  return pid;
}

// SIGTERM, then the exit status (-1 for a death by signal or a timeout).
int StopPid(pid_t pid) {
  kill(pid, SIGTERM);
  for (int i = 0; i < 250; ++i) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
  return -1;
}

bool PidAlive(pid_t pid) {
  int status = 0;
  return waitpid(pid, &status, WNOHANG) == 0;
}

void SendSignalsThatUsedToKill(ChildProcess* child) {
  for (const int signal_number : {SIGHUP, SIGUSR1, SIGUSR2, SIGALRM, SIGPIPE}) {
    child->Signal(signal_number);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}

TEST(SignalsTest, DaemonsSurviveHangupUserAlarmAndPipeSignals) {
  const std::string url = PrivateUrl(7747);
  const std::string prefix = UniquePrefix("REL_SIGNALS_");
  struct Daemon {
    std::string name;
    std::vector<std::string> argv;
  };
  std::vector<std::string> sim = SimCommand(url, prefix, 30.0);
  const std::vector<Daemon> daemons = {
      {"estimator", DaemonCommand(url, prefix)},
      {"controller", {BIROTOR_CONTROLLER_BIN, "--lcm-url", url, "--prefix", prefix}},
      {"sim", sim},
  };
  for (const Daemon& daemon : daemons) {
    const std::string log = TempPath("signals_" + daemon.name + ".log");
    std::remove(log.c_str());
    ChildProcess child;
    ASSERT_TRUE(child.Start(daemon.argv, log));
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    SendSignalsThatUsedToKill(&child);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_TRUE(child.Alive()) << daemon.name << " died of a signal; log: " << ReadText(log);
    EXPECT_EQ(child.Stop(), 0) << daemon.name << " log: " << ReadText(log);
    if (daemon.name != "sim") {  // the receive loop says what it ignored
      EXPECT_NE(ReadText(log).find("SIGHUP x1"), std::string::npos) << daemon.name << " log: " << ReadText(log);
    }
  }
}

TEST(SignalsTest, EstimatorSurvivesALogReaderThatExits) {
  const int port = PrivatePort(7748);
  const std::string url = PrivateUrl(7748);
  const std::string prefix = UniquePrefix("REL_EPIPE_");
  const pid_t pid = StartDetached(DaemonCommand(url, prefix), true);
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  // Undecodable strain packets: a warning each second on the closed stderr.
  RawMulticastSender sender(port);
  for (int i = 0; i < 30; ++i) {
    sender.Send(SmallMessageDatagram(prefix + "STRAIN", {1, 2, 3}, static_cast<uint32_t>(i)));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(PidAlive(pid)) << "the estimator died writing to a closed log pipe (exit 141 before)";
  EXPECT_EQ(StopPid(pid), 0);
}

TEST(SignalsTest, ControllerRunsWithItsStandardStreamsClosed) {
  const std::string url = PrivateUrl(7749);
  const std::string prefix = UniquePrefix("REL_CLOSED_");
  const pid_t pid = StartDetached({BIROTOR_CONTROLLER_BIN, "--lcm-url", url, "--prefix", prefix}, false);
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(2000));
  EXPECT_TRUE(PidAlive(pid)) << "the controller stopped with its standard streams closed (exit 0 at once before)";
  EXPECT_EQ(StopPid(pid), 0);
}

TEST(SignalsTest, APrefixOverTheChannelLimitIsRefusedAtStartUp) {
  const std::string log = TempPath("long_prefix.log");
  std::remove(log.c_str());
  ChildProcess child;
  ASSERT_TRUE(
      child.Start({BIROTOR_ESTIMATOR_BIN, "--lcm-url", PrivateUrl(7750), "--prefix", std::string(47, 'P')}, log));
  int status = -1;
  for (int i = 0; i < 250 && child.Alive(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_FALSE(child.Alive());
  status = child.Stop();  // already reaped: -1 from Stop, so read the log
  (void)status;
  const std::string text = ReadText(log);
  EXPECT_NE(text.find("longer than 43"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
}

TEST(SignalsTest, TwoEstimatorsOnOnePrefixFlagEachOther) {
  const std::string url = PrivateUrl(7751);
  const std::string prefix = UniquePrefix("REL_TWO_");
  const std::string log_a = TempPath("two_a.log"), log_b = TempPath("two_b.log");
  std::remove(log_a.c_str());
  std::remove(log_b.c_str());
  DaemonListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  ChildProcess a, b;
  ASSERT_TRUE(a.Start(DaemonCommand(url, prefix), log_a));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_TRUE(b.Start(DaemonCommand(url, prefix), log_b));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  lcm::LCM publisher(url);
  ASSERT_TRUE(publisher.good());
  const double start_s = SteadyClockS();
  for (int i = 0; i < 1000; ++i) {
    strain_t strain{};
    strain.utime = 1000000 + 1000 * i;
    strain.seq = i;
    strain.deflection_rad[0] = -0.0018664;  // hover deflection (tests/estimator equilibrium)
    strain.deflection_rad[1] = 0.0018664;
    std::vector<uint8_t> bytes;
    EncodeMessage(strain, &bytes);
    publisher.publish(prefix + "STRAIN", bytes.data(), static_cast<unsigned>(bytes.size()));
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));  // a status after the last FORCE
  EXPECT_GE(listener.FirstForceWith(force_estimate_t::STATUS_INPUT_CONFLICT, start_s).arrival_s, 0)
      << "no FORCE said INPUT_CONFLICT";
  int64_t foreign_reported = 0;
  for (const StatusRecord& status : listener.Statuses()) {
    foreign_reported = std::max<int64_t>(foreign_reported, status.message.foreign_force);
  }
  EXPECT_GT(foreign_reported, 0);
  EXPECT_EQ(a.Stop(), 0);
  EXPECT_EQ(b.Stop(), 0);
  // Each one saw the other.
  EXPECT_NE(ReadText(log_a).find("did not publish"), std::string::npos) << ReadText(log_a);
  EXPECT_NE(ReadText(log_b).find("did not publish"), std::string::npos) << ReadText(log_b);
}

}  // namespace
}  // namespace birotor::reliability
