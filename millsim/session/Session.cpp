#include "millsim/session/Session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "millsim/devices/HandDevice.h"
#include "millsim/devices/HapticsDevice.h"
#include "millsim/devices/MousePointer.h"
#include "millsim/devices/TrajectoryDevice.h"
#include "millsim/graphics/DrawnFields.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/run/FrameLog.h"
#include "millsim/run/LiveUpdates.h"
#include "millsim/run/RendererPool.h"
#include "millsim/run/RunSetup.h"
#include "millsim/session/RunControls.h"
#include "millsim/session/RunHud.h"
#include "millsim/session/RunSound.h"
#include "millsim/std/EventClock.h"
#include "millsim/volume/VolumeObject.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

namespace {

using Clock = std::chrono::steady_clock;

double nowSeconds() { return std::chrono::duration<double>(Clock::now().time_since_epoch()).count(); }

// The scene thread's period while a wall-clock run goes on, and the period
// of simulated time at which a simulated run does the same work.
constexpr double kSceneTickSeconds = 0.02;
// A servo loop silent this long has stopped calling (a device library that died).
constexpr double kServoSilenceSeconds = 1.0;

// A review opens no device: the loop writes the output here.
class RecordedOutput final : public DeviceDriver {
public:
  DeviceReading read(double, double) override { return {}; }
  void write(const glm::dvec3&, const glm::dvec3&) override {}
};

}  // namespace

LessonReport SessionResult::report(const std::string& sceneFile) const {
  return LessonReport{sceneFile, renderer, duration, stats.removedVolume, stats.peakForce, stats.peakTorque, regions, removal};
}

std::unique_ptr<Session> Session::openDevice(Scene& scene, const SessionOptions& options) {
  return std::unique_ptr<Session>(new Session(scene, options, Source::Device, nullptr, nullptr));
}

std::unique_ptr<Session> Session::replay(Scene& scene, const Trajectory& trajectory, const SessionOptions& options) {
  return std::unique_ptr<Session>(new Session(scene, options, Source::Trajectory, &trajectory, nullptr));
}

std::unique_ptr<Session> Session::review(Scene& scene, const RecordedRun& recorded, const SessionOptions& options) {
  return std::unique_ptr<Session>(new Session(scene, options, Source::Recorded, nullptr, &recorded));
}

