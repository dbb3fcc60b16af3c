// The daemons' systemd notifications: what reaches NOTIFY_SOCKET (a datagram
// socket of the test standing in for systemd) and when.
#include "deploy/systemd_notify.h"

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

namespace birotor {
namespace {

class FakeSystemd {
 public:
  FakeSystemd() {
    path_ = "/tmp/birotor-notify-" + std::to_string(getpid()) + ".sock";
    unlink(path_.c_str());
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    path_.copy(address.sun_path, sizeof(address.sun_path) - 1);
    EXPECT_EQ(bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
    setenv("NOTIFY_SOCKET", path_.c_str(), 1);
  }
  ~FakeSystemd() {
    unsetenv("NOTIFY_SOCKET");
    close(fd_);
    unlink(path_.c_str());
  }
  // The next message, "" when none is waiting.
  std::string Next() {
    char buffer[256];
    const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
    return n > 0 ? std::string(buffer, static_cast<size_t>(n)) : "";
  }

 private:
  std::string path_;
  int fd_ = -1;
};

TEST(SystemdNotifyTest, ReadyAndWatchdogAtHalfThePeriod) {
  FakeSystemd systemd;
  // WatchdogSec=4s: systemd sets WATCHDOG_USEC and WATCHDOG_PID.
  setenv("WATCHDOG_USEC", "4000000", 1);
  setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  ASSERT_TRUE(NotifyReady());
  EXPECT_EQ(systemd.Next(), "READY=1");
  EXPECT_EQ(WatchdogPeriodUs(), 4000000);
  // The loop calls it every iteration; it sends at most every 2 s (half of 4 s).
  EXPECT_FALSE(NotifyWatchdog());
  EXPECT_EQ(systemd.Next(), "");
  const int64_t start_us = int64_t{1} << 50;  // after any steady-clock reading
  EXPECT_TRUE(NotifyWatchdogAt(start_us));    // sends, and is the reference time
  systemd.Next();
  EXPECT_FALSE(NotifyWatchdogAt(start_us + 1'999'999));
  EXPECT_TRUE(NotifyWatchdogAt(start_us + 2'000'000));
  EXPECT_EQ(systemd.Next(), "WATCHDOG=1");
  NotifyStopping();
  EXPECT_EQ(systemd.Next(), "STOPPING=1");
  unsetenv("WATCHDOG_USEC");
  unsetenv("WATCHDOG_PID");
}

TEST(SystemdNotifyTest, NothingWithoutSystemd) {
  unsetenv("NOTIFY_SOCKET");
  unsetenv("WATCHDOG_USEC");
  EXPECT_FALSE(NotifyReady());
  EXPECT_EQ(WatchdogPeriodUs(), 0);
  EXPECT_FALSE(NotifyWatchdogAt(int64_t{1} << 50));
}

}  // namespace
}  // namespace birotor
