#pragma once
// FrameHistogram: frame periods or compute times in 1 µs bins up to 50 ms
// (longer ones land in the last bin; the exact maximum is kept). Sized once,
// so the haptic thread can add to it every frame without allocating, and
// percentiles of a run of any length cost no per-frame storage.
#include <cstdint>
#include <vector>

namespace millsim {

class FrameHistogram {
public:
  static constexpr int kBins = 50000;  // 1 µs each

  FrameHistogram() : bins_(kBins, 0) {}
  void add(double us);
  std::uint64_t count() const { return count_; }
  double mean() const { return count_ ? sum_ / double(count_) : 0.0; }
  double max() const { return max_; }
  // The value below which a fraction p (0…1) of the samples lie, to the bin (µs).
  double percentile(double p) const;
  // Samples strictly above `us`.
  std::uint64_t countAbove(double us) const;

private:
  std::vector<std::uint64_t> bins_;
  std::uint64_t count_ = 0;
  double sum_ = 0.0, max_ = 0.0;
};

}  // namespace millsim
