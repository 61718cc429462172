#pragma once
// A device vendor's closed library opened at run time (OpenHaptics' libHD.so,
// Force Dimension's libdhd.so): the path an environment variable names, else
// the file by the dynamic loader's search path, then the folders the vendor
// installs into; then its functions, resolved by name. MillSim never links
// a vendor SDK, so a machine without one builds and runs everything else.
#include <span>
#include <string>

#include "millsim/driver/DeviceDriver.h"

namespace millsim {

class VendorLibrary {
public:
  // Tries `overrideVariable`'s path when it is set (and only it), else
  // `fileName` on the loader's path and in each of `folders`. On failure
  // error() is "<what> was not found (tried <paths>): <advice>".
  VendorLibrary(const char* overrideVariable, const char* fileName, std::span<const char* const> folders,
                const std::string& what, const std::string& advice);

  bool loaded() const { return handle_ != nullptr; }
  const std::string& from() const { return from_; }    // the path it was loaded from
  const std::string& error() const { return error_; }  // why it was not loaded

  // Resolves `name` into `out` (null when the library lacks it, and the
  // first such name is kept as missing()).
  template <class F> void resolve(const char* name, F& out) { out = reinterpret_cast<F>(symbol(name, true)); }
  // The same for a function only later versions have: no missing() entry.
  template <class F> void resolveOptional(const char* name, F& out) { out = reinterpret_cast<F>(symbol(name, false)); }
  const std::string& missing() const { return missing_; }
  // Unloads it (after a missing function: nothing of it may be called).
  void close();

private:
  void* symbol(const char* name, bool needed);

  void* handle_ = nullptr;
  std::string from_, error_, missing_;
};

// A vendor API as resolved once per process: its functions and where they
// came from, or why they could not be had (kept: the first answer stands).
template <class Api> struct LoadedApi {
  Api api{};
  std::string from;
  std::string error;
  // The functions; DeviceError with `error` when there are none.
  const Api& get() const {
    if (!error.empty()) throw DeviceError(error);
    return api;
  }
};

}  // namespace millsim
