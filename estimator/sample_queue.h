// A fixed-capacity FIFO of samples (no allocation after construction), for
// measurements that wait until the filter is predicted to their time stamp.
#pragma once

#include <array>

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

}  // namespace birotor
