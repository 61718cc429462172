#pragma once
// The calling thread's CPU time in µs. Benchmarks time frames by it because on
// a loaded 2-core machine wall-time percentiles measure the scheduler (4 ms
// ticks, preemption), not the frame.
#include <time.h>

namespace millsim::bench {

inline double threadCpuMicros() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e6 + double(ts.tv_nsec) * 1e-3;
}

}  // namespace millsim::bench
