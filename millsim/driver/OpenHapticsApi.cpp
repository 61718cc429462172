#include "millsim/driver/OpenHapticsApi.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

#include "millsim/driver/DeviceDriver.h"

namespace millsim::openhaptics {

namespace {

// Where OpenHaptics for Linux (3.4) and its Touch driver packages put libHD.so.
const char* const kFolders[] = {"/usr/lib", "/usr/lib64", "/usr/local/lib", "/opt/OpenHaptics/Developer/lib",
                                "/opt/OpenHaptics/lib"};

struct Loaded {
  Api api{};
  std::string from;
  std::string error;  // why it could not be loaded (the first call's answer, kept)
};

template <class F> bool resolve(void* handle, const char* name, F& out, std::string& missing) {
  out = reinterpret_cast<F>(dlsym(handle, name));
  if (!out && missing.empty()) missing = name;
  return out != nullptr;
}

Loaded load() {
  Loaded l;
  std::vector<std::string> tried;
  void* handle = nullptr;
  if (const char* path = std::getenv("MILLSIM_OPENHAPTICS_LIBRARY"); path && *path) {
    tried.push_back(path);
    handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  } else {
    tried.push_back("libHD.so");
    handle = dlopen("libHD.so", RTLD_NOW | RTLD_LOCAL);
    for (const char* folder : kFolders) {
      if (handle) break;
      tried.push_back(std::string(folder) + "/libHD.so");
      handle = dlopen(tried.back().c_str(), RTLD_NOW | RTLD_LOCAL);
    }
  }
  if (!handle) {
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    l.error = "OpenHaptics' libHD.so was not found (tried " + list +
              "): install OpenHaptics for Linux and the Touch device driver from 3D Systems, or set "
              "MILLSIM_OPENHAPTICS_LIBRARY to the library's path";
    return l;
  }
  l.from = tried.back();
  std::string missing;
  Api& a = l.api;
  resolve(handle, "hdInitDevice", a.hdInitDevice, missing);
  resolve(handle, "hdDisableDevice", a.hdDisableDevice, missing);
  resolve(handle, "hdMakeCurrentDevice", a.hdMakeCurrentDevice, missing);
  resolve(handle, "hdBeginFrame", a.hdBeginFrame, missing);
  resolve(handle, "hdEndFrame", a.hdEndFrame, missing);
  resolve(handle, "hdGetError", a.hdGetError, missing);
  resolve(handle, "hdGetErrorString", a.hdGetErrorString, missing);
  resolve(handle, "hdEnable", a.hdEnable, missing);
  resolve(handle, "hdGetIntegerv", a.hdGetIntegerv, missing);
  resolve(handle, "hdGetDoublev", a.hdGetDoublev, missing);
  resolve(handle, "hdGetString", a.hdGetString, missing);
  resolve(handle, "hdSetDoublev", a.hdSetDoublev, missing);
  resolve(handle, "hdCheckCalibration", a.hdCheckCalibration, missing);
  resolve(handle, "hdUpdateCalibration", a.hdUpdateCalibration, missing);
  resolve(handle, "hdStartScheduler", a.hdStartScheduler, missing);
  resolve(handle, "hdStopScheduler", a.hdStopScheduler, missing);
  resolve(handle, "hdScheduleAsynchronous", a.hdScheduleAsynchronous, missing);
  resolve(handle, "hdUnschedule", a.hdUnschedule, missing);
  if (!missing.empty()) {
    l.error = l.from + " has no function " + missing +
              ": it is not OpenHaptics' HD library, or a version MillSim does not know (OpenHaptics 3.x is)";
    dlclose(handle);
  }
  // Otherwise it stays loaded for the process: its scheduler thread runs our callback.
  return l;
}

const Loaded& loaded() {
  static const Loaded l = load();
  return l;
}

}  // namespace

const Api& loadApi() {
  const Loaded& l = loaded();
  if (!l.error.empty()) throw DeviceError(l.error);
  return l.api;
}

const std::string& loadedFrom() { return loaded().from; }

std::string describe(const Api& api, const HDErrorInfo& e) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%x", e.errorCode);
  const char* text = api.hdGetErrorString ? api.hdGetErrorString(e.errorCode) : nullptr;
  return std::string(text && *text ? text : "HD error") + " (" + code + ", device code " +
         std::to_string(e.internalErrorCode) + ")";
}

}  // namespace millsim::openhaptics
