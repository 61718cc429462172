#include "millsim/driver/OpenHapticsDriver.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "millsim/driver/OpenHapticsApi.h"

namespace millsim {

namespace hd = openhaptics;

namespace {
// What the current device says it can do (it must be made current first).
OpenHapticsCapabilities capabilitiesOf(const hd::Api& a) {
  OpenHapticsCapabilities c;
  hd::HDint dof = 3;
  a.hdGetIntegerv(hd::HD_OUTPUT_DOF, &dof);
  c.outputDof = dof;
  a.hdGetDoublev(hd::HD_NOMINAL_MAX_FORCE, &c.maxForce);
  a.hdGetDoublev(hd::HD_NOMINAL_MAX_CONTINUOUS_FORCE, &c.maxContinuousForce);
  double stiffness = 0.0;
  a.hdGetDoublev(hd::HD_NOMINAL_MAX_STIFFNESS, &stiffness);
  c.maxStiffness = stiffness * 1e3;  // N/mm → N/m
  if (const char* model = a.hdGetString(hd::HD_DEVICE_MODEL_TYPE)) c.model = model;
  return c;
}
}  // namespace

OpenHapticsDriver::OpenHapticsDriver(const std::string& deviceName) : api_(&hd::loadApi()) {
  const hd::Api& a = *api_;
  const std::string which = deviceName.empty() ? "the default OpenHaptics device" : "OpenHaptics device '" + deviceName + "'";
  device_ = a.hdInitDevice(deviceName.empty() ? nullptr : deviceName.c_str());
  const hd::HDErrorInfo e = a.hdGetError();
  if (device_ == hd::HD_INVALID_HANDLE || e.errorCode != hd::HD_SUCCESS)
    throw DeviceError("could not open " + which + " with " + hd::loadedFrom() + ": " + hd::describe(a, e) +
                      ". Is the device plugged in and powered, and does the vendor's Touch_Setup (or "
                      "Geomagic_Touch_Setup) find it? A Touch of the HID generation needs the 2022 or newer "
                      "Touch device driver");
  a.hdMakeCurrentDevice(device_);
  hd::HDenum calibration = a.hdCheckCalibration();
  if (calibration == hd::HD_CALIBRATION_NEEDS_UPDATE) {
    hd::HDint style = 0;
    a.hdGetIntegerv(hd::HD_CALIBRATION_STYLE, &style);
    a.hdUpdateCalibration(hd::HDenum(style));
    calibration = a.hdCheckCalibration();
  }
  if (calibration != hd::HD_CALIBRATION_OK) {
    a.hdDisableDevice(device_);
    disabled_ = true;
    throw DeviceError(which + " is not calibrated" +
                      (calibration == hd::HD_CALIBRATION_NEEDS_MANUAL_INPUT
                           ? std::string(": put the stylus in its inkwell (or run the vendor's Touch_Diagnostic "
                                         "calibration) and start again")
                           : std::string(" (hdCheckCalibration said ") + std::to_string(calibration) + ")"));
  }
  caps_ = capabilitiesOf(a);
  a.hdEnable(hd::HD_FORCE_OUTPUT);
  if (hd::HDErrorInfo f = a.hdGetError(); f.errorCode != hd::HD_SUCCESS) {
    a.hdDisableDevice(device_);
    disabled_ = true;
    throw DeviceError("could not enable force output on " + which + ": " + hd::describe(a, f));
  }
}

OpenHapticsDriver::~OpenHapticsDriver() { stopServo(); }

std::string OpenHapticsDriver::describe() const {
  return (caps_.model.empty() ? std::string("an OpenHaptics device") : caps_.model) + " with " + hd::loadedFrom() +
         ", force out (the renderer's torque is logged, not sent)";
}

unsigned int OpenHapticsDriver::servoTick(void* self) {
  auto* d = static_cast<OpenHapticsDriver*>(self);
  return d->frame_() ? hd::HD_CALLBACK_CONTINUE : hd::HD_CALLBACK_DONE;
}

void OpenHapticsDriver::startServo(std::function<bool()> frame) {
  frame_ = std::move(frame);
  handle_ = api_->hdScheduleAsynchronous(&OpenHapticsDriver::servoTick, this, hd::HD_MAX_SCHEDULER_PRIORITY);
  scheduled_ = true;
  api_->hdStartScheduler();
  if (hd::HDErrorInfo e = api_->hdGetError(); e.errorCode != hd::HD_SUCCESS)
    throw DeviceError("OpenHaptics' scheduler did not start: " + hd::describe(*api_, e));
}

void OpenHapticsDriver::stopServo() {
  if (servoStopped_) return;
  servoStopped_ = true;
  if (scheduled_) {
    api_->hdStopScheduler();  // returns once its thread calls no more
    api_->hdUnschedule(handle_);
  }
  if (!disabled_) {
    api_->hdDisableDevice(device_);
    disabled_ = true;
  }
}

bool OpenHapticsDriver::checkError(const char* during) {
  const hd::HDErrorInfo e = api_->hdGetError();
  if (e.errorCode == hd::HD_SUCCESS) return false;
  ++counters_.transferErrors;
  if (!failed_) {  // the run stops: one message, made once (not steady state)
    failed_ = true;
    failure_ = std::string("the OpenHaptics device failed ") + during + ": " + hd::describe(*api_, e) +
               (e.errorCode == hd::HD_COMM_ERROR ? " (unplugged, or its driver stopped?)" : "");
  }
  return true;
}

DeviceReading OpenHapticsDriver::read(double, double) {
  DeviceReading r;
  api_->hdBeginFrame(device_);
  inFrame_ = true;
  double m[16];
  hd::HDint buttons = 0;
  api_->hdGetDoublev(hd::HD_CURRENT_TRANSFORM, m);
  api_->hdGetIntegerv(hd::HD_CURRENT_BUTTONS, &buttons);
  if (checkError("reading its pose")) {
    r.valid = false;
    return r;
  }
  ++counters_.framesReceived;
  // Column-major 4x4 (hdDefines.h's hd::HD_CURRENT_TRANSFORM): rotation in the
  // upper 3x3, translation (mm) in elements 12-14.
  const glm::dmat3 rotation(m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10]);
  r.pose.position = glm::dvec3(m[12], m[13], m[14]) * 1e-3;
  r.pose.orientation = glm::normalize(glm::quat_cast(rotation));
  r.button = (buttons & hd::HD_DEVICE_BUTTON_1) != 0;
  return r;
}

