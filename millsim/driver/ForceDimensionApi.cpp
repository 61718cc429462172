#include "millsim/driver/ForceDimensionApi.h"


#include "millsim/driver/VendorLibrary.h"

namespace millsim::forcedimension {

namespace {

// Where the Force Dimension SDK for Linux is unpacked or installed: its
// archive has lib/release/lin-x86_64-gcc/libdhd.so, which users copy or link
// into /usr/local/lib; /opt/forcedimension is where the SDK's installer puts it.
const char* const kFolders[] = {"/usr/lib", "/usr/lib64", "/usr/local/lib", "/opt/forcedimension/lib",
                                "/opt/forcedimension/sdk/lib/release/lin-x86_64-gcc"};

LoadedApi<Api> load() {
  LoadedApi<Api> l;
  VendorLibrary lib("MILLSIM_FORCEDIMENSION_LIBRARY", "libdhd.so", kFolders, "Force Dimension's libdhd.so",
                    "install the Force Dimension SDK for Linux (its lib/release/lin-x86_64-gcc/libdhd.so into "
                    "/usr/local/lib), or set MILLSIM_FORCEDIMENSION_LIBRARY to the library's path");
  if (!lib.loaded()) {
    l.error = lib.error();
    return l;
  }
  l.from = lib.from();
  Api& a = l.api;
  lib.resolve("dhdGetDeviceCount", a.dhdGetDeviceCount);
  lib.resolve("dhdOpen", a.dhdOpen);
  lib.resolve("dhdOpenID", a.dhdOpenID);
  lib.resolve("dhdOpenType", a.dhdOpenType);
  lib.resolve("dhdClose", a.dhdClose);
  lib.resolve("dhdEnableForce", a.dhdEnableForce);
  lib.resolve("dhdGetSystemType", a.dhdGetSystemType);
  lib.resolve("dhdGetSystemName", a.dhdGetSystemName);
  lib.resolve("dhdGetSDKVersion", a.dhdGetSDKVersion);
  lib.resolve("dhdHasWrist", a.dhdHasWrist);
  lib.resolve("dhdHasActiveWrist", a.dhdHasActiveWrist);
  lib.resolve("dhdGetPositionAndOrientationFrame", a.dhdGetPositionAndOrientationFrame);
  lib.resolve("dhdGetButtonMask", a.dhdGetButtonMask);
  lib.resolve("dhdSetForceAndTorqueAndGripperForce", a.dhdSetForceAndTorqueAndGripperForce);
  lib.resolve("dhdErrorGetLast", a.dhdErrorGetLast);
  lib.resolve("dhdErrorGetLastStr", a.dhdErrorGetLastStr);
  lib.resolveOptional("dhdGetMaxForce", a.dhdGetMaxForce);
  if (!lib.missing().empty()) {
    l.error = l.from + " has no function " + lib.missing() +
              ": it is not Force Dimension's DHD library, or older than MillSim needs (SDK 3.3 or later)";
    lib.close();
  }
  return l;  // otherwise it stays loaded for the process
}

const LoadedApi<Api>& loaded() {
  static const LoadedApi<Api> l = load();
  return l;
}

}  // namespace

const Api& loadApi() { return loaded().get(); }

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
