// An emulator of OpenHaptics' HD library (libHD.so) for the `device` tests:
// the same C functions with the same semantics as far as MillSim uses them —
// device init and the error stack, the calibration state, frames, the
// scheduler's own servo thread at 1 kHz calling asynchronous callbacks until
// they return HD_CALLBACK_DONE — behind which MillSim's simulated hand
// (millsim/devices/HandDevice.h) holds the stylus, closed loop: the forces
// the device is sent push back on the hand. A test
// points MILLSIM_OPENHAPTICS_LIBRARY at it, so `millsim run` itself opens it.
// Never a stand-in for the real library: it is built only with the tests.
//
//   MILLSIM_HD_EMULATOR_TRAJECTORY  CSV (t,x,y,z,qw,qx,qy,qz,button; metres) the hand's reference
//                                   follows in the device's frame (reported in mm, as the library
//                                   does); unset: the stylus rests at the origin
//   MILLSIM_HD_EMULATOR_MAP         "s ox oy oz": the trajectory is in scene coordinates and the
//                                   stylus at (p - o) / s (a scene's positionScale and positionCalibration)
//   MILLSIM_HD_EMULATOR_RECORD      file to write every force the device was sent, one row per
//                                   ended frame (t,fx,fy,fz), when the device is disabled
//   MILLSIM_HD_EMULATOR_FAULT       no-device | not-calibrated | needs-update | unplug-at=S |
//                                   stop-calling-at=S | stall-at=S (one servo tick 60 ms late)
// The types and constants are MillSim's own declarations of the vendor's
// (millsim/driver/OpenHapticsApi.h, checked against hdDefines.h and hdScheduler.h).
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "EmulatedHand.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/driver/OpenHapticsApi.h"

using namespace millsim::openhaptics;

namespace {

using Clock = std::chrono::steady_clock;

struct Async {
  HDSchedulerCallback cb;
  void* data;
  HDSchedulerHandle id;
  bool active;
};

struct Emulator {
  std::mutex mutex;  // the error stack and the callback list (not the frame data: the servo thread's own)
  std::vector<HDErrorInfo> errors;
  std::vector<Async> async;
  HDSchedulerHandle nextId = 1;
  std::thread servo;
  std::atomic<bool> running{false};
  Clock::time_point start;
  std::unique_ptr<millsim::DeviceDriver> hand;  // null: no trajectory, the stylus rests at the origin
  millsim::DeviceReading stylus;                // the hand's pose and button this tick
  double lastHandT = 0.0;
  bool handRead = false, stalled = false;
  std::string fault;
  double faultAt = 1e300;
  bool calibrated = true, needsUpdate = false, enabled = false, inFrame = false, opened = false;
  double tickT = 0.0;   // the current servo tick's time (s since hdStartScheduler)
  double force[3] = {0, 0, 0};
  std::vector<double> record;  // t, fx, fy, fz per ended frame (reserved: no growth in the loop)
  bool recording = false;
};

Emulator& emu() {
  static Emulator e;
  return e;
}

void push(HDerror code, int internal = 0) {
  std::lock_guard lock(emu().mutex);
  emu().errors.push_back(HDErrorInfo{code, internal, 0});
}

bool unplugged() { return emu().fault == "unplug-at" && emu().tickT >= emu().faultAt; }

void servoLoop() {
  Emulator& e = emu();
  auto next = Clock::now();
  while (e.running.load()) {
    e.tickT = std::chrono::duration<double>(Clock::now() - e.start).count();
    if (e.fault == "stall-at" && !e.stalled && e.tickT >= e.faultAt) {  // a late tick, as a busy USB bus makes one
      e.stalled = true;
      std::this_thread::sleep_for(std::chrono::milliseconds(60));
      e.tickT = std::chrono::duration<double>(Clock::now() - e.start).count();
      next = Clock::now();
    }
    const bool silent = e.fault == "stop-calling-at" && e.tickT >= e.faultAt;
    if (!silent) {
      std::vector<Async> due;
      {
        std::lock_guard lock(e.mutex);
        for (const Async& a : e.async)
          if (a.active) due.push_back(a);
      }
      for (const Async& a : due)
        if (a.cb(a.data) == HD_CALLBACK_DONE) {
          std::lock_guard lock(e.mutex);
          for (Async& b : e.async)
            if (b.id == a.id) b.active = false;
        }
    }
    next += std::chrono::milliseconds(1);
    // As a servo thread keeps its period: sleep most of it, spin the rest
    // (a plain sleep wakes late by the scheduler's slack on a loaded machine).
    std::this_thread::sleep_until(next - std::chrono::microseconds(200));
    while (Clock::now() < next) {
    }
  }
}

}  // namespace

