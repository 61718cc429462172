#pragma once
// The calling thread's CPU time in µs (CLOCK_THREAD_CPUTIME_ID). Frame times
// are judged by it next to the wall clock: on a loaded 2-core machine
// wall-time percentiles measure the scheduler (ticks, preemption, a host's
// steal), and the difference between the two says which frames lost the CPU.
// One read costs about 0.6 µs on this project's VM (a system call: the vDSO
// has no thread clocks).
#include <time.h>

namespace millsim {

inline double threadCpuMicros() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e6 + double(ts.tv_nsec) * 1e-3;
}

}  // namespace millsim
