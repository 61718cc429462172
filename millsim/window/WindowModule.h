#pragma once
// Loading the window library at run time, like the graphics library
// (millsim/graphics/GraphicsModule.h): the millsim command links neither SDL2
// nor libGL, so every verb runs where they are missing, and `millsim run`
// says why it cannot open a window and goes on offscreen.
//
//   const WindowModule& w = loadWindowModule();          // throws GraphicsError
//   auto window = w.open(scene, options);                // on the window thread
#include <memory>

namespace millsim {

class AppWindow;
class Scene;
struct WindowOptions;

// Bumped whenever AppWindow or this table change incompatibly.
inline constexpr int kWindowAbiVersion = 2;

struct WindowModule {
  int abiVersion;
  // Opens the window and its GL context on the calling thread and meshes the
  // scene. Throws GraphicsError (no display, no GL 3.3) naming the cause.
  std::unique_ptr<AppWindow> (*open)(const Scene& scene, const WindowOptions& options);
};

// Opens libmillsim_window once per process (MILLSIM_WINDOW_LIBRARY overrides
// its path; by default it is next to libmillsim). Throws GraphicsError.
const WindowModule& loadWindowModule();

// True when a display server is reachable by name: DISPLAY or WAYLAND_DISPLAY is set.
bool displayAvailable();

}  // namespace millsim
