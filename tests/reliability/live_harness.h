// Test helpers for the live reliability tests: start the real programs
// (birotor-estimator, birotor-sim, lcm-logplayer) as child processes, signal
// and reap only those, and record what the daemon publishes on a private
// udpm URL (ttl=0, one port per test, so ctest -j2 has no crosstalk).
#pragma once

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "birotor/estimator_status_t.hpp"
#include "birotor/force_estimate_t.hpp"
#include "transport/channels.h"
#include "transport/host_clock.h"
#include "transport/lcm_codec.h"
#include "transport/lcm_packet.h"

namespace birotor::reliability {

// Private udpm URL on loopback-only multicast (ttl=0) for one test. The
// environment variable BIROTOR_TEST_PORT_OFFSET shifts every port, so two
// checkouts can run the live tests at the same time without crosstalk.
inline int PrivatePort(int port) {
  const char* offset = std::getenv("BIROTOR_TEST_PORT_OFFSET");
  return offset != nullptr ? port + std::atoi(offset) : port;
}
inline std::string PrivateUrl(int port) {
  return "udpm://239.255.76.67:" + std::to_string(PrivatePort(port)) + "?ttl=0&recv_buf_size=4194304";
}

// Sends raw datagrams to the LCM group on a port (ttl=0), as an attacker on
// the host would: crafted LC02/LC03 packets that no LCM publisher makes.
class RawMulticastSender {
 public:
  explicit RawMulticastSender(int port) : fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    const unsigned char ttl = 0;
    setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl));
    const int size = 4 << 20;
    setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &size, sizeof(size));
    to_.sin_family = AF_INET;
    to_.sin_port = htons(static_cast<uint16_t>(port));
    inet_pton(AF_INET, "239.255.76.67", &to_.sin_addr);
  }
  ~RawMulticastSender() { close(fd_); }
  RawMulticastSender(const RawMulticastSender&) = delete;
  RawMulticastSender& operator=(const RawMulticastSender&) = delete;
  bool Send(const std::vector<uint8_t>& bytes) {
    return sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&to_), sizeof(to_)) ==
           static_cast<ssize_t>(bytes.size());
  }
  // Sends packets[first, last) with as few system calls as sendmmsg allows
  // (a burst sender that leaves the cores to the daemon under test). Returns
  // how many were sent.
  size_t SendBatch(const std::vector<std::vector<uint8_t>>& packets, size_t first, size_t last) {
    std::vector<iovec> iov(last - first);
    std::vector<mmsghdr> headers(last - first);
    for (size_t i = first; i < last; ++i) {
      iov[i - first] = {const_cast<uint8_t*>(packets[i].data()), packets[i].size()};
      msghdr& h = headers[i - first].msg_hdr;
      h = msghdr{};
      h.msg_name = &to_;
      h.msg_namelen = sizeof(to_);
      h.msg_iov = &iov[i - first];
      h.msg_iovlen = 1;
    }
    size_t sent = 0;
    while (sent < headers.size()) {
      const int n = sendmmsg(fd_, headers.data() + sent, static_cast<unsigned>(headers.size() - sent), 0);
      if (n <= 0) break;
      sent += static_cast<size_t>(n);
    }
    return sent;
  }

 private:
  int fd_;
  sockaddr_in to_{};
};

inline void PutBigEndian(uint64_t value, int bytes, std::vector<uint8_t>* out) {
  for (int i = bytes - 1; i >= 0; --i) out->push_back(static_cast<uint8_t>(value >> (8 * i)));
}

// An LC02 datagram: header, channel, NUL, payload.
inline std::vector<uint8_t> SmallMessageDatagram(const std::string& channel, const std::vector<uint8_t>& payload,
                                                 uint32_t seqno) {
  std::vector<uint8_t> packet;
  PutBigEndian(kLcmSmallMessageMagic, 4, &packet);
  PutBigEndian(seqno, 4, &packet);
  packet.insert(packet.end(), channel.begin(), channel.end());
  packet.push_back(0);
  packet.insert(packet.end(), payload.begin(), payload.end());
  return packet;
}

