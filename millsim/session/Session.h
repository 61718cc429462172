#pragma once
// Session: one run of a loaded scene, as a library object. It compiles the
// run (the device, its renderer, the VoxelScene, LoopSettings), opens what
// moves the tool, owns the haptic loop, and does the scene thread's part:
// the frame log, the device node's output fields, each VolumeObject's
// removedVolume, region accounting, the milling sound, the scene's events
// and routes, the live fields (LiveUpdates, RendererPool) and the
// graphics/window hand-off. At the end it gives the run's statistics and the
// lesson report. `millsim run`, `millsim replay` and `millsim render` are thin
// wrappers around it; an integrator embeds MillSim through it.
//
// What moves the tool is chosen when the session is made:
//   openDevice  the scene's device node, opened (hardware, a simulated hand,
//               the window's mouse);
//   replay      a trajectory (a simulated device follows it, a hardware
//               device's place is taken by it, open loop);
//   review      a recorded run's frames (RecordedRun.h), bit for bit.
// Who calls each haptic frame is chosen by how the session is driven, and
// every driver runs the same frame (HapticLoop) and the same scene tick:
//   start()          MillSim's own real-time thread at the device's rate —
//                    or, for a device whose library owns the servo loop
//                    (PhantomDevice: OpenHaptics' scheduler), that library's
//                    thread, which the driver hands servoFrame();
//   startServo()     a thread MillSim did not create (an integrator's own
//                    loop) calls servoFrame() once per tick;
//   stepSimulated()  simulated time on the calling thread (deterministic).
// With the first two the caller's thread is the scene thread: it calls
// tick() every ~20 ms until finished() (runRealTime does both), then
// finish(). stepSimulated() ticks the scene itself after every frame, as
// replay always has.
#include <functional>
#include <iosfwd>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "millsim/core/Scene.h"
#include "millsim/devices/RecordedRun.h"
#include "millsim/devices/Trajectory.h"
#include "millsim/lesson/RegionAccounting.h"
#include "millsim/run/HapticLoop.h"
#include "millsim/session/LessonReport.h"
#include "millsim/session/RunGraphics.h"

namespace millsim {

class EventClock;
class FieldWatch;
class HapticsDevice;
class FrameLogWriter;
class HudFeed;
class LiveUpdates;
class RendererPool;
class RunControls;
class RunSound;
class ShapeMeshCache;
struct CompiledRun;

struct SessionOptions {
  std::string renderer;   // a default renderer of this registered type instead of the device's
  double rate = 0.0;      // Hz; 0: the device's desiredHapticsRate
  bool timing = true;     // measure compute time per frame (replay leaves it off: the log then repeats byte for byte)
  // openDevice: a simulated device follows this instead of its url; any other
  // device is replaced by it (played open loop, as replay does).
  std::shared_ptr<const Trajectory> trajectory;
  // openDevice: what drives the run in place of the scene's device node, so
  // that one lesson file serves students at a device and tests or
  // demonstrations without one. The node's renderer, tool, limits and
  // calibration stay (trajectory rows are the device's coordinates, as replay
  // reads them; the mouse moves in the scene's own). Trajectory plays
  // `trajectory` (or the device's own) open loop, Hand pulls a simulated hand
  // along it (the HandDevice's fields, else HandDevice's defaults), Mouse
  // follows the window's mouse (needs Display::Window).
  enum class DeviceSource { Scene, Trajectory, Hand, Mouse };
  DeviceSource deviceSource = DeviceSource::Scene;
  // replay and review: stop after this trajectory time (s).
  double until = std::numeric_limits<double>::infinity();
  std::ostream* log = nullptr;      // the frame log (FrameLog.h), one row a frame; written on the scene thread
  std::string soundOut;             // WAV of the milling sound; empty: none
  bool liveSound = false;           // play it on the audio device (a notice and silence without one)
  enum class Display { None, Offscreen, Window };
  Display display = Display::None;  // graphics: none, an OSMesa context, or the window (needs a display)
  int width = 512, height = 512;
  std::string screenshot;           // PNG of the last graphics frame, written at finish()
  std::string title;                // the window's
  // Compile every renderer type before the first frame, so that keys 1-3 or a
  // new node in the device's hapticsRenderer field swap to a ready one (on
  // with a window; a review whose log swaps renderers or burrs prepares them anyway).
  bool prepareRenderers = false;
  int stallWindowMs = 0;            // test hook: the window thread sleeps this long every frame
  std::ostream* notices = nullptr;  // one-line notices (no audio device, which device AnyDevice opened); null: none
};

struct SessionResult {
  std::string renderer;  // the renderer the run started with
  std::string device;    // "HandDevice 'HAND'"
  double rate = 0.0;     // Hz, desired
  LoopStats stats;
  double duration = 0.0;  // s: the run's length (simulated: frames / rate)
  FrameRecord last;       // the last haptic frame (the log then has the stop row)
  std::vector<RegionResult> regions;
  RemovalSummary removal;  // outside the targets, per tissue, time to completion
  std::optional<RunGraphicsStats> graphics;
  std::string soundSummary;  // one line, or empty without sound
  // Why the device or the loop ended the run early (the device failed, a
  // frame threw, a servo loop stopped calling); empty when it ran its course
  // or was stopped.
  std::string failure;
  std::string graphicsError;  // graphics failed while running or could not write the screenshot
  std::string soundError;     // the WAV could not be written
  bool ok() const { return failure.empty() && graphicsError.empty() && soundError.empty(); }

