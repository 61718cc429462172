#pragma once
// VolumeError: a volume that cannot be loaded or made. Its own header, free of
// OpenVDB, so that the node side (VolumeObject) can throw it too.
#include <stdexcept>

namespace millsim {

// The message names the file and the problem.
struct VolumeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace millsim
