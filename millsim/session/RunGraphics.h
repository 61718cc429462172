#pragma once
// The graphics thread of a Session (millsim run): the window (libmillsim_window) when
// there is a display, else an offscreen OSMesa context; its own copy of the
// voxels (one VolumeReplica per volume, fed by the haptic thread's
// BlockChannels), drawing the newest haptic frame at its own rate with the
// same SceneDrawer either way. The haptic thread never waits for it: it only
// pushes blocks into fixed rings and publishes frames into a triple buffer
// (HapticLoop.h). With a window, keys and HUD numbers pass through
// RunControls (scene thread) and the mouse through PointerInput (MouseDevice).
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "millsim/devices/MouseDevice.h"
#include "millsim/driver/TripleBuffer.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/graphics/Image.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/volume/DirtyBlocks.h"

namespace millsim {
class BlockChannel;
class VoxelScene;
class Scene;
class VolumeReplica;
}  // namespace millsim

namespace millsim {

class RunControls;

struct RunGraphicsOptions {
  int width = 512, height = 512;
  double rate = 30.0;                 // frames per second to aim for
  std::filesystem::path screenshot;   // written after the last frame if not empty
  // The window instead of offscreen drawing (needs controls).
  bool window = false;
  std::string title;
  std::vector<std::string> renderers;  // keys 1, 2, 3 …
  RunControls* controls = nullptr;
  PointerInput* pointer = nullptr;     // a MouseDevice's input, fed from the window's mouse
  Pose pointerStart;
  double pointerDepthStep = 2e-4;
  // Test hook (MILLSIM_TEST_STALL_WINDOW_MS): the window thread sleeps this
  // long every frame, to show that the haptic thread does not wait for it.
  int stallMs = 0;
};

struct RunGraphicsStats {
  long frames = 0;
  double meshSeconds = 0.0;                // the renderer made and its first frame drawn: every volume meshed
  double meanMs = 0.0, p95Ms = 0.0;        // all frames
  double meanUpdateMs = 0.0;               // frames that re-meshed milled blocks
  long updateFrames = 0;
  std::string gl;                          // GL version and renderer
  bool window = false;
  double firstFrameSeconds = 0.0;          // from start() to the first frame shown
  int width = 0, height = 0;               // the frame's size
  std::string screenshot;                  // where the last frame was written (empty: not asked for)
};

class RunGraphics {
public:
  RunGraphics(const Scene& scene, VoxelScene& haptic, HapticLoop& loop, const ToolGeometry& tool,
              const RunGraphicsOptions& options);
  ~RunGraphics();

  // Scene thread, before the haptic loop starts: copies the voxels, connects
  // the block channels, starts the thread and waits until its context and
  // meshes are ready. Throws GraphicsError (no OSMesa, bad size) if not.
  void start();
  // Scene thread, after the haptic loop ended: draws the final frame, writes
  // the screenshot and joins. Throws GraphicsError if the screenshot fails.
  RunGraphicsStats stop();
  // Scene thread, while running: the scene's drawn fields changed (an event
  // moved a Transform, chose a Switch child, changed a Material or a
  // ClipPlane). Wait-free: a triple buffer, whose newest view the graphics
  // thread adopts at its next frame (SceneDrawer::adoptView).
  void publishView(SceneView view) {
    views_.back() = std::move(view);
    views_.publish();
  }

private:
  void run();
  void runWindow();
  // Both paths' frame loop: applies milled blocks (volumeChanged), draws at
  // options_.rate until stop(), draws the final state, writes the screenshot
  // and fills the frame statistics.
  void paceFrames(const std::function<void(std::size_t, const std::vector<BlockOrigin>&)>& volumeChanged,
                  const std::function<void()>& drawFrame, const std::function<Image()>& screenshot);

  const Scene& scene_;
  VoxelScene& haptic_;
  HapticLoop& loop_;
  ToolGeometry tool_;
  RunGraphicsOptions options_;
  TripleBuffer<SceneView> views_;
  std::vector<std::unique_ptr<BlockChannel>> channels_;
  std::vector<std::unique_ptr<VolumeReplica>> replicas_;
  std::chrono::steady_clock::time_point startTime_;
  std::thread thread_;
  std::atomic<int> state_{0};  // 0 starting, 1 ready, 2 failed
  std::atomic<bool> stop_{false};
  std::string error_;
  RunGraphicsStats stats_;
};

}  // namespace millsim
