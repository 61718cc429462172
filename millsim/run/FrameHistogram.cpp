#include "millsim/run/FrameHistogram.h"

#include <algorithm>
#include <cmath>

namespace millsim {

void FrameHistogram::add(double us) {
  if (!std::isfinite(us) || us < 0.0) us = 0.0;
  bins_[std::size_t(std::min(us, double(kBins - 1)))] += 1;
  ++count_;
  sum_ += us;
  max_ = std::max(max_, us);
}

double FrameHistogram::percentile(double p) const {
  if (count_ == 0) return 0.0;
  const auto rank = std::uint64_t(std::ceil(std::clamp(p, 0.0, 1.0) * double(count_)));
  std::uint64_t seen = 0;
  for (int i = 0; i < kBins; ++i) {
    seen += bins_[std::size_t(i)];
    // The bin's upper edge, so a percentile never reads low.
    if (seen >= std::max<std::uint64_t>(rank, 1)) return std::min(double(i + 1), max_);
  }
  return max_;
}

std::uint64_t FrameHistogram::countAbove(double us) const {
  std::uint64_t n = 0;
  for (int i = std::max(0, int(std::floor(us)) + 1); i < kBins; ++i) n += bins_[std::size_t(i)];
  return n;
}

}  // namespace millsim
