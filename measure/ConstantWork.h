#pragma once
// A control for frame-time tails. A frame of fixed arithmetic, calibrated to
// last a given CPU time, is timed like a renderer's frame. Whatever its p99
// adds to its p50 comes from the machine, not the code: the kernel's 1 kHz
// tick and other interrupts are charged to the running thread's CPU clock,
// and a host's steal and preemption to its wall clock. A renderer's tail
// beyond the control's at the same length is its own.
#include <vector>

namespace millsim::measure {

struct FrameTimes {
  double p50 = 0, p99 = 0, p999 = 0, max = 0;  // µs
  static FrameTimes of(std::vector<double> us);
};

// Calibrates a loop to about `us` of the thread's CPU time, then times it
// `frames` times by that clock.
FrameTimes timeConstantWork(double us, long frames);

}  // namespace millsim::measure
