#pragma once
// The one error type of the graphics side: no OSMesa, an unsupported GL
// version, a bad image size, a shader that does not compile, an unwritable
// PNG path. The message names the offending value. Header-only, so that the
// millsim command can catch it without linking the graphics library.
#include <stdexcept>

namespace millsim {

struct GraphicsError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace millsim
