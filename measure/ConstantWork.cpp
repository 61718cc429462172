#include "measure/ConstantWork.h"

#include <algorithm>
#include <cmath>

#include "millsim/run/ThreadCpuTime.h"

namespace millsim::measure {

namespace {

// A dependent chain of multiply-adds the compiler cannot fold or vectorise.
double work(long iterations, double seed) {
  volatile double sink = seed;
  double s = sink;
  for (long i = 0; i < iterations; ++i) s = s * 1.0000001 + 1e-9;
  sink = s;
  return sink;
}

}  // namespace

FrameTimes FrameTimes::of(std::vector<double> us) {
  FrameTimes t;
  if (us.empty()) return t;
  std::sort(us.begin(), us.end());
  auto at = [&](double q) { return us[std::min(us.size() - 1, std::size_t(q * double(us.size())))]; };
  t.p50 = at(0.5), t.p99 = at(0.99), t.p999 = at(0.999), t.max = us.back();
  return t;
}

FrameTimes timeConstantWork(double us, long frames) {
  // Calibrate on the median of short trials, so a tick in one trial does not skew it.
  constexpr long kTrial = 20000;
  std::vector<double> trial;
  for (int i = 0; i < 21; ++i) {
    const double c0 = threadCpuMicros();
    work(kTrial, 1.0);
    trial.push_back(threadCpuMicros() - c0);
  }
  const double perIteration = std::max(1e-6, FrameTimes::of(trial).p50 / double(kTrial));
  const long iterations = std::max(1L, std::lround(std::max(0.0, us) / perIteration));
  std::vector<double> times(std::size_t(std::max(1L, frames)));
  for (double& t : times) {
    const double c0 = threadCpuMicros();
    work(iterations, 1.0);
    t = threadCpuMicros() - c0;
  }
  return FrameTimes::of(std::move(times));
}

}  // namespace millsim::measure
