#pragma once
// Swapping the haptics renderer while the loop runs. A new algorithm takes over
// between frames; for `fadeTime` seconds both run and the output blends
// linearly from the old one's to the new one's, so the hand feels no jolt.
// The drawn tool switches at once (graphics can jump; the hand must not).
#include <memory>

#include "millsim/haptics/HapticsRenderer.h"

namespace millsim {

class RendererSwitch {
public:
  static constexpr double kDefaultFadeTime = 0.1;  // s: 100 frames at 1 kHz

  explicit RendererSwitch(std::unique_ptr<HapticAlgorithm> initial, double fadeTime = kDefaultFadeTime)
      : current_(std::move(initial)), fadeTime_(fadeTime) {}

  // Takes effect at the next step; the new algorithm starts from `device`.
  // (Allocation and the algorithm's construction happen on the caller's thread.)
  void replace(std::unique_ptr<HapticAlgorithm> next, const Pose& device);
  HapticOutput step(HapticScene& scene, const HapticInput& in);

  bool fading() const { return previous_ != nullptr; }
  HapticAlgorithm& current() { return *current_; }
  // The algorithm that finished fading out, for the caller to free off the haptic thread.
  std::unique_ptr<HapticAlgorithm> takeRetired() { return std::move(retired_); }

private:
  std::unique_ptr<HapticAlgorithm> current_, previous_, retired_;
  double fadeTime_;
  double elapsed_ = 0.0;
};

}  // namespace millsim
