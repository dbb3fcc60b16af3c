// The N-arm daemon live (birotor-estimator --vehicle): the trirotor's
// simulator (birotor-sim --vehicle) and the estimator as two processes on a
// private udpm URL (ttl=0). Every FORCE_N is decodable, has three rotors and
// finite values, VALID comes once the filter converged, and the estimator
// publishes one FORCE_N per strain sample it received. Nothing is asserted on
// the wall clock; a strain packet lost in a loaded kernel is not the
// estimator's, so the count is checked against what it received.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "birotor/force_estimate_n_t.hpp"
#include "tests/reliability/live_harness.h"

namespace birotor::reliability {
namespace {

// Every FORCE_N on the prefix, decoded.
class ForceNListener {
 public:
  ForceNListener(const std::string& url, const std::string& prefix) : lcm_(url) {
    lcm_.subscribe(MakeChannelNames(prefix).force_n, &ForceNListener::OnForce, this)->setQueueCapacity(100000);
    thread_ = std::thread([this] {
      while (!stop_.load()) lcm_.handleTimeout(20);
    });
  }
  ~ForceNListener() {
    stop_ = true;
    thread_.join();
  }
  bool good() { return lcm_.good(); }
  std::vector<force_estimate_n_t> Forces() {
    std::lock_guard<std::mutex> lock(mutex_);
    return forces_;
  }

 private:
  void OnForce(const lcm::ReceiveBuffer* buffer, const std::string& /*channel*/) {
    force_estimate_n_t message;
    if (DecodeMessage(buffer->data, buffer->data_size, &message) != DecodeError::kNone) return;
    std::lock_guard<std::mutex> lock(mutex_);
    forces_.push_back(message);
  }

  lcm::LCM lcm_;
  std::mutex mutex_;
  std::vector<force_estimate_n_t> forces_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

TEST(LiveVehicleTest, TrirotorEstimatorPublishesOneFiniteForceNPerStrainSample) {
  const std::string url = PrivateUrl(7755);
  const std::string prefix = UniquePrefix("REL_VEHICLE_");
  const std::string vehicle = std::string(BIROTOR_SOURCE_DIR) + "/config/vehicles/trirotor.yaml";
  const std::string estimator_log = TempPath("vehicle_estimator.log");
  const std::string sim_log = TempPath("vehicle_sim.log");
  std::remove(estimator_log.c_str());
  ForceNListener listener(url, prefix);
  ASSERT_TRUE(listener.good());
  ChildProcess estimator;
  ASSERT_TRUE(estimator.Start(
      {BIROTOR_ESTIMATOR_BIN, "--vehicle", vehicle, "--lcm-url", url, "--prefix", prefix, "--params",
       std::string(BIROTOR_SOURCE_DIR) + "/config/estimator.yaml", "--realtime-priority", kEstimatorPriority},
      estimator_log));
  ASSERT_TRUE(
      DaemonListener::WaitUntil([&] { return ReadTextFile(estimator_log).find(": in ") != std::string::npos; }, 20))
      << ReadTextFile(estimator_log);
  ChildProcess sim;
  ASSERT_TRUE(
      sim.Start({BIROTOR_SIM_BIN, "--vehicle", vehicle, "--scenario",
                 std::string(BIROTOR_SOURCE_DIR) + "/config/scenarios/hover.yaml", "--lcm-url", url, "--prefix", prefix,
                 "--set", "scenario.duration_s=3", "--log-level", "warn", "--realtime-priority", kSimPriority},
                sim_log));
  ASSERT_TRUE(DaemonListener::WaitUntil([&] { return !sim.Alive(); }, 60)) << "the simulator did not finish";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the last FORCE_N arrives
  EXPECT_EQ(estimator.Stop(), 0);
  const std::string log = ReadTextFile(estimator_log);
  long published = -1, received = -1;
  const size_t at = log.find("stopped: ");
  ASSERT_NE(at, std::string::npos) << log;
  std::sscanf(log.c_str() + at, "stopped: %ld FORCE_N published; strain received %ld", &published, &received);
  std::printf("trirotor live: %ld strain received, %ld FORCE_N published, %zu FORCE_N heard\n", received, published,
              listener.Forces().size());
  EXPECT_GT(received, 1500);  // 3 s at 1 kHz, less what a loaded kernel dropped
  EXPECT_EQ(published, received);
  const std::vector<force_estimate_n_t> forces = listener.Forces();
  ASSERT_GT(forces.size(), 1000u);
  for (const force_estimate_n_t& m : forces) {
    ASSERT_EQ(m.n_rotors, 3);
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(std::isfinite(m.force_n[static_cast<size_t>(i)]) &&
                  std::isfinite(m.force_std_n[static_cast<size_t>(i)]));
    }
  }
  EXPECT_NE(forces.back().status & force_estimate_n_t::STATUS_VALID, 0);
  EXPECT_EQ(forces.back().rotor_fault_bits, 0);
}

}  // namespace
}  // namespace birotor::reliability