Session::Session(Scene& scene, const SessionOptions& options, Source source, const Trajectory* trajectory,
                 const RecordedRun* recorded)
    : scene_(scene), options_(options), source_(source), recorded_(recorded) {
  std::string renderer = options.renderer;
  if (source == Source::Recorded) {
    const auto& frames = recorded->frames();
    if (frames.empty()) throw std::runtime_error("the recorded run has no frames");
    const auto& names = recorded->renderers();
    if (renderer.empty() && !names.empty()) {
      // The scene's own renderer when the run began with its type: its
      // fields (a lesson's stiffness), not a default node of that type.
      const std::string& first = names[std::size_t(std::max(frames.front().renderer, 0))];
      const HapticsDevice* device = findDevice(scene);
      const HapticsRendererNode* own = device ? device->hapticsRenderer.get().get() : nullptr;
      if (!own || own->typeName() != first) renderer = first;
    }
    // The review mills with the burr the run milled with, from its first frame.
    if (HapticsDevice* device = findDevice(scene)) toolNode_ = device->tool.get().get();
    if (toolNode_ && frames.front().tool >= 0) toolNode_->setGeometry(recorded->tools()[std::size_t(frames.front().tool)]);
    recordedRenderer_ = frames.front().renderer;
    recordedTool_ = frames.front().tool;
    recordedSwaps_ = options.renderer.empty() && names.size() > 1;
    recordedBurrSwaps_ = toolNode_ && recorded->tools().size() > 1;
  }
  run_ = std::make_unique<CompiledRun>(compileRun(scene, renderer));
  CompiledRun& run = *run_;
  if (options.rate != 0.0) run.settings.rate = options.rate;
  if (!(run.settings.rate > 0.0) || !std::isfinite(run.settings.rate))
    throw std::runtime_error("the haptic rate must be a positive number of Hz");
  run.settings.timing = options.timing;
  if (source != Source::Device) run.settings.logCapacity = 4;  // drained after every frame
  if (source == Source::Recorded) {  // the log's poses are world poses, calibration already applied
    run.settings.calibrationRotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
    run.settings.calibrationOffset = glm::dvec3(0.0);
  }

  // The lesson's regions and their starting material, measured before a
  // device is opened: a device waits for its first frame from then on (and a
  // watchdog or a library's servo loop counts that wait).
  regions_ = std::make_unique<RegionAccounting>(scene);

  std::unique_ptr<DeviceDriver> driver;
  HapticsDevice& device = *run.device;
  deviceName_ = device.typeName() + (device.defName().empty() ? "" : " '" + device.defName() + "'");
  if (source == Source::Device) {
    using DeviceSource = SessionOptions::DeviceSource;
    DeviceSource replaced = options.deviceSource;
    // A trajectory for a device that does not follow one replaces it.
    if (replaced == DeviceSource::Scene && options.trajectory && !device.followsTrajectory())
      replaced = DeviceSource::Trajectory;
    if (replaced == DeviceSource::Scene) {
      DriverOptions d{options.trajectory.get(), nullptr};
      const auto start = device.pointerStart();
      if (start && options.display == SessionOptions::Display::Window) {
        pointer_ = std::make_unique<PointerInput>(start->pose);
        d.pointer = pointer_.get();
      }
      driver = device.openDriver(d);
      const std::string opened = device.noteOpened();
      if (!opened.empty() && options.notices) *options.notices << opened << "\n";
      if (pointer_ && device.followsPointer()) {
        graphicsOptions_.pointer = pointer_.get();
        graphicsOptions_.pointerStart = start->pose;
        graphicsOptions_.pointerDepthStep = start->depthStep;
      }
    } else {
      driver = openReplacedDevice(device, replaced);
    }
  } else if (source == Source::Trajectory) {
    driver = device.followsTrajectory() ? device.openDriver(DriverOptions{trajectory})
                                        : makeTrajectoryDriver(*trajectory, false);
    const double t0 = trajectory->startTime();
    const double t1 = std::min(trajectory->endTime(), std::max(t0, options.until));
    // Frame times come from an integer count so that no rounding drifts.
    simulatedFrames_ = long(std::floor((t1 - t0) * run.settings.rate + 1e-9)) + 1;
  } else {
    driver = std::make_unique<RecordedOutput>();
  }
  naturalDuration_ = driver->naturalDuration();
  run.settings.outputsTorque = source == Source::Recorded ? !recorded->torqueNotOutput() : driver->outputsTorque();

  const bool window = options.display == SessionOptions::Display::Window;
  if (options.prepareRenderers || window || recordedSwaps_ || recordedBurrSwaps_)
    pool_ = std::make_unique<RendererPool>(scene, run, run.algorithm.get());
  rendererName_ = run.rendererName;
  loop_ = std::make_unique<HapticLoop>(*run.scene, std::move(run.algorithm), std::move(driver), run.settings);

  // Assessment counts on the scene thread, from blocks the loop publishes.
  if (!regions_->empty())
    for (std::size_t i = 0; i < regions_->volumeCount(); ++i) loop_->publishBlocks(i, regions_->channel(i));
  if (!options.soundOut.empty() || options.liveSound) {
    std::ostream discard(nullptr);
    sound_ = std::make_unique<RunSound>(RunSoundOptions{options.soundOut, options.liveSound, run.settings.rate},
                                        options.notices ? *options.notices : discard);
  }
  writer_ = std::make_unique<FrameLogWriter>(options.log);
  if (sound_) writer_->observe([this](const FrameRecord& f) { sound_->add(f); });
  // Simulated time counts each frame's blocks at its own time; a wall-clock
  // run counts what arrived by each tick (region accounting lags a tick).
  // A forbidden soft tissue (the pulp) is entered at the frame the drawn burr reaches it, in either.
  if (!regions_->empty())
    writer_->observe([this](const FrameRecord& f) {
      if (simulated_) regions_->update(f.t);
      if (f.out.flags != kSafetyStopped) regions_->burrAt(f.out.drawnTool, f.tool.head(), f.t);
    });
  writer_->observe([this](const FrameRecord& f) {
    if (f.out.flags != kSafetyStopped) last_ = f;  // not the stop row
  });
  if (window) {
    hud_ = std::make_unique<HudFeed>(run.settings.rate);
    writer_->observe([this](const FrameRecord& f) { hud_->add(f); });
  }
  events_ = std::make_unique<EventClock>(scene);
  live_ = std::make_unique<LiveUpdates>(run, *loop_);
}

