#pragma once
// HudFeed: the window's HUD numbers, kept by the scene thread from every frame
// record it drains — the haptic rate and compute time over the last second
// (p50, p99), and the newest frame's force, torque, contacts and milling.
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "millsim/run/HapticLoop.h"
#include "millsim/window/AppWindow.h"

namespace millsim {

class HudFeed {
public:
  explicit HudFeed(double rate) : compute_(std::size_t(std::max(rate, 1.0)) + 1, 0.0) {}
  void add(const FrameRecord& r);
  // The HUD for the frames so far; `status` is the latest notice.
  HudState state(const std::string& status) const;

private:
  std::vector<double> compute_;  // the last second's compute times (µs), a ring
  mutable std::vector<double> times_;  // scratch for percentiles (scene thread only)
  std::size_t next_ = 0, filled_ = 0;
  FrameRecord last_;
  std::vector<double> starts_;   // t of each ring entry
};

}  // namespace millsim
