#pragma once
// A wait-free triple buffer: one writer publishes whole values at its own
// rate, one reader takes the newest whenever it likes. Neither ever waits for
// the other (the haptic thread publishes its frame for graphics and the scene
// thread this way).
#include <atomic>
#include <cstdint>

namespace millsim {

template <class T> class TripleBuffer {
public:
  // Writer: the slot to fill, then publish().
  T& back() { return slots_[back_]; }
  void publish() {
    // Hand the filled slot over as the newest and take the old middle one.
    const std::uint8_t old = middle_.exchange(std::uint8_t(back_ | kFresh), std::memory_order_acq_rel);
    back_ = old & kIndex;
  }

  // Reader: the newest published value (the same one again if nothing new).
  const T& read() {
    if (middle_.load(std::memory_order_relaxed) & kFresh) {
      const std::uint8_t old = middle_.exchange(front_, std::memory_order_acq_rel);
      front_ = old & kIndex;
    }
    return slots_[front_];
  }
  bool hasNew() const { return (middle_.load(std::memory_order_acquire) & kFresh) != 0; }

private:
  static constexpr std::uint8_t kIndex = 3, kFresh = 4;
  T slots_[3]{};
  std::uint8_t back_ = 0;   // writer's
  std::uint8_t front_ = 1;  // reader's
  alignas(64) std::atomic<std::uint8_t> middle_{2};
};

}  // namespace millsim