// The window's pointer gives world poses: the scene device's calibration,
// which maps that device's own coordinates into the scene, does not apply to
// them. (A trajectory's rows are the device's coordinates, as replay reads
// them: a stand-in trajectory is calibrated as the device would be.)
void Session::moveInTheWorld() {
  run_->settings.calibrationRotation = glm::dquat(1.0, 0.0, 0.0, 0.0);
  run_->settings.calibrationOffset = glm::dvec3(0.0);
  run_->settings.positionScale = 1.0;
}

std::unique_ptr<DeviceDriver> Session::openReplacedDevice(const HapticsDevice& device,
                                                         SessionOptions::DeviceSource replaced) {
  using DeviceSource = SessionOptions::DeviceSource;
  const std::string sceneDevice = deviceName_;
  std::unique_ptr<DeviceDriver> driver;
  std::string kind;
  if (replaced == DeviceSource::Mouse) {
    if (options_.display != SessionOptions::Display::Window)
      throw DeviceError("the mouse follows the pointer in the window of `millsim run`, and there is none (no "
                        "DISPLAY, or --no-window); replace the device with a trajectory or a hand instead");
    const auto start = device.pointerStart();
    const HapticsDevice::PointerStart from = start ? *start : HapticsDevice::PointerStart{};
    moveInTheWorld();
    pointer_ = std::make_unique<PointerInput>(from.pose);
    driver = MousePointerFields::followPointer(*pointer_);
    graphicsOptions_.pointer = pointer_.get();
    graphicsOptions_.pointerStart = from.pose;
    graphicsOptions_.pointerDepthStep = from.depthStep;
    kind = "MouseDevice";
  } else {
    const std::shared_ptr<const Trajectory> trajectory = options_.trajectory ? options_.trajectory : device.trajectory();
    if (!trajectory)
      throw DeviceError(std::string("a ") + (replaced == DeviceSource::Hand ? "hand" : "trajectory") + " in place of " +
                        sceneDevice + " needs a trajectory to follow: pass --trajectory T.csv");
    if (replaced == DeviceSource::Hand) {
      const auto* hand = dynamic_cast<const HandDevice*>(&device);
      driver = makeHandDriver(*trajectory, hand ? hand->model() : HandModel{}, false);
      kind = "HandDevice";
    } else {
      driver = makeTrajectoryDriver(*trajectory, false);
      kind = "TrajectoryDevice";
    }
  }
  deviceName_ = kind + " in place of " + sceneDevice;
  if (options_.notices) *options_.notices << "the scene's " << sceneDevice << " is replaced by a " << kind << " for this run\n";
  return driver;
}

Session::~Session() {
  if (loop_) {
    loop_->stop();
    loop_->join();
  }
  if (graphics_) {
    try {
      graphics_->stop();
    } catch (const std::exception&) {  // a destructor cannot report it; finish() does
    }
  }
}

const std::string& Session::rendererName() const { return rendererName_; }
double Session::rate() const { return run_->settings.rate; }

std::vector<std::string> Session::preparedRenderers() const {
  return pool_ ? pool_->typeNames() : std::vector<std::string>{};
}

void Session::observe(std::function<void(const FrameRecord&)> observer) { writer_->observe(std::move(observer)); }

void Session::beginWallClock() {
  if (started_) throw std::logic_error("Session: already started");
  started_ = true;
  // The first tick, at 0, is before graphics reads the scene, so that its first frame shows it.
  events_->tick(0.0);
  startGraphics();
}

void Session::startGraphics() {
  if (options_.display == SessionOptions::Display::None) return;
  RunGraphicsOptions& g = graphicsOptions_;
  g.window = options_.display == SessionOptions::Display::Window;
  g.width = options_.width;
  g.height = options_.height;
  g.screenshot = options_.screenshot;
  g.title = options_.title;
  g.stallMs = options_.stallWindowMs;
  if (g.window) {
    controls_ = std::make_unique<RunControls>();
    g.controls = controls_.get();
    if (pool_) g.renderers = pool_->typeNames();
  }
  drawn_ = std::make_unique<FieldWatch>(drawnFields(scene_));
  shapeMeshes_ = std::make_unique<ShapeMeshCache>();
  graphics_ = std::make_unique<RunGraphics>(scene_, *run_->scene, *loop_, run_->tool, g);
  graphics_->start();  // its context and meshes are ready (or it threw) before the first haptic frame
}

