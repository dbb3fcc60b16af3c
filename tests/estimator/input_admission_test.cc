// Input admission by stamp and seq (estimator/input_admission.h), without a
// method: order, duplicates, backwards jumps, seq gaps, time outliers and
// their bursts (issue 23 item 5), a real jump of every stream, a dead input at
// the jump, and conflicting publishers. Numbers from PipelineOptions'
// defaults: max_forward_jump_s 0.05, forward_jump_confirm_samples 3,
// time_backwards_reset_s 0.5, conflict 5 violations in 0.1 s, cleared after 1 s.
#include "estimator/input_admission.h"

#include <gtest/gtest.h>

namespace birotor {
namespace {

constexpr InputChannel kStrain = InputChannel::kStrain;
constexpr InputChannel kMotor = InputChannel::kMotor;
constexpr InputChannel kImu = InputChannel::kImu;

struct Inputs {
  InputAdmission admission{PipelineOptions()};
  InputCounters counters[kNumInputChannels];
  int32_t seq[kNumInputChannels] = {};
  Admission Send(InputChannel channel, int64_t utime) {
    return admission.Admit(channel, utime, ++seq[static_cast<int>(channel)], counters);
  }
  const InputCounters& operator[](InputChannel channel) const { return counters[static_cast<int>(channel)]; }
  // Strain, MOTOR and IMU at 1 kHz from t0_us for n periods, all in bounds.
  void Streams(int64_t t0_us, int n) {
    for (int k = 0; k < n; ++k) {
      for (InputChannel c : {kMotor, kImu, kStrain}) EXPECT_EQ(Send(c, t0_us + 1000 * k), Admission::kAccepted);
    }
  }
};

TEST(InputAdmissionTest, OrderDuplicatesBackwardsJumpsAndSeqGaps) {
  Inputs in;
  EXPECT_EQ(in.admission.newest_utime(), -1);
  EXPECT_EQ(in.admission.Admit(kStrain, 1000, 1, in.counters), Admission::kAccepted);
  EXPECT_EQ(in.admission.Admit(kStrain, 1000, 2, in.counters), Admission::kDuplicate);
  EXPECT_EQ(in.admission.Admit(kStrain, 900, 2, in.counters), Admission::kOutOfOrder);
  EXPECT_EQ(in.admission.Admit(kStrain, 2000, 5, in.counters), Admission::kAccepted);  // seq 2, 3, 4 missing
  EXPECT_EQ(in[kStrain].duplicates, 1);
  EXPECT_EQ(in[kStrain].out_of_order, 1);
  EXPECT_EQ(in[kStrain].gaps, 1);
  EXPECT_EQ(in[kStrain].missing_samples, 3);
  EXPECT_EQ(in[kStrain].last_utime, 2000);
  EXPECT_EQ(in[kStrain].last_seq, 5);
  EXPECT_EQ(in[kStrain].accepted_in_period, 2);
  // 0.6 s back (more than 0.5 s): a log loop, accepted and said.
  for (int k = 1; k <= 15; ++k)
    EXPECT_EQ(in.admission.Admit(kStrain, 2000 + 40000 * k, 5 + k, in.counters), Admission::kAccepted);
  EXPECT_EQ(in.admission.Admit(kStrain, 0, 1, in.counters), Admission::kAcceptedBackwardsJump);
  EXPECT_EQ(in.admission.newest_utime(), 0);
  EXPECT_EQ(in[kStrain].gaps, 1);  // no seq book-keeping across the jump
  EXPECT_EQ(in.admission.Admit(kStrain, -1, 2, in.counters), Admission::kInvalidStamp);
  EXPECT_EQ(in.admission.Admit(kStrain, InputAdmission::kMaxUtime, 2, in.counters), Admission::kInvalidStamp);
  EXPECT_EQ(in[kStrain].rejected_invalid, 2);
}

// One sample 0.4 s ahead: an outlier; it moves no clock.
TEST(InputAdmissionTest, ASampleFarAheadIsAnOutlier) {
  Inputs in;
  in.Streams(0, 100);
  EXPECT_EQ(in.Send(kStrain, 99000 + 400000), Admission::kTimeOutlier);
  EXPECT_EQ(in[kStrain].time_outliers, 1);
  EXPECT_EQ(in[kStrain].last_utime, 99000);
  EXPECT_EQ(in.admission.newest_utime(), 99000);
  in.Streams(100000, 10);
}

// Issue 23 item 5: three outliers sent 1 us apart (stamps 1 us apart, 0.4 s
// ahead) agree with each other, but MOTOR and IMU never jumped: not "every
// stream jumped". All three are outliers, no clock moves, and the honest
// strain sample after them is accepted (FORCE goes on). The same with the
// burst on all three channels in a row, where the forged MOTOR and IMU do not
// make the other live inputs jump either, and with a burst of 30 on one channel
// interleaved with honest samples.
TEST(InputAdmissionTest, ABurstOfOutliersOnOneInputIsNotAJumpOfEveryStream) {
  Inputs in;
  in.Streams(0, 100);
  const int64_t ahead = 99000 + 400000;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(in.Send(kStrain, ahead + k), Admission::kTimeOutlier) << k;
  EXPECT_EQ(in[kStrain].time_outliers, 3);
  EXPECT_EQ(in.admission.newest_utime(), 99000);
  EXPECT_EQ(in[kStrain].last_utime, 99000);
  in.Streams(100000, 10);  // every honest sample accepted
  EXPECT_EQ(in[kStrain].out_of_order, 0);

  for (int k = 0; k < 5; ++k) EXPECT_EQ(in.Send(kStrain, ahead + 20000 + k), Admission::kTimeOutlier) << k;
  for (int burst = 0; burst < 30; ++burst) {
    EXPECT_EQ(in.Send(kStrain, ahead + 30000 + burst), Admission::kTimeOutlier);
    in.Streams(110000 + 1000 * burst, 1);  // the present goes on between them
  }
  EXPECT_EQ(in[kStrain].time_outliers, 38);
  EXPECT_EQ(in[kStrain].last_utime, 139000);
}

// A sender paused on a wall clock: every stream jumps 2 s. The first sample
// of each input confirms it once all three live inputs have sent one (3
// samples in all): MOTOR and IMU are counted outliers, STRAIN is accepted.
TEST(InputAdmissionTest, AJumpOfEveryLiveStreamIsAccepted) {
  Inputs in;
  in.Streams(0, 100);
  const int64_t jump = 99000 + 2000000;
  EXPECT_EQ(in.Send(kMotor, jump), Admission::kTimeOutlier);
  EXPECT_EQ(in.Send(kImu, jump), Admission::kTimeOutlier);
  EXPECT_EQ(in.Send(kStrain, jump), Admission::kAccepted);
  EXPECT_EQ(in.admission.newest_utime(), jump);
  EXPECT_EQ(in[kMotor].time_outliers + in[kImu].time_outliers + in[kStrain].time_outliers, 2);
  in.Streams(jump + 1000, 10);
}

// An input that was live dies at the jump: the others confirm it alone after
// 10 x forward_jump_confirm_samples = 30 agreeing outliers in a row (29
// counted), so the estimator does not drop every sample for ever.
TEST(InputAdmissionTest, AJumpIsAcceptedWhenALiveInputDiedAtIt) {
  Inputs in;
  in.Streams(0, 100);
  const int64_t jump = 99000 + 2000000;
  int outliers = 0;
  Admission last = Admission::kTimeOutlier;
  for (int k = 0; k < 15 && last == Admission::kTimeOutlier; ++k) {
    for (InputChannel c : {kImu, kStrain}) {
      last = in.Send(c, jump + 1000 * k);
      if (last != Admission::kTimeOutlier) break;
      ++outliers;
    }
  }
  EXPECT_EQ(outliers, 29);
  EXPECT_TRUE(IsAccepted(last));
  EXPECT_EQ(in.admission.newest_utime(), jump + 14000);
}

// Five order violations within 0.1 s raise the conflict; it clears after 1 s
// of stream time without one. POSE conflicts are counted, not flagged.
TEST(InputAdmissionTest, ConflictingPublishersAreFlaggedAndClear) {
  Inputs in;
  in.Streams(0, 10);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(in.Send(kImu, 5000), Admission::kOutOfOrder);
    EXPECT_FALSE(in[kImu].conflict_active);
  }
  EXPECT_EQ(in.Send(kImu, 5000), Admission::kOutOfOrder);
  EXPECT_TRUE(in[kImu].conflict_active);
  EXPECT_EQ(in[kImu].conflicts, 1);
  EXPECT_TRUE(InputAdmission::AnyConflictActive(in.counters));
  in.Streams(10000, 1100);  // 1.1 s of clean input
  EXPECT_FALSE(in[kImu].conflict_active);
  EXPECT_FALSE(InputAdmission::AnyConflictActive(in.counters));
  for (int k = 0; k < 6; ++k) in.admission.Admit(InputChannel::kPose, 0, 0, in.counters);  // 5 duplicates
  EXPECT_TRUE(in[InputChannel::kPose].conflict_active);
  EXPECT_FALSE(InputAdmission::AnyConflictActive(in.counters));
}

}  // namespace
}  // namespace birotor
