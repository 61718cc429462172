// An emulator of Force Dimension's DHD library (libdhd.so) for the `device`
// tests: the C functions MillSim resolves, with the semantics MillSim relies
// on — open by index or by type, what the device says it is and can do, the
// last error and its text, force output on at open (a sigma's only once
// enabled), poses in DHD's axes (metres; x towards the user, y right, z up) —
// behind which MillSim's simulated hand (millsim/devices/HandDevice.h) holds
// the handle, closed loop. A test points MILLSIM_FORCEDIMENSION_LIBRARY at it,
// so `millsim run` itself opens it. Never a stand-in for the real library: it
// is built only with the tests.
//
//   MILLSIM_DHD_EMULATOR_TRAJECTORY  CSV (t,x,y,z,qw,qx,qy,qz,button; X3D axes, metres) the hand's
//                                    reference follows, t from the open; unset: the handle rests
//                                    at the origin, button up
//   MILLSIM_DHD_EMULATOR_MAP         "s ox oy oz": the trajectory is in scene coordinates and the
//                                    device at (p - o) / s (a scene's positionScale and
//                                    positionCalibration; positions only)
//   MILLSIM_DHD_EMULATOR_RECORD      file written at dhdClose: t,fx,fy,fz,tx,ty,tz, one row per
//                                    dhdSetForceAndTorqueAndGripperForce, the wrench as sent (before
//                                    a force-only device drops the torque) in X3D axes, %.17g
//   MILLSIM_DHD_EMULATOR_TYPE        omega6 (default) | omega3 | sigma7 | delta6 | falcon
//   MILLSIM_DHD_EMULATOR_FAULT       no-driver | no-device | unplug-at=S | stall-at=S
// The types and constants are MillSim's own declarations of the vendor's
// (millsim/driver/ForceDimensionApi.h); t is seconds since the open (steady clock).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "EmulatedHand.h"
#include "millsim/devices/HandDevice.h"
#include "millsim/driver/ForceDimensionApi.h"

using namespace millsim::forcedimension;