void Session::start(double duration) {
  beginWallClock();
  sceneStart_ = nowSeconds();
  loop_->start(duration > 0.0 ? duration : naturalDuration_);
}

void Session::startServo(double duration) {
  beginWallClock();
  sceneStart_ = nowSeconds();
  loop_->startServo(duration > 0.0 ? duration : naturalDuration_);
}

bool Session::servoFrame() { return loop_->servoFrame(); }

SessionResult Session::runRealTime(double duration, const std::function<bool()>& interrupted) {
  start(duration);
  // A device library's servo loop that stops calling ends the run (finish() says so).
  while (!loop_->finished() && !loop_->servoSilentFor(kServoSilenceSeconds)) {
    std::this_thread::sleep_for(std::chrono::duration<double>(kSceneTickSeconds));
    if (interrupted && interrupted()) loop_->stop();
    tick();
  }
  return finish();
}

bool Session::finished() const { return loop_->finished(); }

void Session::stop() { loop_->stop(); }

double Session::naturalDuration() const { return naturalDuration_; }

void Session::tick() {
  if (controls_ && controls_->closed()) loop_->stop();
  const double t = nowSeconds() - sceneStart_;
  if (drain() > 0) publishFrame();
  if (sound_) sound_->pump();
  followWindow();
  if (!events_->empty()) events_->tick(t);
  followLiveFields();
}

std::size_t Session::drain() { return writer_->drain(*loop_); }

void Session::publishFrame() {
  publishToDevice(*run_->device, last_, run_->settings.rate);
  if (!simulated_) regions_->update(writer_->last().t);
  regions_->publishFields();
  publishRemovedVolumes(*run_);  // each VolumeObject's removedVolume follows the milling
}

void Session::followWindow() {
  if (!controls_) return;
  for (const WindowCommand& c : controls_->take()) {
    if (c.kind == WindowCommand::Kind::SelectRenderer && pool_) status_ = pool_->select(std::size_t(c.index), *loop_);
    // The keys set fields; LiveUpdates carries them to the haptic thread, as for a route.
    HapticsDevice& device = *run_->device;
    if (c.kind == WindowCommand::Kind::ToggleEnabled) device.enabled.set(!device.enabled.get());
    if (c.kind == WindowCommand::Kind::ToggleMillable)
      for (VolumeObject* v : scene_.nodesOfType<VolumeObject>()) v->millable.set(!v->millable.get());
    // B: the next burr shape, same dimensions; the pool swaps to it (or refuses it).
    if (c.kind == WindowCommand::Kind::NextBurrShape && device.tool.get()) {
      MillTool& t = *device.tool.get();
      t.shape.set(std::string(nextBurrShape(t.geometry().shape)));
      // A cone needs its narrow end narrower than the head: halve it if a round burr's dimensions do not say so.
      if (t.tipEndRadius.get() > t.tipRadius.get()) t.tipEndRadius.set(0.5f * t.tipRadius.get());
    }
    if (c.kind == WindowCommand::Kind::Key && events_->hasKeySensors())
      events_->key(KeyEvent{c.press, c.character, c.index, KeyEvent::Modifier(int(c.modifier))});
  }
}

void Session::followLiveFields() {
  if (std::string s = live_->poll(); !s.empty()) status_ = s;
  // What graphics draws follows the events, routes and keys: a new view when a drawn field changed.
  if (graphics_ && drawn_->changed()) {
    graphics_->publishView(readSceneView(scene_, nullptr, shapeMeshes_.get()));
    drawn_->mark();
  }
  if (!pool_) {
    loop_->collectRetired();
    return;
  }
  pool_->collect(*loop_);
  if (std::string s = pool_->followDeviceField(*loop_); !s.empty()) status_ = s;
  if (std::string s = pool_->followRendererFields(*loop_); !s.empty()) status_ = s;
  if (std::string s = pool_->followTool(*loop_); !s.empty()) status_ = s;
  if (controls_ && hud_) {
    HudState h = hud_->state(status_);
    h.swapPending = std::string(h.renderer) != pool_->typeName(pool_->current());
    controls_->setHud(h);
  }
}

