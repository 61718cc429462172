#pragma once
// Frame-time statistics for the bench and for `millsim run`'s report: record
// one duration per frame, read the mean and the 95th percentile. Header-only.
#include <algorithm>
#include <chrono>
#include <vector>

namespace millsim {

class FrameTimer {
public:
  using Clock = std::chrono::steady_clock;

  void start() { begin_ = Clock::now(); }
  void stop() { add(std::chrono::duration<double>(Clock::now() - begin_).count()); }
  void add(double seconds) { samples_.push_back(seconds); }
  void clear() { samples_.clear(); }

  std::size_t count() const { return samples_.size(); }
  double mean() const {
    double sum = 0.0;
    for (double s : samples_) sum += s;
    return samples_.empty() ? 0.0 : sum / double(samples_.size());
  }
  // Nearest-rank percentile, q in [0, 1].
  double percentile(double q) const {
    if (samples_.empty()) return 0.0;
    std::vector<double> sorted = samples_;
    std::sort(sorted.begin(), sorted.end());
    const auto rank = std::size_t(std::clamp(q, 0.0, 1.0) * double(sorted.size() - 1) + 0.5);
    return sorted[rank];
  }
  double p95() const { return percentile(0.95); }

private:
  Clock::time_point begin_;
  std::vector<double> samples_;
};

}  // namespace millsim
