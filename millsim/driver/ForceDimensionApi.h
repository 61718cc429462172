#pragma once
// The part of Force Dimension's DHD API that MillSim calls, declared here
// (the SDK is a closed binary licensed to device owners: nothing of it is
// needed to build MillSim) and found at run time in libdhd.so.
//
// Every signature and constant below was read from the vendor's own C header
// dhdc.h ("DHD - Haptic SDK ver 3.7.0-pre, (C) 2001-2016 Force Dimension"):
// the functions return int (< 0 on error, dhdErrorGetLastStr says why), and
// the last argument is the device index as a char (-1: the default device;
// the header's default argument is C++ sugar, the C ABI always passes it).
// dhdGetMaxForce (double dhdGetMaxForce(char)) came later (SDK 3.8) and is
// optional: an older library simply does not say its force limit.
#include <string>

namespace millsim::forcedimension {

// dhdc.h, "devices"
inline constexpr int DHD_DEVICE_NONE = 0;
inline constexpr int DHD_DEVICE_OMEGA3 = 33;
inline constexpr int DHD_DEVICE_OMEGA33 = 34;
inline constexpr int DHD_DEVICE_OMEGA331 = 35;
inline constexpr int DHD_DEVICE_OMEGA33_LEFT = 36;
inline constexpr int DHD_DEVICE_OMEGA331_LEFT = 37;
inline constexpr int DHD_DEVICE_FALCON = 60;
inline constexpr int DHD_DEVICE_DELTA3 = 63;
inline constexpr int DHD_DEVICE_DELTA6 = 64;
inline constexpr int DHD_DEVICE_SIGMA331 = 104;
inline constexpr int DHD_DEVICE_SIGMA331_LEFT = 105;
// dhdc.h, "status" and "useful non-error, positive return values"
inline constexpr unsigned char DHD_ON = 1;
inline constexpr unsigned char DHD_OFF = 0;
inline constexpr int DHD_TIMEGUARD = 1;
inline constexpr int DHD_MOTOR_SATURATED = 2;
// dhdc.h, enum dhd_errors (in order from DHD_NO_ERROR = 0)
inline constexpr int DHD_ERROR_COM = 2;
inline constexpr int DHD_ERROR_NO_DRIVER_FOUND = 4;
inline constexpr int DHD_ERROR_NO_DEVICE_FOUND = 5;
inline constexpr int DHD_ERROR_TIMEOUT = 7;
inline constexpr int DHD_ERROR_DEVICE_NOT_READY = 12;

// The functions MillSim calls, resolved from one loaded libdhd.so.
struct Api {
  int (*dhdGetDeviceCount)();
  int (*dhdOpen)();
  int (*dhdOpenID)(char id);
  int (*dhdOpenType)(int type);
  int (*dhdClose)(char id);
  int (*dhdEnableForce)(unsigned char on, char id);
  int (*dhdGetSystemType)(char id);
  const char* (*dhdGetSystemName)(char id);
  void (*dhdGetSDKVersion)(int* major, int* minor, int* release, int* revision);
  bool (*dhdHasWrist)(char id);
  bool (*dhdHasActiveWrist)(char id);
  int (*dhdGetPositionAndOrientationFrame)(double* px, double* py, double* pz, double matrix[3][3], char id);
  unsigned int (*dhdGetButtonMask)(char id);
  int (*dhdSetForceAndTorqueAndGripperForce)(double fx, double fy, double fz, double tx, double ty, double tz,
                                             double fg, char id);
  int (*dhdErrorGetLast)();
  const char* (*dhdErrorGetLastStr)();
  double (*dhdGetMaxForce)(char id);  // optional (SDK 3.8 and later): null when the library lacks it
};

// The library, opened once per process: MILLSIM_FORCEDIMENSION_LIBRARY when
// set (a path), else libdhd.so by the dynamic loader's search path, then the
// folders the Force Dimension SDK is unpacked or installed into. Throws
// DeviceError saying what was tried and what to install, or which function
// the library lacks.
const Api& loadApi();
// Where the loaded library came from (after loadApi).
const std::string& loadedFrom();
// "SDK 3.7.0" (after loadApi).
std::string sdkVersion(const Api& api);
// The library's last error: "<its text> (DHD error N)".
std::string lastError(const Api& api);

}  // namespace millsim::forcedimension