bool Session::stepSimulated() {
  if (started_ && !simulated_) throw std::logic_error("Session::stepSimulated: the session runs on a wall clock");
  started_ = simulated_ = true;
  double eventTime = 0.0;
  if (source_ == Source::Recorded) {
    const auto& frames = recorded_->frames();
    if (std::size_t(nextSimulated_) >= frames.size()) return false;
    const RecordedFrame& f = frames[std::size_t(nextSimulated_)];
    if (f.t > options_.until) return false;
    repeatRecordedSwaps(f);
    loop_->stepRecorded(f.t, f.periodUs, f.device, f.button);
    eventTime = f.t - frames.front().t;
  } else {
    if (source_ == Source::Trajectory && nextSimulated_ >= simulatedFrames_) return false;
    loop_->stepSimulated();
    eventTime = double(nextSimulated_) / run_->settings.rate;
  }
  ++nextSimulated_;
  drain();
  // The scene's events (TimeSensors, interpolators) in the same simulated
  // time, ticked every frame as replay always has; a route from
  // removedVolume shows the progress.
  if (!events_->empty()) {
    publishRemovedVolumes(*run_);
    events_->advanceTo(eventTime);
  }
  // The rest of the scene thread's tick every 20 ms of simulated time.
  if (eventTime >= nextSceneTick_) {
    nextSceneTick_ = (std::floor(eventTime / kSceneTickSeconds + 1e-9) + 1.0) * kSceneTickSeconds;
    publishFrame();
    if (sound_) sound_->pump();
    followLiveFields();
  }
  return true;
}

void Session::repeatRecordedSwaps(const RecordedFrame& f) {
  // Swaps the run made (a renderer or tool column that changes) are made
  // again, at the same frames, with renderers prepared as the live run
  // prepared them (a --renderer override keeps to its renderer).
  if (recordedSwaps_ && f.renderer != recordedRenderer_) {
    pool_->collect(*loop_);
    const std::string& next = recorded_->renderers()[std::size_t(f.renderer)];
    const auto types = pool_->typeNames();
    const auto it = std::find(types.begin(), types.end(), next);
    if (it == types.end())
      throw std::runtime_error("the recorded run switches to renderer '" + next + "', which this scene cannot prepare");
    pool_->select(std::size_t(it - types.begin()), *loop_);
    recordedRenderer_ = f.renderer;
  }
  if (recordedBurrSwaps_ && f.tool != recordedTool_) {
    pool_->collect(*loop_);
    const ToolGeometry& tool = recorded_->tools()[std::size_t(f.tool)];
    toolNode_->setGeometry(tool);
    const std::string said = pool_->followTool(*loop_);
    if (!(pool_->tool() == tool)) throw std::runtime_error("the recorded run swaps to a burr this review cannot: " + said);
    recordedTool_ = f.tool;
  }
}

SessionResult Session::runSimulated() {
  if (source_ == Source::Device)
    throw std::logic_error("Session::runSimulated: a session of an opened device has no end; step it");
  while (stepSimulated()) {
  }
  return finish();
}

SessionResult Session::finish() {
  if (finishedCalled_) throw std::logic_error("Session::finish: called twice");
  finishedCalled_ = true;
  SessionResult result;
  if (simulated_ || !started_) {
    loop_->finish();  // the stop row: the zero output the device got
  } else {
    loop_->stop();
    loop_->join();  // a servo loop that stopped calling is said in failure()
  }
  drain();
  if (!simulated_) regions_->update(writer_->last().t);
  regions_->publishFields();
  if (sound_) {
    // Simulated frames are at n / rate, each one period long.
    sound_->finish(simulated_ ? std::optional<double>(double(loop_->stats().frames) / rate()) : std::nullopt);
    result.soundError = sound_->error();
    std::ostringstream summary;
    sound_->printSummary(summary);
    result.soundSummary = summary.str();
  }
  if (graphics_) {
    try {
      result.graphics = graphics_->stop();
    } catch (const std::exception& e) {
      result.graphicsError = e.what();
    }
    graphics_.reset();
  }
  result.stats = loop_->stats();
  result.renderer = rendererName_;
  result.device = deviceName_;
  result.rate = rate();
  result.duration = simulated_ ? double(result.stats.frames) / rate() : result.stats.elapsed;
  result.last = last_;
  result.regions = regions_->results();
  result.removal = regions_->summary();
  result.failure = loop_->failure();
  publishToDevice(*run_->device, last_, rate());
  publishRemovedVolumes(*run_);
  return result;
}

}  // namespace millsim
