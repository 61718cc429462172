#pragma once
// AppWindow: the on-screen window of `millsim run` (libmillsim_window: SDL2
// for the window and input, OpenGL through glvnd, Dear ImGui for the HUD). It
// draws with the same SceneDrawer as the offscreen harness, navigates as X3D
// browsers do in EXAMINE mode, moves and toggles the cut planes, and turns
// keys into commands for the scene thread. With a MouseDevice it also turns
// the mouse into a tool pose (pointer()).
//
// Threads: everything here runs on one thread (the window thread), which
// creates the window, polls its events and draws. The window knows nothing
// of the haptic loop: the caller hands it tool poses and HUD numbers.
#include <cstddef>
#include <string>
#include <vector>

#include "millsim/graphics/Image.h"
#include "millsim/graphics/SceneDrawer.h"
#include "millsim/math/Pose.h"
#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

class Scene;
class VoxelVolume;

struct WindowOptions {
  int width = 1024, height = 768;
  std::string title;  // "MillSim — <WorldInfo title or file name>"
  // Voxels to mesh in place of each scene VolumeObject's own (the window
  // thread's VolumeReplica volumes), in VoxelScene order; empty: the objects'.
  std::vector<const VoxelVolume*> voxels;
  // Renderer type names for the keys 1, 2, 3 … (help line and HUD).
  std::vector<std::string> renderers;
  // A MouseDevice drives the tool: the burr follows the cursor.
  bool pointer = false;
  Pose pointerStart;
  double pointerDepthStep = 2e-4;  // m per Ctrl+wheel notch
  double toolRadius = 1e-3;        // m: the burr, for framing and picking
};

// What the HUD shows; filled by the caller from the haptic frames.
struct HudState {
  double hapticRate = 0.0;                     // Hz over the last second
  double computeP50Us = 0.0, computeP99Us = 0.0;  // per frame, over the last second
  double force = 0.0, torque = 0.0;            // N, N·m as sent
  bool torqueNotOutput = false;                // the device applies force only: the torque was rendered, not sent
  int contacts = 0;
  double removedMm3 = 0.0;
  std::string renderer;                        // type name of the renderer in charge
  std::string burr;                            // the burr milling, e.g. "round 0.6 mm" (key B swaps it)
  bool milling = false;                        // the milling switch
  bool swapPending = false;                    // a selected renderer has not taken over yet
  std::string status;                          // last notice (a swap, an error)
};

// Something the window asks the scene thread to do.
struct WindowCommand {
  enum class Kind { SelectRenderer, ToggleEnabled, ToggleMillable, NextBurrShape, Key } kind;
  int index = 0;  // SelectRenderer: 0 for key 1, …; Key: X3D's action key code (0: not an action key)
  // Key: a key going down or up, for the scene's KeySensors (every key but
  // Escape, as well as whatever the window itself does with it).
  bool press = true;
  std::string character;  // the key's character ("a", "A" with Shift, " "), empty for action and modifier keys
  enum class Modifier { None, Shift, Control, Alt } modifier = Modifier::None;
};

// The mouse's tool, for a MouseDevice.
struct PointerState {
  Pose pose;
  bool button = false;  // milling switch: left button held or Space toggled
};

class AppWindow {
public:
  virtual ~AppWindow() = default;
  // Handles pending input; false once the user closed the window (or Escape).
  virtual bool pollEvents() = 0;
  virtual std::vector<WindowCommand> takeCommands() = 0;
  virtual PointerState pointer() const = 0;

  // The scene's drawn fields changed while running: Transforms, Switches,
  // Materials, ClipPlanes (SceneDrawer::adoptView).
  virtual void sceneChanged(const SceneView& fresh) = 0;
  // Milled blocks of volume `index` (as VolumeReplica::apply gives them).
  virtual void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) = 0;
  // Draws the scene, the tools and the HUD, and shows the frame.
  virtual void draw(const std::vector<ToolView>& tools, const HudState& hud) = 0;
  // The latest frame as shown (rows from the top).
  virtual Image readPixels() = 0;

  virtual int width() const = 0;
  virtual int height() const = 0;
  virtual std::string glDescription() const = 0;
};

}  // namespace millsim
