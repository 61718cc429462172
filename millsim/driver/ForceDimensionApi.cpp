#include "millsim/driver/ForceDimensionApi.h"

#include <dlfcn.h>

#include <cstdlib>
#include <vector>

#include "millsim/driver/DeviceDriver.h"

namespace millsim::forcedimension {

namespace {

// Where the Force Dimension SDK for Linux is unpacked or installed: its
// archive has lib/release/lin-x86_64-gcc/libdhd.so, which users copy or link
// into /usr/local/lib; /opt/forcedimension is where the SDK's installer puts it.
const char* const kFolders[] = {"/usr/lib", "/usr/lib64", "/usr/local/lib", "/opt/forcedimension/lib",
                                "/opt/forcedimension/sdk/lib/release/lin-x86_64-gcc"};

struct Loaded {
  Api api{};
  std::string from;
  std::string error;  // why it could not be loaded (the first call's answer, kept)
};

template <class F> void resolve(void* handle, const char* name, F& out, std::string& missing) {
  out = reinterpret_cast<F>(dlsym(handle, name));
  if (!out && missing.empty()) missing = name;
}

Loaded load() {
  Loaded l;
  std::vector<std::string> tried;
  void* handle = nullptr;
  if (const char* path = std::getenv("MILLSIM_FORCEDIMENSION_LIBRARY"); path && *path) {
    tried.push_back(path);
    handle = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  } else {
    tried.push_back("libdhd.so");
    handle = dlopen("libdhd.so", RTLD_NOW | RTLD_LOCAL);
    for (const char* folder : kFolders) {
      if (handle) break;
      tried.push_back(std::string(folder) + "/libdhd.so");
      handle = dlopen(tried.back().c_str(), RTLD_NOW | RTLD_LOCAL);
    }
  }
  if (!handle) {
    std::string list;
    for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
    l.error = "Force Dimension's libdhd.so was not found (tried " + list +
              "): install the Force Dimension SDK for Linux (its lib/release/lin-x86_64-gcc/libdhd.so into "
              "/usr/local/lib), or set MILLSIM_FORCEDIMENSION_LIBRARY to the library's path";
    return l;
  }
  l.from = tried.back();
  std::string missing;
  Api& a = l.api;
  resolve(handle, "dhdGetDeviceCount", a.dhdGetDeviceCount, missing);
  resolve(handle, "dhdOpen", a.dhdOpen, missing);
  resolve(handle, "dhdOpenID", a.dhdOpenID, missing);
  resolve(handle, "dhdOpenType", a.dhdOpenType, missing);
  resolve(handle, "dhdClose", a.dhdClose, missing);
  resolve(handle, "dhdEnableForce", a.dhdEnableForce, missing);
  resolve(handle, "dhdGetSystemType", a.dhdGetSystemType, missing);
  resolve(handle, "dhdGetSystemName", a.dhdGetSystemName, missing);
  resolve(handle, "dhdGetSDKVersion", a.dhdGetSDKVersion, missing);
  resolve(handle, "dhdHasWrist", a.dhdHasWrist, missing);
  resolve(handle, "dhdHasActiveWrist", a.dhdHasActiveWrist, missing);
  resolve(handle, "dhdGetPositionAndOrientationFrame", a.dhdGetPositionAndOrientationFrame, missing);
  resolve(handle, "dhdGetButtonMask", a.dhdGetButtonMask, missing);
  resolve(handle, "dhdSetForceAndTorqueAndGripperForce", a.dhdSetForceAndTorqueAndGripperForce, missing);
  resolve(handle, "dhdErrorGetLast", a.dhdErrorGetLast, missing);
  resolve(handle, "dhdErrorGetLastStr", a.dhdErrorGetLastStr, missing);
  if (!missing.empty()) {
    l.error = l.from + " has no function " + missing +
              ": it is not Force Dimension's DHD library, or older than MillSim needs (SDK 3.3 or later)";
    dlclose(handle);
    return l;
  }
  a.dhdGetMaxForce = reinterpret_cast<double (*)(char)>(dlsym(handle, "dhdGetMaxForce"));  // optional
  return l;  // stays loaded for the process
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

std::string sdkVersion(const Api& api) {
  int major = 0, minor = 0, release = 0, revision = 0;
  api.dhdGetSDKVersion(&major, &minor, &release, &revision);
  return "SDK " + std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(release);
}

std::string lastError(const Api& api) {
  const char* text = api.dhdErrorGetLastStr();
  return std::string(text && *text ? text : "DHD error") + " (DHD error " + std::to_string(api.dhdErrorGetLast()) + ")";
}

}  // namespace millsim::forcedimension
