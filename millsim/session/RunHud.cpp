#include "millsim/session/RunHud.h"

#include <algorithm>

#include <glm/geometric.hpp>

#include "millsim/core/FieldValues.h"

namespace millsim {

void HudFeed::add(const FrameRecord& r) {
  if (starts_.size() != compute_.size()) starts_.assign(compute_.size(), 0.0);
  compute_[next_] = r.computeUs;
  starts_[next_] = r.t;
  next_ = (next_ + 1) % compute_.size();
  filled_ = std::min(filled_ + 1, compute_.size());
  last_ = r;
}

HudState HudFeed::state(const std::string& status) const {
  HudState h;
  h.status = status;
  h.renderer = last_.renderer;
  h.burr = std::string(burrShapeName(last_.tool.shape)) + " " + formatNumber(float(last_.tool.tipRadius * 1e3)) + " mm";
  h.force = glm::length(last_.force);
  h.torque = glm::length(last_.torque);
  h.torqueNotOutput = (last_.out.flags & kSafetyTorqueNotOutput) != 0;
  h.contacts = last_.out.contacts;
  h.removedMm3 = last_.removedVolume * 1e9;
  h.milling = last_.button;
  if (filled_ < 2) return h;
  const std::size_t oldest = filled_ < compute_.size() ? 0 : next_;
  const double span = last_.t - starts_[oldest];
  if (span > 0.0) h.hapticRate = double(filled_ - 1) / span;
  auto& times = times_;
  times.assign(compute_.begin(), compute_.begin() + std::ptrdiff_t(filled_));
  auto at = [&](double q) {
    auto it = times.begin() + std::ptrdiff_t(q * double(times.size() - 1));
    std::nth_element(times.begin(), it, times.end());
    return *it;
  };
  h.computeP50Us = at(0.5);
  h.computeP99Us = at(0.99);
  return h;
}

}  // namespace millsim