void OpenHapticsDriver::write(const glm::dvec3& force, const glm::dvec3&) {
  if (!inFrame_) api_->hdBeginFrame(device_);  // a frame whose read was skipped still sends
  const double f[3] = {force.x, force.y, force.z};
  api_->hdSetDoublev(hd::HD_CURRENT_FORCE, f);
  api_->hdEndFrame(device_);
  inFrame_ = false;
  if (!checkError("sending the force")) ++counters_.framesSent;
}

void OpenHapticsDriver::stop() {
  // On the servo thread after the last frame: one more device frame, with no
  // force. After stopServo (the library stopped calling) frames are no longer
  // ours to make; hdDisableDevice has ended its force output.
  if (servoStopped_) return;
  write(glm::dvec3(0.0), glm::dvec3(0.0));
}

DeviceProbe probeOpenHapticsDevice(const std::string& deviceName) {
  const OpenHapticsProbe p = probeOpenHaptics(deviceName);
  DeviceProbe d;
  if (!p.device) {
    d.what = p.error;
    return d;
  }
  const OpenHapticsCapabilities& c = p.capabilities;
  d.opens = p.calibration == "OK" || p.calibration.rfind("needs an update", 0) == 0;
  d.what = (c.model.empty() ? std::string("an OpenHaptics device") : c.model) + " with " + p.library + ", " +
           (c.outputDof >= 6 ? "6-DOF output (MillSim sends force only)" : "3-DOF force output") + "; calibration " +
           p.calibration;
  d.maxStiffness = c.maxStiffness;
  d.maxForce = c.maxForce;
  return d;
}

OpenHapticsProbe probeOpenHaptics(const std::string& deviceName) {
  OpenHapticsProbe p;
  const hd::Api* api = nullptr;
  try {
    api = &hd::loadApi();
  } catch (const DeviceError& e) {
    p.error = e.what();
    return p;
  }
  const hd::Api& a = *api;
  p.library = hd::loadedFrom();
  const hd::HHD device = a.hdInitDevice(deviceName.empty() ? nullptr : deviceName.c_str());
  if (const hd::HDErrorInfo e = a.hdGetError(); device == hd::HD_INVALID_HANDLE || e.errorCode != hd::HD_SUCCESS) {
    p.error = "no device opened: " + hd::describe(a, e);
    return p;
  }
  p.device = true;
  a.hdMakeCurrentDevice(device);
  const hd::HDenum calibration = a.hdCheckCalibration();
  p.calibration = calibration == hd::HD_CALIBRATION_OK            ? "OK"
                  : calibration == hd::HD_CALIBRATION_NEEDS_UPDATE ? "needs an update (MillSim makes it when it opens the device)"
                                                              : "needs the stylus in its inkwell";
  p.capabilities = capabilitiesOf(a);
  a.hdDisableDevice(device);
  return p;
}

}  // namespace millsim
