// A fixed-capacity FIFO of samples (no allocation after construction), for
// measurements that wait until the filter is predicted to their time stamp,
// and the time-ordered drain of the MOTOR and IMU queues.
#pragma once

#include <array>
#include <cstdint>

namespace birotor {

template <typename Sample, int kCapacity>
class SampleQueue {
 public:
  bool empty() const { return size_ == 0; }
  int size() const { return size_; }
  // The oldest sample; only when !empty().
  const Sample& front() const { return items_[head_]; }
  void pop() {
    head_ = (head_ + 1) % kCapacity;
    --size_;
  }
  // Appends sample. When the queue is full the oldest sample is removed first
  // and copied to *dropped; returns true then.
  bool push(const Sample& sample, Sample* dropped) {
    bool full = size_ == kCapacity;
    if (full) {
      *dropped = items_[head_];
      pop();
    }
    items_[(head_ + size_) % kCapacity] = sample;
    ++size_;
    return full;
  }

 private:
  std::array<Sample, kCapacity> items_{};
  int head_ = 0;
  int size_ = 0;
};

// Hands every sample of both queues stamped at or before utime [us] to its
// apply function in time order, motor first on equal stamps (what the EKFs do
// before predicting to a strain sample).
template <typename MotorQueue, typename ImuQueue, typename ApplyMotor, typename ApplyImu>
void DrainInTimeOrder(int64_t utime, MotorQueue* motor_queue, ImuQueue* imu_queue, ApplyMotor&& apply_motor,
                      ApplyImu&& apply_imu) {
  while (true) {
    const bool motor_due = !motor_queue->empty() && motor_queue->front().utime <= utime;
    const bool imu_due = !imu_queue->empty() && imu_queue->front().utime <= utime;
    if (!motor_due && !imu_due) return;
    if (motor_due && (!imu_due || motor_queue->front().utime <= imu_queue->front().utime)) {
      const auto sample = motor_queue->front();
      motor_queue->pop();
      apply_motor(sample);
    } else {
      const auto sample = imu_queue->front();
      imu_queue->pop();
      apply_imu(sample);
    }
  }
}

}  // namespace birotor
