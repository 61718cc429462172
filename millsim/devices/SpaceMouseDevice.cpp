#include "millsim/devices/SpaceMouseDevice.h"

#include <cmath>

#include <glm/gtc/quaternion.hpp>

#include "millsim/driver/SpaceNav.h"

namespace millsim {

namespace {

// The puck as a rate control, integrated on the haptic thread from the
// newest state the SpaceNav reader published (no socket I/O here).
class SpaceMouseDriver final : public DeviceDriver {
public:
  struct Params {
    Pose start;
    double translationSpeed = 0.005, rotationSpeed = 1.0, deadZone = 0.05;
  };
  SpaceMouseDriver(std::shared_ptr<SpaceNav> nav, const Params& p) : nav_(std::move(nav)), p_(p), pose_(p.start) {}

  DeviceReading read(double, double dt) override {
    if (!nav_->connected()) return DeviceReading{pose_, false, false};
    const SpaceNavState s = nav_->state();
    const SpaceNavDeflection d = toSceneFrame(s, p_.deadZone);
    const glm::dvec3 v(d.translation[0], d.translation[1], d.translation[2]);
    const glm::dvec3 w(d.rotation[0], d.rotation[1], d.rotation[2]);
    pose_.position += v * (p_.translationSpeed * dt);
    const double angle = glm::length(w) * p_.rotationSpeed * dt;
    if (angle > 0.0) pose_.orientation = glm::normalize(glm::angleAxis(angle, glm::normalize(w)) * pose_.orientation);
    return DeviceReading{pose_, (s.buttons & 1u) != 0, true};
  }
  void write(const glm::dvec3&, const glm::dvec3&) override {}  // no force output
  bool failed() const override { return !nav_->connected(); }
  std::string failure() const override { return nav_->failure(); }

private:
  std::shared_ptr<SpaceNav> nav_;
  Params p_;
  Pose pose_;
};

}  // namespace

const NodeType& SpaceMouseDevice::type() {
  static const NodeType t = makeNodeType<SpaceMouseDevice>(
      "SpaceMouseDevice", "children", "MillSim devices",
      "A 3Dconnexion 3D mouse moving the burr (spacenavd and libspnav): 6-DOF in, no force out.");
  return t;
}

std::unique_ptr<DeviceDriver> SpaceMouseDevice::openDriver(const DriverOptions&) const {
  std::shared_ptr<SpaceNav> nav = SpaceNav::open();
  model_ = nav->deviceName();
  opened_ = true;
  SpaceMouseDriver::Params p;
  p.start.position = glm::dvec3(position.get());
  p.start.orientation = glm::dquat(orientation.get().quat());
  p.translationSpeed = translationSpeed.get();
  p.rotationSpeed = rotationSpeed.get();
  p.deadZone = deadZone.get();
  return std::make_unique<SpaceMouseDriver>(std::move(nav), p);
}

std::string SpaceMouseDevice::noteOpened() {
  if (!opened_) return {};
  deviceModel.set(model_);
  return "SpaceMouseDevice: reading " + (model_.empty() ? std::string("the 3D mouse") : model_) +
         " through spacenavd (no force output; the HUD shows what a hand would feel)";
}

std::optional<DeviceProbe> SpaceMouseDevice::probe() const {
  DeviceProbe p;
  try {
    const std::shared_ptr<SpaceNav> nav = SpaceNav::open();
    p.opens = true;
    p.what = (nav->deviceName().empty() ? std::string("a 3D mouse") : nav->deviceName()) +
             " through spacenavd (no force output)";
  } catch (const DeviceError& e) {
    p.what = e.what();
  }
  return p;
}

}  // namespace millsim
