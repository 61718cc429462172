#pragma once
// The part of 3D Systems' OpenHaptics HD API that MillSim calls, declared
// here (the SDK is a closed binary licensed to device owners: nothing of it
// is needed to build MillSim) and found at run time in libHD.so.
//
// Every type and constant below was read from the vendor's own headers
// (banner "Copyright (c) 2004 SensAble Technologies", OpenHaptics 3.x):
// hdDefines.h (types, error codes, parameter and capability enums,
// calibration return values, button masks, HD_INVALID_HANDLE), hdScheduler.h
// (HDCallbackCode, HD_CALLBACK_DONE 0 / HD_CALLBACK_CONTINUE 1,
// HDSchedulerHandle) and hdDevice.h (the functions' signatures). Third-party
// re-declarations disagree with them (HD_NOMINAL_MAX_FORCE, HD_COMM_ERROR,
// the callback codes): do not take values from those.
#include <string>

namespace millsim::openhaptics {

using HHD = unsigned int;
using HDenum = unsigned int;
using HDerror = unsigned int;
using HDint = int;
using HDdouble = double;
using HDushort = unsigned short;
using HDstring = const char*;
using HDCallbackCode = unsigned int;
using HDSchedulerHandle = unsigned long;
using HDSchedulerCallback = HDCallbackCode (*)(void* userData);
struct HDErrorInfo {
  HDerror errorCode;
  int internalErrorCode;
  HHD hHD;
};

// hdDefines.h
inline constexpr HDerror HD_SUCCESS = 0x0000;
inline constexpr HDerror HD_COMM_ERROR = 0x0302;
inline constexpr HDerror HD_DEVICE_FAULT = 0x0300;
inline constexpr HDenum HD_CURRENT_BUTTONS = 0x2000;
inline constexpr HDenum HD_CURRENT_TRANSFORM = 0x2052;
inline constexpr HDenum HD_DEVICE_MODEL_TYPE = 0x2501;
inline constexpr HDenum HD_OUTPUT_DOF = 0x2554;
inline constexpr HDenum HD_NOMINAL_MAX_STIFFNESS = 0x2602;
inline constexpr HDenum HD_NOMINAL_MAX_FORCE = 0x2603;
inline constexpr HDenum HD_NOMINAL_MAX_CONTINUOUS_FORCE = 0x2604;
inline constexpr HDenum HD_CURRENT_FORCE = 0x2700;
inline constexpr HDenum HD_FORCE_OUTPUT = 0x4000;
inline constexpr HDenum HD_CALIBRATION_OK = 0x5000;
inline constexpr HDenum HD_CALIBRATION_NEEDS_UPDATE = 0x5001;
inline constexpr HDenum HD_CALIBRATION_NEEDS_MANUAL_INPUT = 0x5002;
inline constexpr HDenum HD_CALIBRATION_STYLE = 0x2555;
inline constexpr int HD_DEVICE_BUTTON_1 = 1 << 0;
inline constexpr HHD HD_INVALID_HANDLE = 0xFFFFFFFF;
inline constexpr HDushort HD_MAX_SCHEDULER_PRIORITY = 0xFFFF;  // USHRT_MAX
// hdScheduler.h
inline constexpr HDCallbackCode HD_CALLBACK_DONE = 0;
inline constexpr HDCallbackCode HD_CALLBACK_CONTINUE = 1;

// The functions MillSim calls, resolved from one loaded libHD.so.
struct Api {
  HHD (*hdInitDevice)(HDstring configName);
  void (*hdDisableDevice)(HHD);
  void (*hdMakeCurrentDevice)(HHD);
  void (*hdBeginFrame)(HHD);
  void (*hdEndFrame)(HHD);
  HDErrorInfo (*hdGetError)();
  HDstring (*hdGetErrorString)(HDerror);
  void (*hdEnable)(HDenum);
  void (*hdGetIntegerv)(HDenum, HDint*);
  void (*hdGetDoublev)(HDenum, HDdouble*);
  HDstring (*hdGetString)(HDenum);
  void (*hdSetDoublev)(HDenum, const HDdouble*);
  HDenum (*hdCheckCalibration)();
  void (*hdUpdateCalibration)(HDenum style);
  void (*hdStartScheduler)();
  void (*hdStopScheduler)();
  HDSchedulerHandle (*hdScheduleAsynchronous)(HDSchedulerCallback, void* userData, HDushort priority);
  void (*hdUnschedule)(HDSchedulerHandle);
};

// The library, opened once per process: MILLSIM_OPENHAPTICS_LIBRARY when set
// (a path), else libHD.so by the dynamic loader's search path, then the
// folders OpenHaptics for Linux installs into. Throws DeviceError saying
// what was tried and what to install, or which function the library lacks.
const Api& loadApi();
// Where the loaded library came from (after loadApi).
const std::string& loadedFrom();
// "HD_COMM_ERROR (0x302): <the library's text>" for an error on the stack.
std::string describe(const Api& api, const HDErrorInfo& e);

}  // namespace millsim::openhaptics
