#include "millsim/run/RendererSwitch.h"

#include <algorithm>

namespace millsim {

void RendererSwitch::replace(std::unique_ptr<HapticAlgorithm> next, const Pose& device) {
  next->reset(device);
  next->carryOver(*current_);
  // A switch during a fade drops the oldest; the blend restarts from the one in charge.
  retired_ = std::move(previous_);
  previous_ = std::move(current_);
  current_ = std::move(next);
  elapsed_ = 0.0;
}

HapticOutput RendererSwitch::step(HapticScene& scene, const HapticInput& in) {
  HapticOutput out = current_->step(scene, in);
  if (!previous_) return out;
  elapsed_ += in.dt;
  const HapticOutput old = previous_->step(scene, in);
  const double w = fadeTime_ > 0.0 ? std::clamp(elapsed_ / fadeTime_, 0.0, 1.0) : 1.0;
  out.force = old.force + (out.force - old.force) * w;
  out.torque = old.torque + (out.torque - old.torque) * w;
  if (w >= 1.0) retired_ = std::move(previous_);
  return out;
}

}  // namespace millsim