extern "C" {

HHD hdInitDevice(HDstring) {
  Emulator& e = emu();
  if (const char* f = std::getenv("MILLSIM_HD_EMULATOR_FAULT")) {
    std::string fault = f;
    if (auto eq = fault.find('='); eq != std::string::npos) {
      e.faultAt = std::atof(fault.c_str() + eq + 1);
      fault.resize(eq);
    }
    e.fault = fault;
  }
  if (e.fault == "no-device") {
    push(HD_COMM_ERROR, -1);
    return HD_INVALID_HANDLE;
  }
  e.calibrated = e.fault != "not-calibrated" && e.fault != "needs-update";
  e.needsUpdate = e.fault == "needs-update";
  if (const char* t = std::getenv("MILLSIM_HD_EMULATOR_TRAJECTORY")) {
    try {
      e.hand = millsim::test::emulatedHand(t, std::getenv("MILLSIM_HD_EMULATOR_MAP"), "MILLSIM_HD_EMULATOR_MAP");
    } catch (const std::exception& x) {
      std::fprintf(stderr, "OpenHaptics emulator: %s\n", x.what());
      std::abort();
    }
  }
  if (std::getenv("MILLSIM_HD_EMULATOR_RECORD")) {
    e.record.reserve(4 * 200000);
    e.recording = true;
  }
  e.opened = true;
  return 1;
}

void hdMakeCurrentDevice(HHD) {}

void hdDisableDevice(HHD) {
  Emulator& e = emu();
  if (!e.opened) return;
  e.opened = false;
  e.hand.reset();  // after hdStopScheduler: no tick reads it any more
  if (const char* path = std::getenv("MILLSIM_HD_EMULATOR_RECORD")) {
    std::ofstream out(path);
    out << "t,fx,fy,fz\n";
    out.precision(17);
    for (std::size_t i = 0; i + 4 <= e.record.size(); i += 4)
      out << e.record[i] << "," << e.record[i + 1] << "," << e.record[i + 2] << "," << e.record[i + 3] << "\n";
  }
}

void hdBeginFrame(HHD) {
  Emulator& e = emu();
  if (e.inFrame) push(0x0400);  // HD_ILLEGAL_BEGIN
  e.inFrame = true;
  if (unplugged()) push(HD_COMM_ERROR, -2);
  // The hand moves to this tick under the force of the last one.
  if (e.hand) {
    e.stylus = e.hand->read(e.tickT, e.handRead ? e.tickT - e.lastHandT : 0.0);
    e.handRead = true;
    e.lastHandT = e.tickT;
  }
}

void hdEndFrame(HHD) {
  Emulator& e = emu();
  if (!e.inFrame) push(0x0401);  // HD_ILLEGAL_END
  e.inFrame = false;
  if (unplugged()) {
    push(HD_COMM_ERROR, -2);
    return;
  }
  if (e.recording && e.record.size() + 4 <= e.record.capacity()) {
    e.record.push_back(e.tickT);
    for (double f : e.force) e.record.push_back(f);
  }
  // Forces go out at the end of the frame; a Touch outputs no torque.
  if (e.hand) e.hand->write(glm::dvec3(e.force[0], e.force[1], e.force[2]), glm::dvec3(0.0));
}

HDErrorInfo hdGetError() {
  std::lock_guard lock(emu().mutex);
  if (emu().errors.empty()) return HDErrorInfo{HD_SUCCESS, 0, 0};
  const HDErrorInfo e = emu().errors.back();
  emu().errors.pop_back();
  return e;
}

HDstring hdGetErrorString(HDerror code) {
  switch (code) {
    case HD_COMM_ERROR: return "Communication error";
    case 0x0400: return "Illegal begin of frame";
    case 0x0401: return "Illegal end of frame";
    default: return "Emulated HD error";
  }
}

void hdEnable(HDenum cap) {
  if (cap == HD_FORCE_OUTPUT) emu().enabled = true;
}

void hdGetIntegerv(HDenum name, HDint* v) {
  const Emulator& e = emu();
  if (name == HD_CURRENT_BUTTONS) *v = e.stylus.button ? HD_DEVICE_BUTTON_1 : 0;
  else if (name == HD_OUTPUT_DOF) *v = 3;
  else if (name == HD_CALIBRATION_STYLE) *v = 1 << 2;  // HD_CALIBRATION_INKWELL
  else push(0x0100);  // HD_INVALID_ENUM
}

void hdGetDoublev(HDenum name, HDdouble* v) {
  const Emulator& e = emu();
  if (name == HD_CURRENT_TRANSFORM) {
    const millsim::Pose& p = e.stylus.pose;
    // Column-major 4x4: the rotation of the unit quaternion, translation in mm.
    const double w = p.orientation.w, x = p.orientation.x, y = p.orientation.y, z = p.orientation.z;
    const double r[9] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),
                         2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),
                         2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
    const double m[16] = {r[0], r[1], r[2], 0, r[3], r[4], r[5], 0, r[6], r[7], r[8], 0,
                          p.position.x * 1e3, p.position.y * 1e3, p.position.z * 1e3, 1};
    std::memcpy(v, m, sizeof m);
  } else if (name == HD_NOMINAL_MAX_FORCE) {
    *v = 3.3;  // what a Touch reports
  } else if (name == HD_NOMINAL_MAX_CONTINUOUS_FORCE) {
    *v = 0.88;
  } else if (name == HD_NOMINAL_MAX_STIFFNESS) {
    *v = 1.26;  // N/mm
  } else {
    push(0x0100);
  }
}

