#pragma once
// A fixed-capacity single-producer/single-consumer ring of trivially copyable
// records: the haptic thread pushes (never waits, never allocates; a full ring
// drops the record and counts it), another thread drains.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace millsim {

template <class T> class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "records are copied between threads byte for byte");

public:
  explicit SpscRing(std::size_t capacity) : slots_(capacity + 1) {}

  // Producer. False (and counted) when the consumer has fallen behind.
  bool push(const T& value) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    const std::size_t next = head + 1 == slots_.size() ? 0 : head + 1;
    if (next == tail_.load(std::memory_order_acquire)) {
      dropped_.fetch_add(1, std::memory_order_relaxed);
      return false;
    }
    slots_[head] = value;
    head_.store(next, std::memory_order_release);
    return true;
  }

  // Consumer: calls f(const T&) for every record pushed so far; returns how many.
  template <class F> std::size_t drain(F&& f) {
    std::size_t n = 0, tail = tail_.load(std::memory_order_relaxed);
    const std::size_t head = head_.load(std::memory_order_acquire);
    while (tail != head) {
      f(slots_[tail]);
      tail = tail + 1 == slots_.size() ? 0 : tail + 1;
      ++n;
    }
    tail_.store(tail, std::memory_order_release);
    return n;
  }

  std::size_t capacity() const { return slots_.size() - 1; }
  std::uint64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }

private:
  std::vector<T> slots_;
  alignas(64) std::atomic<std::size_t> head_{0};
  alignas(64) std::atomic<std::size_t> tail_{0};
  alignas(64) std::atomic<std::uint64_t> dropped_{0};
};

}  // namespace millsim