  LessonReport report(const std::string& sceneFile) const;
};

class Session {
public:
  // Each throws std::runtime_error (or DeviceError, GraphicsError) with a
  // message for the user when the scene has no device or renderer, the
  // renderer type is unknown, the device cannot be opened, or a file
  // cannot be written. The scene must outlive the session.
  static std::unique_ptr<Session> openDevice(Scene& scene, const SessionOptions& options);
  static std::unique_ptr<Session> replay(Scene& scene, const Trajectory& trajectory, const SessionOptions& options);
  static std::unique_ptr<Session> review(Scene& scene, const RecordedRun& recorded, const SessionOptions& options);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // --- Driver 1: MillSim's own real-time thread.
  // Starts graphics (if any; it is ready before the first frame), then the
  // haptic thread, for `duration` s (0: what the device has to do — a
  // trajectory's length, or until stop() for a device a person holds).
  void start(double duration = 0.0);
  // start(), tick() every 20 ms until finished() or `interrupted()` says so, finish().
  SessionResult runRealTime(double duration = 0.0, const std::function<bool()>& interrupted = {});

  // --- Driver 2: a servo loop another library owns (one call per device tick).
  // Scene thread: starts graphics and readies the loop; the first
  // servoFrame() is time 0.
  void startServo(double duration = 0.0);
  // The foreign thread: one haptic frame at its wall-clock time. Wait-free,
  // no allocation. False once the run is over (duration reached, stop(), the
  // device failed): the device has been released, and later calls do nothing.
  bool servoFrame();

  // --- Driver 3: simulated time on the calling thread (deterministic).
  // One frame and the scene tick after it; false, doing nothing, when a
  // replay's trajectory or a review's frames are done. An openDevice session
  // steps at t = n / rate until stopped.
  bool stepSimulated();
  // Every frame of the replay or review, then finish().
  SessionResult runSimulated();

  // Scene thread, while a real-time or servo run goes on (~every 20 ms): drains
  // the frame log, sets the device's output fields, counts the regions, feeds
  // the sound, does the window's commands, ticks the scene's events and
  // carries live field changes to the haptic thread.
  void tick();
  bool finished() const;
  void stop();  // any thread: the run ends after the current frame

  // Scene thread, once, after the last frame: joins, drains, stops graphics
  // and sound, publishes the final fields and returns the results.
  SessionResult finish();

  // The scene the session runs, and its compiled run (for tests and benchmarks).
  Scene& scene() { return scene_; }
  HapticLoop& loop() { return *loop_; }
  const std::string& rendererName() const;
  const std::string& deviceName() const { return deviceName_; }
  double rate() const;
  // How long the device has something to do (s): a trajectory's length, or
  // infinity for a device a person holds (start's and startServo's default).
  double naturalDuration() const;
  // Also hands every frame record, in order, to `observer` on the scene thread
  // (as it drains the log). Before the first frame.
  void observe(std::function<void(const FrameRecord&)> observer);
  // Renderers prepared for live swapping (empty without prepareRenderers).
  std::vector<std::string> preparedRenderers() const;
  // The latest notice for the user (a renderer swap, a live field change).
  const std::string& status() const { return status_; }

private:
  enum class Source { Device, Trajectory, Recorded };
  Session(Scene& scene, const SessionOptions& options, Source source, const Trajectory* trajectory,
          const RecordedRun* recorded);
  // Before the first wall-clock frame: the events' first tick, then graphics.
  void beginWallClock();
  void startGraphics();
  // openDevice with SessionOptions::deviceSource other than Scene: the driver in the device node's place.
  std::unique_ptr<DeviceDriver> openReplacedDevice(const HapticsDevice& device, SessionOptions::DeviceSource replaced);
  // The mouse as a stand-in moves in the world: no calibration.
  void moveInTheWorld();
  std::size_t drain();
  // The newest frame into the scene: device fields, regions, removed volumes.
  void publishFrame();
  // The window's commands and keys (scene thread).
  void followWindow();
  // Live field changes to the haptic thread, a new view to graphics, renderer swaps, the HUD.
  void followLiveFields();
  // Before a review frame: the swaps the recorded run made at this frame.
  void repeatRecordedSwaps(const RecordedFrame& f);

  Scene& scene_;
  SessionOptions options_;
  Source source_;
  const RecordedRun* recorded_ = nullptr;
  std::unique_ptr<CompiledRun> run_;
  std::string rendererName_, deviceName_;
  std::unique_ptr<HapticLoop> loop_;
  std::unique_ptr<PointerInput> pointer_;
  std::unique_ptr<RunControls> controls_;
  std::unique_ptr<RendererPool> pool_;
  std::unique_ptr<RegionAccounting> regions_;
  std::unique_ptr<RunSound> sound_;
  std::unique_ptr<FrameLogWriter> writer_;
  std::unique_ptr<HudFeed> hud_;
  std::unique_ptr<EventClock> events_;
  std::unique_ptr<FieldWatch> drawn_;  // what graphics draws from
  std::unique_ptr<ShapeMeshCache> shapeMeshes_;
  std::unique_ptr<LiveUpdates> live_;
  std::unique_ptr<RunGraphics> graphics_;
  RunGraphicsOptions graphicsOptions_;
  std::string status_;
  FrameRecord last_;        // the newest haptic frame drained (never the stop row)
  double naturalDuration_ = 0.0;
  bool simulated_ = false;
  bool started_ = false, finishedCalled_ = false;
  double sceneStart_ = 0.0;  // steady clock, s: the run's 0 for the scene's events
  // Simulated stepping: frames to go, and where the review is.
  long simulatedFrames_ = 0, nextSimulated_ = 0;
  double nextSceneTick_ = 0.0;
  int recordedRenderer_ = 0, recordedTool_ = 0;
  bool recordedSwaps_ = false, recordedBurrSwaps_ = false;
  MillTool* toolNode_ = nullptr;
};

}  // namespace millsim