namespace {

using Clock = std::chrono::steady_clock;

// dhdc.h's enum dhd_errors goes on past the ones MillSim names.
constexpr int kError = 1;          // DHD_ERROR
constexpr int kInvalidIndex = 15;  // DHD_ERROR_INVALID_INDEX

struct Model {
  const char* key;
  int type;
  const char* name;
  bool wrist, activeWrist, forceAtOpen;
  double maxForce;  // N
};

constexpr Model kModels[] = {
    {"omega6", DHD_DEVICE_OMEGA33, "omega.6 (MillSim's DHD emulator)", true, false, true, 12.0},
    {"omega3", DHD_DEVICE_OMEGA3, "omega.3 (MillSim's DHD emulator)", false, false, true, 12.0},
    {"sigma7", DHD_DEVICE_SIGMA331, "sigma.7 (MillSim's DHD emulator)", true, true, false, 20.0},
    {"delta6", DHD_DEVICE_DELTA6, "delta.6 (MillSim's DHD emulator)", true, true, true, 20.0},
    {"falcon", DHD_DEVICE_FALCON, "Falcon (MillSim's DHD emulator)", false, false, true, 9.0},
};

enum class Fault { None, NoDriver, NoDevice, UnplugAt, StallAt, Unknown };

constexpr std::size_t kRecordRows = 300000;  // 5 min at 1 kHz; later rows are dropped

struct Emulator {
  std::mutex mutex;  // open and close (one thread) against the calls (the haptic thread)
  bool open = false;
  const Model* model = &kModels[0];
  Fault fault = Fault::None;
  double faultAt = 1e300;
  bool stalled = false, forceOn = false, readYet = false;
  Clock::time_point start;
  double lastT = 0.0;
  unsigned int buttons = 0;
  std::unique_ptr<millsim::DeviceDriver> hand;  // null: no trajectory, the handle rests at the origin
  std::vector<double> record;                   // t, fx, fy, fz, tx, ty, tz per call (reserved at open)
  bool recording = false;
  std::string message;  // an open's detailed failure (a bad trajectory or setting)
};

Emulator& emu() {
  static Emulator e;
  return e;
}

// The last error, per calling thread: an open fails on the scene thread, a
// call on the haptic thread, and each asks right after its own failure.
thread_local int lastCode = 0;
thread_local const char* lastText = "no error";

void setError(int code, const char* text) {
  lastCode = code;
  lastText = text;
}

Fault faultSetting(double& at) {
  const char* f = std::getenv("MILLSIM_DHD_EMULATOR_FAULT");
  if (!f || !*f) return Fault::None;
  if (std::strcmp(f, "no-driver") == 0) return Fault::NoDriver;
  if (std::strcmp(f, "no-device") == 0) return Fault::NoDevice;
  const bool unplug = std::strncmp(f, "unplug-at=", 10) == 0, stall = std::strncmp(f, "stall-at=", 9) == 0;
  if (!unplug && !stall) return Fault::Unknown;
  at = std::atof(std::strchr(f, '=') + 1);
  return unplug ? Fault::UnplugAt : Fault::StallAt;
}

double now(const Emulator& e) { return std::chrono::duration<double>(Clock::now() - e.start).count(); }

// The open device `id` names, still plugged in; null (the error set) if none.
Emulator* device(char id) {
  Emulator& e = emu();
  if (id != char(-1) && id != 0) return setError(kInvalidIndex, "invalid device index"), nullptr;
  if (!e.open) return setError(DHD_ERROR_NO_DEVICE_FOUND, "no device open"), nullptr;
  if (e.fault == Fault::UnplugAt && now(e) >= e.faultAt) return setError(DHD_ERROR_COM, "communication error"), nullptr;
  return &e;
}

// Fails the open with `message` (also on stderr: a test's setting is wrong).
int refuse(Emulator& e, std::string message) {
  e.message = "MillSim's DHD emulator: " + std::move(message);
  std::fprintf(stderr, "%s\n", e.message.c_str());
  setError(kError, e.message.c_str());
  return -1;
}

// Opens the one device when it is of `type` (-1: any).
int openDevice(int type) {
  Emulator& e = emu();
  std::lock_guard lock(e.mutex);
  const char* key = std::getenv("MILLSIM_DHD_EMULATOR_TYPE");
  if (!key || !*key) key = kModels[0].key;
  const Model* model = nullptr;
  for (const Model& m : kModels)
    if (std::strcmp(key, m.key) == 0) model = &m;
  if (!model) return refuse(e, std::string("unknown MILLSIM_DHD_EMULATOR_TYPE ") + key);
  double at = 1e300;
  const Fault fault = faultSetting(at);
  if (fault == Fault::Unknown)
    return refuse(e, std::string("unknown MILLSIM_DHD_EMULATOR_FAULT ") + std::getenv("MILLSIM_DHD_EMULATOR_FAULT"));
  if (fault == Fault::NoDriver) return setError(DHD_ERROR_NO_DRIVER_FOUND, "no driver found"), -1;
  if (fault == Fault::NoDevice) return setError(DHD_ERROR_NO_DEVICE_FOUND, "no device found"), -1;
  if (type >= 0 && type != model->type) return setError(DHD_ERROR_NO_DEVICE_FOUND, "no device found"), -1;
  if (e.open) return 0;

  std::unique_ptr<millsim::DeviceDriver> hand;
  if (const char* file = std::getenv("MILLSIM_DHD_EMULATOR_TRAJECTORY"); file && *file) {
    try {
      hand = millsim::test::emulatedHand(file, std::getenv("MILLSIM_DHD_EMULATOR_MAP"), "MILLSIM_DHD_EMULATOR_MAP");
    } catch (const std::exception& x) {
      return refuse(e, x.what());
    }
  }
  e.recording = false;
  e.record.clear();
  if (const char* path = std::getenv("MILLSIM_DHD_EMULATOR_RECORD"); path && *path) {
    e.record.reserve(7 * kRecordRows);
    e.recording = true;
  }
  e.model = model;
  e.fault = fault;
  e.faultAt = at;
  e.hand = std::move(hand);
  e.stalled = e.readYet = false;
  e.forceOn = model->forceAtOpen;
  e.lastT = 0.0;
  e.buttons = 0;
  e.start = Clock::now();
  e.open = true;
  return 0;
}

void writeRecord(const Emulator& e, const char* path) {
  std::ofstream out(path);
  out << "t,fx,fy,fz,tx,ty,tz\n";
  out.precision(17);
  for (std::size_t i = 0; i + 7 <= e.record.size(); i += 7)
    out << e.record[i] << "," << e.record[i + 1] << "," << e.record[i + 2] << "," << e.record[i + 3] << ","
        << e.record[i + 4] << "," << e.record[i + 5] << "," << e.record[i + 6] << "\n";
}

}  // namespace