HDstring hdGetString(HDenum name) { return name == HD_DEVICE_MODEL_TYPE ? "Touch (MillSim's OpenHaptics emulator)" : ""; }

void hdSetDoublev(HDenum name, const HDdouble* v) {
  Emulator& e = emu();
  if (name != HD_CURRENT_FORCE || !e.inFrame) {
    push(0x0102);  // HD_INVALID_OPERATION
    return;
  }
  for (int i = 0; i < 3; ++i) e.force[i] = e.enabled && std::isfinite(v[i]) ? v[i] : 0.0;
}

HDenum hdCheckCalibration() {
  const Emulator& e = emu();
  return e.calibrated ? HD_CALIBRATION_OK : e.needsUpdate ? HD_CALIBRATION_NEEDS_UPDATE : HD_CALIBRATION_NEEDS_MANUAL_INPUT;
}

void hdUpdateCalibration(HDenum) {
  if (emu().needsUpdate) emu().calibrated = true;
}

void hdStartScheduler() {
  Emulator& e = emu();
  if (e.running.exchange(true)) return;
  e.start = Clock::now();
  e.servo = std::thread(servoLoop);
}

void hdStopScheduler() {
  Emulator& e = emu();
  if (!e.running.exchange(false)) return;
  e.servo.join();
}

HDSchedulerHandle hdScheduleAsynchronous(HDSchedulerCallback cb, void* data, HDushort) {
  std::lock_guard lock(emu().mutex);
  emu().async.push_back(Async{cb, data, emu().nextId, true});
  return emu().nextId++;
}

void hdUnschedule(HDSchedulerHandle id) {
  std::lock_guard lock(emu().mutex);
  for (Async& a : emu().async)
    if (a.id == id) a.active = false;
}

}  // extern "C"