// An LC03 fragment header (20 bytes) followed by body.
inline std::vector<uint8_t> FragmentDatagram(uint32_t seqno, uint32_t message_size, uint32_t fragment_offset,
                                             uint16_t fragment_no, uint16_t fragments_in_message,
                                             const std::vector<uint8_t>& body) {
  std::vector<uint8_t> packet;
  PutBigEndian(kLcmFragmentMagic, 4, &packet);
  PutBigEndian(seqno, 4, &packet);
  PutBigEndian(message_size, 4, &packet);
  PutBigEndian(fragment_offset, 4, &packet);
  PutBigEndian(fragment_no, 2, &packet);
  PutBigEndian(fragments_in_message, 2, &packet);
  packet.insert(packet.end(), body.begin(), body.end());
  return packet;
}

// Issue 16/23 fragment attacks on one channel; returns the datagrams sent.
// 1. The two datagrams that crash LCM's _recv_message_fragment (lcm-logger
// 1.3.1 on the same port: exit 139): fragment 1 carrying a short channel
// name, then a header-only fragment 0 with offset 11 of the same message.
// LCM reads the name again from the stale bytes past the second packet,
// frag_size = 0 - 7 underflows, 11 + frag_size wraps below 100, and memcpy
// copies about 4 GB.
// 2. `fragments` fragments of a message on channel declared as 256 MB, never
// completed (LCM allocates the whole message and keeps it: RSS 7 -> 101 MB
// after 1500). seqno tells attacks on several channels apart.
inline int SendFragmentAttack(RawMulticastSender* attacker, const std::string& channel, int fragments, uint32_t seqno) {
  int sent = 0;
  const std::vector<uint8_t> short_name = {'S', 'T', 'R', 'A', 'I', 'N', 0};
  if (attacker->Send(FragmentDatagram(seqno, 100, 0, 1, 2, short_name))) ++sent;
  if (attacker->Send(FragmentDatagram(seqno, 100, 11, 0, 2, {}))) ++sent;
  std::vector<uint8_t> name(channel.begin(), channel.end());
  name.push_back(0);
  const uint32_t declared = 256u << 20;
  const std::vector<uint8_t> body(65000, 0x5A);
  for (int i = 0; i < fragments; ++i) {
    std::vector<uint8_t> fragment_body;
    if (i == 0) fragment_body = name;
    fragment_body.insert(fragment_body.end(), body.begin(), body.end());
    if (attacker->Send(FragmentDatagram(seqno + 1, declared, static_cast<uint32_t>(i) * 65000u,
                                        static_cast<uint16_t>(i), 4130, fragment_body))) {
      ++sent;
    }
  }
  return sent;
}

