#pragma once
// The summary statistics the accuracy suites report: RMS and percentiles of a
// sample (NaN for an empty one).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace millsim::measure {

// The q-quantile (0 ≤ q ≤ 1) by the nearest rank below.
inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

inline double rms(const std::vector<double>& v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / double(v.size()));
}

}  // namespace millsim::measure
