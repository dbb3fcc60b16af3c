// Regression trace: the reference `hover` scenario (first 0.5 s) replayed
// through the EKF pipeline, every 10th estimate diffed against the committed
// tests/estimator/data/ekf_hover_trace.csv, so any change in the numbers shows
// in review. After an intended change, regenerate with
//   BIROTOR_UPDATE_TRACE=1 estimator_test --gtest_filter='EkfRegressionTrace*'
// and commit the new file with the change.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

constexpr char kTraceFile[] = BIROTOR_SOURCE_DIR "/tests/estimator/data/ekf_hover_trace.csv";
constexpr char kHeader[] = "utime,seq,force1_n,force2_n,force_std1_n,force_std2_n,thrust_scale1,thrust_scale2,status";

std::vector<std::string> TraceLines() {
  const auto events = testing_support::RecordScenario("hover", {"scenario.duration_s=0.5"});
  EstimatorPipeline pipeline(EstimatorConfig{});  // built-in defaults, independent of config/
  std::vector<std::string> lines;
  int k = 0;
  for (const auto& e : events) {
    if (e.kind == testing_support::InputEvent::kMotor) pipeline.OnMotor(e.motor);
    if (e.kind == testing_support::InputEvent::kImu) pipeline.OnImu(e.imu);
    if (e.kind != testing_support::InputEvent::kStrain) continue;
    ForceEstimate x;
    if (!pipeline.OnStrain(e.strain, &x) || (k++ % 10) != 0) continue;
    char line[512];
    std::snprintf(line, sizeof(line), "%lld,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%d", static_cast<long long>(x.utime),
                  x.seq, x.force_n[0], x.force_n[1], x.force_std_n[0], x.force_std_n[1], x.thrust_scale[0],
                  x.thrust_scale[1], x.status);
    lines.push_back(line);
  }
  return lines;
}

std::vector<double> Fields(const std::string& line) {
  std::vector<double> out;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) out.push_back(std::stod(field));
  return out;
}

TEST(EkfRegressionTrace, MatchesTheCommittedTrace) {
  const std::vector<std::string> lines = TraceLines();
  if (std::getenv("BIROTOR_UPDATE_TRACE") != nullptr) {
    std::ofstream out(kTraceFile);
    out << kHeader << "\n";
    for (const std::string& l : lines) out << l << "\n";
    GTEST_SKIP() << "trace rewritten: " << kTraceFile;
  }
  std::ifstream in(kTraceFile);
  ASSERT_TRUE(in.good()) << "missing " << kTraceFile;
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, kHeader);
  std::vector<std::string> expected;
  for (std::string l; std::getline(in, l);) expected.push_back(l);
  ASSERT_EQ(lines.size(), expected.size());
  // Tolerance: last digits may differ between compilers and CPUs (FMA), not more.
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::vector<double> got = Fields(lines[i]), want = Fields(expected[i]);
    ASSERT_EQ(got.size(), want.size());
    for (size_t j = 0; j < got.size(); ++j) {
      EXPECT_NEAR(got[j], want[j], 1e-6 * (1.0 + std::abs(want[j]))) << "line " << i + 2 << " field " << j
                                                                      << "\n got:  " << lines[i]
                                                                      << "\n want: " << expected[i];
    }
  }
}

}  // namespace
}  // namespace birotor