// Resident set size of a process [kB] (VmRSS in /proc/<pid>/status); -1 if unknown.
inline int64_t ResidentKb(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      int64_t kb = -1;
      status >> kb;
      return kb;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

// This test process's site key: 32 random bytes in a file only its owner
// reads and writes, made once.
inline const std::string& TestSiteKey() {
  static const std::string path = [] {
    const std::string key_path = "/tmp/birotor_reliability_" + std::to_string(getpid()) + "_site.key";
    const int fd = open(key_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW, 0600);
    std::ifstream random("/dev/urandom", std::ios::binary);
    char bytes[32];
    random.read(bytes, sizeof(bytes));
    if (fd < 0 || write(fd, bytes, sizeof(bytes)) != static_cast<ssize_t>(sizeof(bytes))) std::abort();
    close(fd);
    return key_path;
  }();
  return path;
}

// A daemon's command line with --site-key TestSiteKey() added (the
// simulator, the estimator, the controller and the latency probe
// authenticate MOTOR_COMMAND, SETPOINT, POSE and FORCE), unless it names
// a key itself. A program is recognised by its path as the test's CMake
// definitions give it.
inline std::vector<std::string> WithTestSiteKey(std::vector<std::string> argv) {
  const std::vector<std::string> daemons = {
#ifdef BIROTOR_SIM_BIN
      BIROTOR_SIM_BIN,
#endif
#ifdef BIROTOR_ESTIMATOR_BIN
      BIROTOR_ESTIMATOR_BIN,
#endif
#ifdef BIROTOR_CONTROLLER_BIN
      BIROTOR_CONTROLLER_BIN,
#endif
#ifdef BIROTOR_LATENCY_PROBE_BIN
      BIROTOR_LATENCY_PROBE_BIN,
#endif
  };
  bool daemon = false;
  for (const std::string& path : daemons) daemon = daemon || (!argv.empty() && argv[0] == path);
  for (const std::string& arg : argv) {
    if (arg == "--site-key") return argv;
  }
  if (daemon) {
    argv.push_back("--site-key");
    argv.push_back(TestSiteKey());
  }
  return argv;
}

// A child process; the destructor SIGKILLs and reaps it if it still runs.
class ChildProcess {
 public:
  ChildProcess() = default;
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() { Kill(SIGKILL); }

  // Starts argv[0] with stdout and stderr appended to log_path (a daemon
  // with this test process's site key, WithTestSiteKey). False on failure.
  bool Start(const std::vector<std::string>& command, const std::string& log_path) {
    const std::vector<std::string> argv = WithTestSiteKey(command);
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_ = fork();
    if (pid_ < 0) return false;
    if (pid_ == 0) {
      const int fd = open(log_path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (fd >= 0) {
        dup2(fd, 1);
        dup2(fd, 2);
      }
      execv(args[0], args.data());
      _exit(127);
    }
    return true;
  }
  int pid() const { return pid_; }
  bool running() const { return pid_ > 0; }
  void Signal(int signal_number) const {
    if (pid_ > 0) kill(pid_, signal_number);
  }
  // Sends signal_number and reaps the process.
  void Kill(int signal_number) {
    if (pid_ <= 0) return;
    kill(pid_, signal_number);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  // SIGTERM, then SIGKILL after timeout_s. Returns the exit status (or -1).
  int Stop(double timeout_s = 5.0) {
    if (pid_ <= 0) return -1;
    kill(pid_, SIGTERM);
    const double deadline = SteadyClockS() + timeout_s;
    int status = 0;
    while (SteadyClockS() < deadline) {
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    Kill(SIGKILL);
    return -1;
  }
  // True while the process has not exited (reaps it if it has).
  bool Alive() {
    if (pid_ <= 0) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      pid_ = -1;
      return false;
    }
    return true;
  }

 private:
  pid_t pid_ = -1;
};

// One FORCE or ESTIMATOR_STATUS as received, with the host arrival time.
// Decodes an LCM message into a new record (arrival time on the steady
// clock) and appends it under the lock; an undecodable message is skipped.
// Record has arrival_s and message (of the channel's type).
template <typename Record>
void AppendDecoded(const lcm::ReceiveBuffer* buffer, std::mutex* mutex, std::vector<Record>* records) {
  Record record;
  record.arrival_s = SteadyClockS();
  if (DecodeMessage(buffer->data, buffer->data_size, &record.message) != DecodeError::kNone) return;
  std::lock_guard<std::mutex> lock(*mutex);
  records->push_back(record);
}

struct ForceRecord {
  double arrival_s = 0;  // steady clock [s]
  force_estimate_t message;
};
struct StatusRecord {
  double arrival_s = 0;
  estimator_status_t message;
};

// Subscribes to FORCE and ESTIMATOR_STATUS of a prefix on its own thread.
class DaemonListener {
 public:
  DaemonListener(const std::string& url, const std::string& prefix) : lcm_(url), channels_(MakeChannelNames(prefix)) {
    lcm_.subscribe(channels_.force, &DaemonListener::OnForce, this)->setQueueCapacity(100000);
    lcm_.subscribe(channels_.estimator_status, &DaemonListener::OnStatus, this)->setQueueCapacity(1000);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~DaemonListener() {
    stop_ = true;
    thread_.join();
  }
  bool good() { return lcm_.good(); }
  const ChannelNames& channels() const { return channels_; }

  // Copies of everything received so far.
  std::vector<ForceRecord> Forces() {
    std::lock_guard<std::mutex> lock(mutex_);
    return forces_;
  }
  std::vector<StatusRecord> Statuses() {
    std::lock_guard<std::mutex> lock(mutex_);
    return statuses_;
  }
  // Polls predicate every 10 ms until it holds or timeout_s passes.
  static bool WaitUntil(const std::function<bool()>& predicate, double timeout_s) {
    const double deadline = SteadyClockS() + timeout_s;
    while (SteadyClockS() < deadline) {
      if (predicate()) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return predicate();
  }
  // First FORCE arriving at or after since_s whose status has all of `bits`;
  // nullptr-like (arrival_s < 0) if none.
  ForceRecord FirstForceWith(int32_t bits, double since_s) {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const ForceRecord& r : forces_) {
      if (r.arrival_s >= since_s && (r.message.status & bits) == bits) return r;
    }
    ForceRecord none;
    none.arrival_s = -1;
    return none;
  }

 private:
  void OnForce(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    AppendDecoded(buffer, &mutex_, &forces_);
  }
  void OnStatus(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    AppendDecoded(buffer, &mutex_, &statuses_);
  }

  lcm::LCM lcm_;
  ChannelNames channels_;
  std::mutex mutex_;
  std::vector<ForceRecord> forces_;
  std::vector<StatusRecord> statuses_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The programs under test run with the real-time priorities of the shipped
// units and the demo (docs/realtime.md): the simulator stands for the
// vehicle's physics and ESCs, above the controller, above the estimator. Under
// SCHED_FIFO a CPU hog beside the suite (tools/test-under-load.sh) cannot
// delay them; where the system refuses (no CAP_SYS_NICE) each warns once and
// runs on the normal scheduler.
inline constexpr const char* kSimPriority = "60";
inline constexpr const char* kControllerPriority = "55";
inline constexpr const char* kEstimatorPriority = "50";

// Command lines of the programs under test (paths from CMake).
inline std::vector<std::string> DaemonCommand(const std::string& url, const std::string& prefix) {
  return {BIROTOR_ESTIMATOR_BIN, "--lcm-url",       url, "--prefix", prefix, "--status-rate-hz", "20",
          "--realtime-priority", kEstimatorPriority};
}
#ifdef BIROTOR_CONTROLLER_BIN
// birotor-controller --mode mode (force_feedback or mpc), warnings only.
inline std::vector<std::string> ControllerCommand(const std::string& url, const std::string& prefix,
                                                  const std::string& mode) {
  return {BIROTOR_CONTROLLER_BIN, "--lcm-url",        url, "--prefix", prefix, "--mode", mode, "--log-level", "warn",
          "--realtime-priority",  kControllerPriority};
}
#endif
inline std::vector<std::string> SimCommand(const std::string& url, const std::string& prefix, double duration_s) {
  return {BIROTOR_SIM_BIN, "--scenario", std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml",
          "--lcm-url",     url,          "--prefix",
          prefix,          "--set",      "scenario.duration_s=" + std::to_string(duration_s),
          "--log-level",   "warn",       "--realtime-priority",
          kSimPriority};
}

// The plumbing of a test's listener: an LCM instance on the private URL whose
// subscriptions are handled on its own thread from Start() until destruction.
// A listener holds it as its last member, so that the thread stops before the
// state its handlers write is destroyed.
class ListenerThread {
 public:
  ListenerThread(const std::string& url, const std::string& prefix) : lcm_(url), channels_(MakeChannelNames(prefix)) {}
  ~ListenerThread() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  const ChannelNames& channels() const { return channels_; }
  template <class Listener>
  void Subscribe(const std::string& channel, void (Listener::*handler)(const lcm::ReceiveBuffer*, const std::string&),
                 Listener* listener) {
    lcm_.subscribe(channel, handler, listener)->setQueueCapacity(100000);
  }
  void Start() {
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  bool good() { return lcm_.good(); }

 private:
  lcm::LCM lcm_;
  ChannelNames channels_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Channel prefix unique to this test process: the same test running from
// another build directory at the same time (a shared machine) does not mix in.
inline std::string UniquePrefix(const std::string& base) { return base + std::to_string(getpid()) + "_"; }

// The whole text of a file ("" when it cannot be read): a daemon's log.
inline std::string ReadTextFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Temporary file path for a test's logs.
inline std::string TempPath(const std::string& name) {
  return "/tmp/birotor_reliability_" + std::to_string(getpid()) + "_" + name;
}

}  // namespace birotor::reliability
