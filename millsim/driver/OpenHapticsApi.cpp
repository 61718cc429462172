#include "millsim/driver/OpenHapticsApi.h"

#include <cstdio>

#include "millsim/driver/VendorLibrary.h"

namespace millsim::openhaptics {

namespace {

// Where OpenHaptics for Linux (3.4) and its Touch driver packages put libHD.so.
const char* const kFolders[] = {"/usr/lib", "/usr/lib64", "/usr/local/lib", "/opt/OpenHaptics/Developer/lib",
                                "/opt/OpenHaptics/lib"};

LoadedApi<Api> load() {
  LoadedApi<Api> l;
  VendorLibrary lib("MILLSIM_OPENHAPTICS_LIBRARY", "libHD.so", kFolders, "OpenHaptics' libHD.so",
                    "install OpenHaptics for Linux and the Touch device driver from 3D Systems, or set "
                    "MILLSIM_OPENHAPTICS_LIBRARY to the library's path");
  if (!lib.loaded()) {
    l.error = lib.error();
    return l;
  }
  l.from = lib.from();
  Api& a = l.api;
  lib.resolve("hdInitDevice", a.hdInitDevice);
  lib.resolve("hdDisableDevice", a.hdDisableDevice);
  lib.resolve("hdMakeCurrentDevice", a.hdMakeCurrentDevice);
  lib.resolve("hdBeginFrame", a.hdBeginFrame);
  lib.resolve("hdEndFrame", a.hdEndFrame);
  lib.resolve("hdGetError", a.hdGetError);
  lib.resolve("hdGetErrorString", a.hdGetErrorString);
  lib.resolve("hdEnable", a.hdEnable);
  lib.resolve("hdGetIntegerv", a.hdGetIntegerv);
  lib.resolve("hdGetDoublev", a.hdGetDoublev);
  lib.resolve("hdGetString", a.hdGetString);
  lib.resolve("hdSetDoublev", a.hdSetDoublev);
  lib.resolve("hdCheckCalibration", a.hdCheckCalibration);
  lib.resolve("hdUpdateCalibration", a.hdUpdateCalibration);
  lib.resolve("hdStartScheduler", a.hdStartScheduler);
  lib.resolve("hdStopScheduler", a.hdStopScheduler);
  lib.resolve("hdScheduleAsynchronous", a.hdScheduleAsynchronous);
  lib.resolve("hdUnschedule", a.hdUnschedule);
  if (!lib.missing().empty()) {
    l.error = l.from + " has no function " + lib.missing() +
              ": it is not OpenHaptics' HD library, or a version MillSim does not know (OpenHaptics 3.x is)";
    lib.close();
  }
  // Otherwise it stays loaded for the process: its scheduler thread runs our callback.
  return l;
}

const LoadedApi<Api>& loaded() {
  static const LoadedApi<Api> l = load();
  return l;
}

}  // namespace

const Api& loadApi() { return loaded().get(); }

const std::string& loadedFrom() { return loaded().from; }

std::string describe(const Api& api, const HDErrorInfo& e) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%x", e.errorCode);
  const char* text = api.hdGetErrorString ? api.hdGetErrorString(e.errorCode) : nullptr;
  return std::string(text && *text ? text : "HD error") + " (" + code + ", device code " +
         std::to_string(e.internalErrorCode) + ")";
}

}  // namespace millsim::openhaptics
