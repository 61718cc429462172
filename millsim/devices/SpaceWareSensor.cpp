#include "millsim/devices/SpaceWareSensor.h"

#include <algorithm>

#include <glm/gtc/quaternion.hpp>

#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/SpaceNav.h"

namespace millsim {

namespace {
Rotation rotationOf(const glm::vec3& v, float scale) {
  const float size = glm::length(v);
  if (!(size > 0.f)) return Rotation{};
  return Rotation{v / size, size * scale};
}
}  // namespace

const NodeType& SpaceWareSensor::type() {
  static const NodeType t = makeNodeType<SpaceWareSensor>(
      "SpaceWareSensor", "children", "MillSim devices",
      "H3DAPI's 3D mouse sensor: a 3Dconnexion puck's push, twist and buttons as events (spacenavd and libspnav).");
  return t;
}

bool SpaceWareSensor::hasPendingEvent() const {
  if (!enabled.get()) return isActive.get();  // to say it stopped
  if (!nav_) return Clock::now() >= nextTry_;
  if (!nav_->connected()) return true;
  const SpaceNavState s = nav_->state();
  const SpaceNavDeflection d = toSceneFrame(s, 0.0);
  const bool still = std::all_of(d.translation, d.translation + 3, [](double v) { return v == 0.0; }) &&
                     std::all_of(d.rotation, d.rotation + 3, [](double v) { return v == 0.0; });
  return s.events != seenEvents_ || !still;  // a held push keeps accumulating
}

bool SpaceWareSensor::processEvents() {
  const Clock::time_point now = Clock::now();
  if (!enabled.get()) {
    nav_.reset();
    if (!isActive.get()) return false;
    isActive.set(false);
    return true;
  }
  if (!nav_) {
    try {
      nav_ = SpaceNav::open();
    } catch (const DeviceError&) {
      nextTry_ = now + std::chrono::seconds(1);  // spacenavd may come up later
      return false;
    }
    isActive.set(true);
    lastUpdate_ = now;
    return true;
  }
  if (!nav_->connected()) {
    nav_.reset();
    nextTry_ = now + std::chrono::seconds(1);
    isActive.set(false);
    return true;
  }
  const SpaceNavState s = nav_->state();
  const SpaceNavDeflection d = toSceneFrame(s, 0.0);
  const glm::vec3 push(float(d.translation[0]), float(d.translation[1]), float(d.translation[2]));
  const glm::vec3 twist(float(d.rotation[0]), float(d.rotation[1]), float(d.rotation[2]));
  rawTranslation.set(push);
  rawRotation.set(rotationOf(twist, 1.f));
  const glm::vec3 instant = push * translationScale.get();
  const Rotation turn = rotationOf(twist, rotationScale.get());
  instantTranslation.set(instant);
  instantRotation.set(turn);
  // Per second of the scene's clock, at most a tenth of one per tick (a stalled scene thread jumps no further).
  const float step = accumulateTimeDependent.get()
                         ? float(std::min(std::chrono::duration<double>(now - lastUpdate_).count(), 0.1))
                         : 1.f;
  lastUpdate_ = now;
  accumulatedTranslation.set(accumulatedTranslation.get() + instant * step);
  accumulated_ = glm::normalize(glm::angleAxis(turn.angle * step, turn.axis) * accumulated_);
  const float angle = 2.f * std::acos(std::clamp(accumulated_.w, -1.f, 1.f));
  const glm::vec3 axis = angle > 1e-6f ? glm::normalize(glm::vec3(accumulated_.x, accumulated_.y, accumulated_.z))
                                       : glm::vec3(0.f, 0.f, 1.f);
  accumulatedRotation.set(Rotation{axis, angle});
  if (int(s.buttons) != buttons.get()) buttons.set(int(s.buttons));
  if (s.latestPress != seenPress_ && s.latestPress >= 0) latestButtonPress.set(s.latestPress);
  if (s.latestRelease != seenRelease_ && s.latestRelease >= 0) latestButtonRelease.set(s.latestRelease);
  seenPress_ = s.latestPress, seenRelease_ = s.latestRelease;
  seenEvents_ = s.events;
  return true;
}

}  // namespace millsim
