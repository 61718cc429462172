#include "millsim/driver/VendorLibrary.h"

#include <dlfcn.h>

#include <cstdlib>
#include <vector>

namespace millsim {

VendorLibrary::VendorLibrary(const char* overrideVariable, const char* fileName, std::span<const char* const> folders,
                             const std::string& what, const std::string& advice) {
  std::vector<std::string> tried;
  if (const char* path = std::getenv(overrideVariable); path && *path) {
    tried.push_back(path);
    handle_ = dlopen(path, RTLD_NOW | RTLD_LOCAL);
  } else {
    tried.push_back(fileName);
    handle_ = dlopen(fileName, RTLD_NOW | RTLD_LOCAL);
    for (const char* folder : folders) {
      if (handle_) break;
      tried.push_back(std::string(folder) + "/" + fileName);
      handle_ = dlopen(tried.back().c_str(), RTLD_NOW | RTLD_LOCAL);
    }
  }
  if (handle_) {
    from_ = tried.back();
    return;
  }
  std::string list;
  for (const auto& t : tried) list += (list.empty() ? "" : ", ") + t;
  error_ = what + " was not found (tried " + list + "): " + advice;
}

void* VendorLibrary::symbol(const char* name, bool needed) {
  void* f = handle_ ? dlsym(handle_, name) : nullptr;
  if (!f && needed && missing_.empty()) missing_ = name;
  return f;
}

void VendorLibrary::close() {
  if (handle_) dlclose(handle_);
  handle_ = nullptr;
}

}  // namespace millsim