extern "C" {

int dhdGetDeviceCount() {
  double at = 0.0;
  const Fault fault = faultSetting(at);
  if (fault == Fault::NoDriver) return setError(DHD_ERROR_NO_DRIVER_FOUND, "no driver found"), -1;
  return fault == Fault::NoDevice ? 0 : 1;
}

int dhdOpen() { return openDevice(-1); }

int dhdOpenID(char id) {
  if (id != 0) return setError(kInvalidIndex, "invalid device index"), -1;
  return openDevice(-1);
}

int dhdOpenType(int type) { return openDevice(type); }

int dhdClose(char id) {
  Emulator& e = emu();
  std::lock_guard lock(e.mutex);
  if (id != char(-1) && id != 0) return setError(kInvalidIndex, "invalid device index"), -1;
  if (!e.open) return 0;  // idempotent
  e.open = false;         // an unplugged device closes too: the record is still written
  const char* path = std::getenv("MILLSIM_DHD_EMULATOR_RECORD");
  if (e.recording && path && *path) writeRecord(e, path);
  e.recording = false;
  e.record = {};
  e.hand.reset();
  return 0;
}

int dhdEnableForce(unsigned char on, char id) {
  std::lock_guard lock(emu().mutex);
  Emulator* e = device(id);
  if (!e) return -1;
  e->forceOn = on != DHD_OFF;
  return 0;
}

int dhdGetSystemType(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e ? e->model->type : -1;
}

const char* dhdGetSystemName(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e ? e->model->name : nullptr;
}

void dhdGetSDKVersion(int* major, int* minor, int* release, int* revision) {
  *major = 3, *minor = 17, *release = 0, *revision = 0;
}

bool dhdHasWrist(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e && e->model->wrist;
}

bool dhdHasActiveWrist(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e && e->model->activeWrist;
}

int dhdGetPositionAndOrientationFrame(double* px, double* py, double* pz, double matrix[3][3], char id) {
  std::lock_guard lock(emu().mutex);
  Emulator* e = device(id);
  if (!e) return -1;
  if (e->fault == Fault::StallAt && !e->stalled && now(*e) >= e->faultAt) {
    e->stalled = true;  // one USB hiccup: the answer comes 60 ms late, with the pose of then
    std::this_thread::sleep_for(std::chrono::milliseconds(60));
  }
  const double t = now(*e);
  millsim::DeviceReading r;  // the origin, identity, button up
  if (e->hand) r = e->hand->read(t, e->readYet ? t - e->lastT : 0.0);
  e->lastT = t;
  e->readYet = true;
  e->buttons = r.button ? 1u : 0u;
  const glm::dvec3& p = r.pose.position;
  *px = p.z, *py = p.x, *pz = p.y;
  // DHD axis i is X3D axis kAxis[i]: R_dhd = P R_x3d Pᵀ, element by element
  // (glm's matrices are indexed [column][row]). No wrist: no orientation.
  static constexpr int kAxis[3] = {2, 0, 1};
  const glm::dmat3 rx = e->model->wrist ? glm::mat3_cast(r.pose.orientation) : glm::dmat3(1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) matrix[i][j] = rx[kAxis[j]][kAxis[i]];
  return 0;
}

unsigned int dhdGetButtonMask(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e ? e->buttons : 0u;
}

int dhdSetForceAndTorqueAndGripperForce(double fx, double fy, double fz, double tx, double ty, double tz, double,
                                        char id) {
  std::lock_guard lock(emu().mutex);
  Emulator* e = device(id);
  if (!e) return -1;
  const glm::dvec3 force(fy, fz, fx), torque(ty, tz, tx);  // back to X3D axes
  if (e->recording && e->record.size() + 7 <= e->record.capacity()) {
    const double row[7] = {now(*e), force.x, force.y, force.z, torque.x, torque.y, torque.z};
    e->record.insert(e->record.end(), row, row + 7);
  }
  if (e->hand) {
    const bool finite = std::isfinite(fx + fy + fz + tx + ty + tz);
    const glm::dvec3 zero(0.0);
    e->hand->write(e->forceOn && finite ? force : zero, e->forceOn && finite && e->model->activeWrist ? torque : zero);
  }
  return 0;
}

int dhdErrorGetLast() { return lastCode; }

const char* dhdErrorGetLastStr() { return lastText; }

double dhdGetMaxForce(char id) {
  std::lock_guard lock(emu().mutex);
  const Emulator* e = device(id);
  return e ? e->model->maxForce : -1.0;
}

}  // extern "C"
