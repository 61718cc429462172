#include "millsim/driver/ForceDimensionDriver.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "millsim/driver/ForceDimensionApi.h"

namespace millsim {

namespace fd = forcedimension;

namespace {

// DHD's axes (x towards the user, y right, z up) and X3D's (x right, y up,
// z towards the user) are the same right-handed frame with the axes renamed:
// a cyclic permutation, exact in floating point both ways.
glm::dvec3 toScene(double x, double y, double z) { return {y, z, x}; }
glm::dvec3 toDevice(const glm::dvec3& v) { return {v.z, v.x, v.y}; }

// What the open device `id` says it is and can do.
ForceDimensionCapabilities capabilitiesOf(const fd::Api& a, char id) {
  ForceDimensionCapabilities c;
  c.systemType = a.dhdGetSystemType(id);
  if (const char* name = a.dhdGetSystemName(id)) c.model = name;
  c.sensesOrientation = a.dhdHasWrist(id);
  c.outputsTorque = a.dhdHasActiveWrist(id);
  if (a.dhdGetMaxForce) {
    const double limit = a.dhdGetMaxForce(id);
    if (limit > 0.0) c.maxForce = limit;  // negative: no limit set, the library does not say the device's
  }
  return c;
}

// What to do about the library's last error when opening failed.
std::string advice(int error, bool falcon) {
  switch (error) {
    case fd::DHD_ERROR_NO_DRIVER_FOUND:
      return ". The device's USB driver was not found: on Linux, install the udev rule that comes with the Force "
             "Dimension SDK so that a user may open the device, then plug it in again";
    case fd::DHD_ERROR_NO_DEVICE_FOUND:
      return falcon ? ". Is the Falcon plugged in and powered, and is it not open in another program?"
                    : ". Is the device plugged in and powered, and does the SDK's HapticDesk find it?";
    case fd::DHD_ERROR_DEVICE_NOT_READY:
      return falcon ? ". A Falcon reports true positions only once homed: pull the grip fully out and push it back in"
                    : ". Run the SDK's HapticInit (or autoinit) to initialise it";
    default:
      return ". Does the SDK's HapticDesk open it?";
  }
}

int openSelected(const fd::Api& a, const ForceDimensionSelector& which) {
  if (which.falcon) return a.dhdOpenType(fd::DHD_DEVICE_FALCON);
  if (which.index < 0) return a.dhdOpen();
  return a.dhdOpenID(char(which.index));
}

}  // namespace

std::string ForceDimensionSelector::describe() const {
  if (falcon) return "the first Falcon";
  if (index < 0) return "the first Force Dimension device";
  return "Force Dimension device " + std::to_string(index);
}

ForceDimensionDriver::ForceDimensionDriver(const ForceDimensionSelector& which) : api_(&fd::loadApi()) {
  const fd::Api& a = *api_;
  const int id = openSelected(a, which);
  if (id < 0)
    throw DeviceError("could not open " + which.describe() + " with " + fd::loadedFrom() + ": " + fd::lastError(a) +
                      advice(a.dhdErrorGetLast(), which.falcon));
  id_ = char(id);
  open_ = true;
  caps_ = capabilitiesOf(a, id_);
  if (a.dhdEnableForce(fd::DHD_ON, id_) < 0) {
    const std::string why = fd::lastError(a);
    a.dhdClose(id_);
    open_ = false;
    throw DeviceError("could not enable force output on " + which.describe() + " (" + caps_.model + "): " + why);
  }
}

ForceDimensionDriver::~ForceDimensionDriver() {
  if (open_) api_->dhdClose(id_);
}

std::string ForceDimensionDriver::describe() const {
  std::string s = caps_.model.empty() ? "a Force Dimension device" : caps_.model;
  s += ", " + fd::sdkVersion(*api_) + ", ";
  s += caps_.outputsTorque ? "force and torque out" : "force out (the renderer's torque is logged, not sent)";
  if (!caps_.sensesOrientation) s += "; it senses no orientation: the burr keeps orientationCalibration's";
  return s;
}

void ForceDimensionDriver::fail(const char* during) {
  ++counters_.transferErrors;
  if (failed_) return;
  failed_ = true;  // the run stops: one message, made once (not steady state)
  failure_ = std::string("the Force Dimension device failed ") + during + ": " + fd::lastError(*api_) +
             (api_->dhdErrorGetLast() == fd::DHD_ERROR_COM ? " (unplugged, or switched off?)" : "");
}

DeviceReading ForceDimensionDriver::read(double, double) {
  DeviceReading r;
  double px = 0.0, py = 0.0, pz = 0.0, m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Positive results (DHD_TIMEGUARD, DHD_MOTOR_SATURATED) are notices, not errors.
  if (api_->dhdGetPositionAndOrientationFrame(&px, &py, &pz, m, id_) < 0) {
    fail("reading its pose");
    r.valid = false;
    return r;
  }
  const unsigned int buttons = api_->dhdGetButtonMask(id_);
  ++counters_.framesReceived;
  r.pose.position = toScene(px, py, pz);
  // m[i][j] is row i, column j of the rotation from the handle's axes to the
  // base's; in X3D axes, column j is that rotation applied to X3D's axis j.
  glm::dmat3 rotation;
  for (int j = 0; j < 3; ++j) {
    glm::dvec3 axis(0.0);
    axis[j] = 1.0;
    const glm::dvec3 d = toDevice(axis);
    rotation[j] = toScene(m[0][0] * d.x + m[0][1] * d.y + m[0][2] * d.z, m[1][0] * d.x + m[1][1] * d.y + m[1][2] * d.z,
                          m[2][0] * d.x + m[2][1] * d.y + m[2][2] * d.z);
  }
  r.pose.orientation = glm::normalize(glm::quat_cast(rotation));
  r.button = buttons != 0;  // any button, or an omega.7's or sigma.7's gripper button
  return r;
}

void ForceDimensionDriver::write(const glm::dvec3& force, const glm::dvec3& torque) {
  if (!open_) return;
  const glm::dvec3 f = toDevice(force);
  const glm::dvec3 t = caps_.outputsTorque ? toDevice(torque) : glm::dvec3(0.0);
  if (api_->dhdSetForceAndTorqueAndGripperForce(f.x, f.y, f.z, t.x, t.y, t.z, 0.0, id_) < 0) {
    fail("sending the force");
    return;
  }
  ++counters_.framesSent;
}

void ForceDimensionDriver::stop() {
  if (!open_) return;
  // The zero wrench first, then force off and close (which also stops it).
  if (!failed_) write(glm::dvec3(0.0), glm::dvec3(0.0));
  api_->dhdEnableForce(fd::DHD_OFF, id_);
  api_->dhdClose(id_);
  open_ = false;
}

DeviceProbe probeForceDimensionDevice(const ForceDimensionSelector& which) {
  const ForceDimensionProbe p = probeForceDimension(which);
  DeviceProbe d;
  d.opens = p.device;
  if (!p.device) {
    d.what = p.error;
    return d;
  }
  const ForceDimensionCapabilities& c = p.capabilities;
  d.what = (c.model.empty() ? std::string("a Force Dimension device") : c.model) + " with " + p.library + " (" +
           p.version + "), " + (c.outputsTorque ? "force and torque out" : "force out only");
  d.maxForce = c.maxForce;
  return d;
}

ForceDimensionProbe probeForceDimension(const ForceDimensionSelector& which) {
  ForceDimensionProbe p;
  const fd::Api* api = nullptr;
  try {
    api = &fd::loadApi();
  } catch (const DeviceError& e) {
    p.error = e.what();
    return p;
  }
  const fd::Api& a = *api;
  p.library = fd::loadedFrom();
  p.version = fd::sdkVersion(a);
  p.deviceCount = std::max(0, a.dhdGetDeviceCount());
  const int id = openSelected(a, which);
  if (id < 0) {
    p.error = "no device opened: " + fd::lastError(a) + advice(a.dhdErrorGetLast(), which.falcon);
    return p;
  }
  p.device = true;
  p.capabilities = capabilitiesOf(a, char(id));
  a.dhdClose(char(id));
  return p;
}

}  // namespace millsim
