// The committed regression trace: the EKF over a short committed input log
// (thrust_loss, 4.75 s to 5.25 s: converging from start, then rotor 2 losing a
// quarter of its thrust at 5 s) must reproduce tests/data/ekf_trace.csv to
// 1e-9 relative. Any change in the filter's numbers shows up here.
//
// Regenerate both files after an intended change (and review the diff):
//   BIROTOR_REGENERATE_TRACE=1 <build>/tests/replay/replay_test --gtest_filter='EkfRegressionTrace*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "replay/replayer.h"
#include "simulator/simulator.h"
#include "sinks/force_csv_sink.h"
#include "sinks/message_sink.h"
#include "sinks/wire_sample_sink.h"
#include "tests/replay/replay_test_support.h"

namespace birotor {
namespace {

const std::string kDataDir = std::string(BIROTOR_SOURCE_DIR) + "/tests/data";
const std::string kInputLog = kDataDir + "/ekf_trace_input.lcm";
const std::string kTraceCsv = kDataDir + "/ekf_trace.csv";
constexpr int64_t kWindowStartUs = 4'750'000;
constexpr double kWindowEndS = 5.25;

// Passes the STRAIN, MOTOR and IMU messages of the window on to next.
class WindowFilter : public MessageSink {
 public:
  WindowFilter(const ChannelNames& channels, MessageSink* next) : channels_(channels), next_(next) {}
  void Publish(const std::string& channel, int64_t timestamp_us, const void* data, size_t size) override {
    const bool input = channel == channels_.strain || channel == channels_.motor || channel == channels_.imu;
    if (input && timestamp_us >= kWindowStartUs) next_->Publish(channel, timestamp_us, data, size);
  }

 private:
  ChannelNames channels_;
  MessageSink* next_;
};

void RegenerateInputLog() {
  LogWriter writer;
  std::string error;
  ASSERT_TRUE(writer.Open(kInputLog, &error)) << error;
  LogSink log_sink(&writer);
  WindowFilter window(MakeChannelNames(), &log_sink);
  WireSampleSink sink(MakeChannelNames(), &window);
  Simulator simulator(ReferenceScenario("thrust_loss"));
  while (!simulator.done() && simulator.time_s() < kWindowEndS) simulator.Step(&sink);
  ASSERT_TRUE(writer.Close());
}

// The trace of the EKF (default EstimatorConfig) over the committed input.
std::vector<std::string> TraceRows() {
  const std::string csv_path = TempPath("ekf_trace.csv");
  std::FILE* csv = std::fopen(csv_path.c_str(), "w");
  EXPECT_NE(csv, nullptr);
  {
    ForceCsvSink sink(csv, MakeChannelNames().force, nullptr);
    EstimatorConfig config;
    config.method = "ekf";
    Replayer replayer(config, ReplayOptions{}, &sink);
    std::string error;
    EXPECT_TRUE(ReplayLogFile(kInputLog, &replayer, nullptr, &error)) << error;
  }
  std::fclose(csv);
  std::vector<std::string> rows;
  std::istringstream in(ReadFileBytes(csv_path));
  for (std::string line; std::getline(in, line);) rows.push_back(line);
  return rows;
}

std::vector<double> Fields(const std::string& row) {
  std::vector<double> values;
  std::istringstream in(row);
  for (std::string field; std::getline(in, field, ',');) values.push_back(std::strtod(field.c_str(), nullptr));
  return values;
}

TEST(EkfRegressionTraceTest, ReplayReproducesTheCommittedTrace) {
  if (std::getenv("BIROTOR_REGENERATE_TRACE") != nullptr) {
    RegenerateInputLog();
    const std::vector<std::string> rows = TraceRows();
    std::FILE* out = std::fopen(kTraceCsv.c_str(), "w");
    ASSERT_NE(out, nullptr);
    for (const std::string& row : rows) std::fprintf(out, "%s\n", row.c_str());
    std::fclose(out);
    GTEST_SKIP() << "regenerated " << kInputLog << " and " << kTraceCsv;
  }
  const std::vector<std::string> actual = TraceRows();
  std::vector<std::string> expected;
  std::istringstream in(ReadFileBytes(kTraceCsv));
  for (std::string line; std::getline(in, line);) expected.push_back(line);
  ASSERT_GT(expected.size(), 400u) << "missing or empty " << kTraceCsv;
  ASSERT_EQ(actual.size(), expected.size());
  EXPECT_EQ(actual[0], expected[0]);  // header
  for (size_t k = 1; k < expected.size(); ++k) {
    const std::vector<double> a = Fields(actual[k]);
    const std::vector<double> e = Fields(expected[k]);
    ASSERT_EQ(a.size(), e.size()) << "row " << k;
    for (size_t i = 0; i < e.size(); ++i) {
      const double tolerance = 1e-9 * std::max(1.0, std::abs(e[i]));
      ASSERT_NEAR(a[i], e[i], tolerance) << "row " << k << " column " << i << "\n  expected " << expected[k]
                                         << "\n  actual   " << actual[k];
    }
  }
}

}  // namespace
}  // namespace birotor
