// EstimatorPipeline on bad input: NaN, out-of-order, duplicate, seq gaps and
// wrap, a backwards time jump, a 2 s gap, missing and stale motor input. Each
// is counted and flagged, the output stays finite, and the filter recovers.
#include "estimator/estimator_pipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

#include "tests/estimator/scenario_harness.h"

namespace birotor {
namespace {

using testing_support::InputEvent;
using testing_support::ReferenceConfig;

const std::vector<InputEvent>& HoverEvents() {
  static const std::vector<InputEvent> events =
      testing_support::RecordScenario("hover", {"scenario.duration_s=2", "sensors.pose.enabled=false"});
  return events;
}

int Index(InputChannel channel) { return static_cast<int>(channel); }

bool Finite(const ForceEstimate& e) {
  return std::isfinite(e.force_n[0]) && std::isfinite(e.force_n[1]) && std::isfinite(e.force_std_n[0]) &&
         std::isfinite(e.force_std_n[1]) && std::isfinite(e.thrust_scale[0]) && std::isfinite(e.thrust_scale[1]);
}

// Feeds recorded events; `edit` may change a strain sample (return false to drop it).
struct Feeder {
  explicit Feeder(const EstimatorConfig& config = ReferenceConfig("ekf")) : pipeline(config) {}
  void Feed(const std::vector<InputEvent>& events, int64_t utime_shift_us,
            const std::function<bool(StrainSample*)>& edit = nullptr, bool motor = true) {
    for (const InputEvent& e : events) {
      switch (e.kind) {
        case InputEvent::kMotor: {
          if (!motor) break;
          MotorSample m = e.motor;
          m.utime += utime_shift_us;
          pipeline.OnMotor(m);
          break;
        }
        case InputEvent::kImu: {
          ImuSample i = e.imu;
          i.utime += utime_shift_us;
          pipeline.OnImu(i);
          break;
        }
        case InputEvent::kStrain: {
          StrainSample s = e.strain;
          s.utime += utime_shift_us;
          if (edit && !edit(&s)) break;
          ForceEstimate estimate;
          if (pipeline.OnStrain(s, &estimate)) {
            ++published;
            all_finite = all_finite && Finite(estimate);
            last = estimate;
            statuses |= estimate.status;
          }
          break;
        }
        case InputEvent::kTruth:
          truth = e.truth;
          break;
      }
    }
  }
  const InputCounters& strain() const { return pipeline.health().inputs[Index(InputChannel::kStrain)]; }
  EstimatorPipeline pipeline;
  ForceEstimate last;
  TruthSample truth;
  int64_t published = 0;
  int32_t statuses = 0;
  bool all_finite = true;
};

// Finite throughout, valid at the end and near the truth (tolerance: about
// five sigma of the method's single-sample error) [N].
void ExpectRecovered(const Feeder& f, double tolerance_n = 0.5) {
  EXPECT_TRUE(f.all_finite);
  EXPECT_TRUE(f.last.status & kStatusValid);
  EXPECT_NEAR(f.last.force_n[0], f.truth.force_n[0], tolerance_n);
  EXPECT_NEAR(f.last.force_n[1], f.truth.force_n[1], tolerance_n);
}

TEST(EstimatorPipelineTest, CleanRunPublishesEverySample) {
  Feeder f;
  f.Feed(HoverEvents(), 0);
  EXPECT_EQ(f.published, 2000);
  EXPECT_EQ(f.strain().fused, 2000);
  EXPECT_EQ(f.strain().gaps, 0);
  EXPECT_EQ(f.pipeline.health().resets, 1);
  EXPECT_EQ(f.pipeline.health().last_reset_reason, "start");
  EXPECT_EQ(f.pipeline.health().inputs[Index(InputChannel::kMotor)].fused, 1000);
  EXPECT_EQ(f.statuses & kStatusInputStale, 0);
  EXPECT_EQ(f.last.status & kStatusNoMotorInput, 0);
  EXPECT_STREQ(f.pipeline.method_name(), "ekf");
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, FirstEstimateIsFlaggedAsReset) {
  EstimatorPipeline pipeline(ReferenceConfig("ekf"));
  StrainSample s;
  s.deflection_rad[0] = -0.0018;
  s.deflection_rad[1] = 0.0018;
  ForceEstimate e;
  ASSERT_TRUE(pipeline.OnStrain(s, &e));
  EXPECT_TRUE(e.status & kStatusFilterReset);
  EXPECT_TRUE(e.status & kStatusNoMotorInput);
  EXPECT_TRUE(e.status & kStatusConverging);
  EXPECT_FALSE(e.status & kStatusValid);
  EXPECT_TRUE(Finite(e));
}

TEST(EstimatorPipelineTest, NanAndOutOfRangeSamplesAreCountedAndDropped) {
  Feeder f;
  int k = 0;
  f.Feed(HoverEvents(), 0, [&](StrainSample* s) {
    ++k;
    if (k == 500) s->deflection_rad[0] = std::nan("");
    if (k == 600) s->deflection_rad[1] = std::numeric_limits<double>::infinity();
    if (k == 700) s->deflection_rad[1] = 0.5;  // beyond max_deflection_rad
    return true;
  });
  EXPECT_EQ(f.strain().rejected_invalid, 3);
  EXPECT_EQ(f.published, 1997);
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, OutOfOrderAndDuplicateSamplesAreCountedAndDropped) {
  Feeder f;
  StrainSample held;
  int k = 0;
  int rejected = 0;
  f.Feed(HoverEvents(), 0, [&](StrainSample* s) {
    ForceEstimate e;
    ++k;
    if (k == 400) {
      held = *s;  // delivered after the next one
      return false;
    }
    if (k == 401) {
      EXPECT_TRUE(f.pipeline.OnStrain(*s, &e));
      if (!f.pipeline.OnStrain(held, &e)) ++rejected;
      return false;
    }
    if (k == 800) {
      EXPECT_TRUE(f.pipeline.OnStrain(*s, &e));
      if (!f.pipeline.OnStrain(*s, &e)) ++rejected;  // duplicate
      return false;
    }
    return true;
  });
  EXPECT_EQ(rejected, 2);
  EXPECT_EQ(f.strain().out_of_order, 1);
  EXPECT_EQ(f.strain().duplicates, 1);
  EXPECT_EQ(f.strain().gaps, 1);  // seq 399 was missing when 400 came first
  EXPECT_EQ(f.strain().missing_samples, 1);
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, SeqGapsAreCountedAndWrapIsNot) {
  Feeder f;
  int k = 0;
  f.Feed(HoverEvents(), 0, [&](StrainSample* s) {
    ++k;
    // Start near INT32_MAX so seq wraps; drop 5 samples at k = 1000.
    s->seq = static_cast<int32_t>(static_cast<uint32_t>(std::numeric_limits<int32_t>::max()) - 100u +
                                  static_cast<uint32_t>(s->seq));
    return k < 1000 || k > 1005;
  });
  EXPECT_EQ(f.strain().gaps, 1);
  EXPECT_EQ(f.strain().missing_samples, 6);
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, TimeJumpBackwardsResetsAndRecovers) {
  Feeder f;
  f.Feed(HoverEvents(), 0);
  const int64_t published = f.published;
  // The same log again from t = 0: a loop in a log player.
  f.Feed(HoverEvents(), 0);
  EXPECT_EQ(f.published, 2 * published);
  EXPECT_EQ(f.pipeline.health().resets, 2);
  EXPECT_EQ(f.pipeline.health().last_reset_reason, "time_backwards");
  EXPECT_EQ(f.strain().out_of_order, 0);
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, LongGapResetsAndRecovers) {
  Feeder f;
  const auto& events = HoverEvents();
  const std::vector<InputEvent> first(events.begin(), events.begin() + events.size() / 2);
  const std::vector<InputEvent> second(events.begin() + events.size() / 2, events.end());
  f.Feed(first, 0);
  ForceEstimate after_gap;
  bool captured = false;
  f.Feed(second, 2000000, [&](StrainSample* s) {
    if (!captured) {
      // Look at the first estimate after the gap.
      captured = true;
      EXPECT_TRUE(f.pipeline.OnStrain(*s, &after_gap));
      return false;
    }
    return true;
  });
  EXPECT_TRUE(after_gap.status & kStatusFilterReset);
  EXPECT_TRUE(Finite(after_gap));
  EXPECT_EQ(f.pipeline.health().resets, 2);
  EXPECT_EQ(f.pipeline.health().last_reset_reason, "gap");
  EXPECT_EQ(f.strain().gaps, 0);  // seq continued: only time jumped
  // Truth utime is not shifted, compare values only.
  ExpectRecovered(f);
}

TEST(EstimatorPipelineTest, MissingMotorInputIsFlagged) {
  Feeder f;
  f.Feed(HoverEvents(), 0, nullptr, /*motor=*/false);
  EXPECT_TRUE(f.last.status & kStatusNoMotorInput);
  EXPECT_TRUE(f.all_finite);
}

TEST(EstimatorPipelineTest, StaleMotorInputIsFlagged) {
  Feeder f;
  const auto& events = HoverEvents();
  std::vector<InputEvent> cut;
  for (const InputEvent& e : events) {
    if (e.kind == InputEvent::kMotor && e.utime() > 1000000) continue;
    cut.push_back(e);
  }
  f.Feed(cut, 0);
  EXPECT_TRUE(f.last.status & kStatusInputStale);
  EXPECT_FALSE(f.last.status & kStatusNoMotorInput);
  EXPECT_TRUE(f.all_finite);
}

TEST(EstimatorPipelineTest, BadMotorAndImuSamplesAreCounted) {
  EstimatorPipeline pipeline(ReferenceConfig("ekf"));
  MotorSample m;
  m.omega_cmd_rad_s[0] = std::nan("");
  pipeline.OnMotor(m);
  ImuSample i;
  i.gyro_y_rad_s = std::numeric_limits<double>::infinity();
  pipeline.OnImu(i);
  PoseSample p;
  p.x_m = std::nan("");
  pipeline.OnPose(p);
  pipeline.CountDecodeError(InputChannel::kStrain);
  pipeline.CountReceived(InputChannel::kStrain);
  pipeline.CountOverloadDrop(InputChannel::kMotor);
  const PipelineHealth& h = pipeline.health();
  EXPECT_EQ(h.inputs[Index(InputChannel::kMotor)].rejected_invalid, 1);
  EXPECT_EQ(h.inputs[Index(InputChannel::kImu)].rejected_invalid, 1);
  EXPECT_EQ(h.inputs[Index(InputChannel::kPose)].rejected_invalid, 1);
  EXPECT_EQ(h.inputs[Index(InputChannel::kStrain)].decode_errors, 1);
  EXPECT_EQ(h.inputs[Index(InputChannel::kStrain)].received, 1);
  EXPECT_EQ(h.inputs[Index(InputChannel::kMotor)].dropped_overload, 1);
  EXPECT_STREQ(InputChannelName(InputChannel::kImu), "IMU");
}

TEST(EstimatorPipelineTest, EveryMethodRunsBehindTheSameInterface) {
  for (const std::string& method : EstimationMethodNames()) {
    Feeder f(ReferenceConfig(method));
    f.Feed(HoverEvents(), 0);
    EXPECT_EQ(f.pipeline.method_name(), method);
    ExpectRecovered(f, 2.0);
  }
  EstimatorConfig bad = ReferenceConfig("ekf");
  bad.method = "kalman";
  EXPECT_THROW(EstimatorPipeline pipeline(bad), std::invalid_argument);
  EXPECT_EQ(MakeForceEstimator(bad), nullptr);
}

TEST(EstimatorPipelineTest, PeriodStatisticsAreCleared) {
  Feeder f;
  f.Feed(HoverEvents(), 0);
  EXPECT_GT(f.pipeline.health().nis_count, 0);
  EXPECT_GT(f.pipeline.health().inputs[Index(InputChannel::kStrain)].accepted_in_period, 0);
  f.pipeline.TakePeriod();
  EXPECT_EQ(f.pipeline.health().nis_count, 0);
  EXPECT_EQ(f.pipeline.health().inputs[Index(InputChannel::kStrain)].accepted_in_period, 0);
}

}  // namespace
}  // namespace birotor
