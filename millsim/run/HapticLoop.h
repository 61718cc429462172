#pragma once
// HapticLoop: runs one device at its haptic rate. Each frame reads the device,
// steps the renderer (through a RendererSwitch, so the algorithm can be
// swapped live), mills, passes the wrench through the safety layer, writes it
// to the device, and publishes the frame for logs and graphics.
//
// The same frame() serves both clocks:
//  - stepSimulated: one frame at t = n / rate on the calling thread (replay, tests);
//    bit-reproducible because nothing reads the wall clock unless timing is on;
//  - start: a dedicated real-time thread, sleep-then-spin to each deadline;
//  - startServo + servoFrame: a thread another library owns (a device
//    vendor's servo scheduler) calls one frame per device tick.
//
// Hand-offs are wait-free: frame records go into an SPSC ring the scene
// thread drains (a full ring drops records and counts them), the newest
// frame goes into a triple buffer for graphics, milled blocks into one
// BlockChannel per volume, and a new renderer arrives through an atomic
// mailbox. The haptic thread never waits on another thread and does not
// allocate once running (algorithms retire through a mailbox to be freed on
// the scene thread).
#include <atomic>
#include <chrono>
#include <deque>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "millsim/driver/DeviceDriver.h"
#include "millsim/driver/SafetyLayer.h"
#include "millsim/haptics/HapticsRenderer.h"
#include "millsim/run/FrameHistogram.h"
#include "millsim/run/RendererSwitch.h"
#include "millsim/run/SpscRing.h"
#include "millsim/driver/TripleBuffer.h"

namespace millsim {

class BlockChannel;
class BlockPublisher;
class VoxelScene;
class HapticsDevice;

// One frame, as logged (docs: the replay log format).
struct FrameRecord {
  long frame = 0;
  double t = 0.0;         // s since the run started
  Pose device;            // calibrated world pose the renderer saw
  bool button = false;
  // N, world frame, as sent (after the safety layer): positionScale times the
  // renderer's force, so that the work done at the hand is the scene's.
  glm::dvec3 force{0.0};
  // N·m about the burr centre, after the safety layer; a force-only device
  // was not sent it (flag kSafetyTorqueNotOutput).
  glm::dvec3 torque{0.0};
  HapticOutput out;       // the renderer's output (flags include the safety events)
  double computeUs = 0.0; // device I/O + step + milling, wall clock; 0 unless timing is on
  double cpuUs = 0.0;     // the same on the thread's CPU clock: less than computeUs when the OS took the CPU
  double periodUs = 0.0;  // time since the previous frame started
  double removedVolume = 0.0;  // m³ milled so far
  ToolGeometry tool;           // the burr that milled this frame (a live burr swap changes it)
  // The renderer in charge (during a cross-fade, the one fading in): its
  // HapticAlgorithm::name(), interned by the loop for the loop's lifetime.
  const char* renderer = "";
};

// The loop's fixed parameters, compiled from the device node on the scene thread.
struct LoopSettings {
  double rate = 1000.0;  // Hz
  glm::dquat calibrationRotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 calibrationOffset{0.0};
  // Scene metres per device metre (HapticsDevice::positionScale): scene
  // position = scale · (rotation · raw) + offset. Energy conserved: the
  // device gets scale × the renderer's force, and a scene stiffness k is felt
  // as scale² · k (docs/devices.md, Workspace mapping).
  double positionScale = 1.0;
  // The opened device applies torque (DeviceDriver::outputsTorque); a review
  // takes it from its log's flags.
  bool outputsTorque = true;
  SafetyLimits limits;
  bool enabled = true;
  ToolGeometry tool;          // the burr the first renderer was compiled for, and mills with
  bool timing = true;         // measure compute time per frame
  std::size_t logCapacity = 1 << 14;  // frames the scene thread may fall behind by

  // From a device node's fields (rate, limits, calibration, enabled) and its tool.
  static LoopSettings from(const HapticsDevice& device, const ToolGeometry& tool);
};

struct LoopStats {
  long frames = 0;
  long missedDeadlines = 0;    // frames started > half a period late, plus skipped slots
  double elapsed = 0.0;        // s, first to last frame
  FrameHistogram periodUs, computeUs, computeCpuUs;
  // Frames whose wall time exceeded their CPU time by more than kPreemptedUs:
  // the thread lost the CPU mid-frame (preemption, a host's steal), so their
  // wall time measures the machine, not the frame.
  static constexpr double kPreemptedUs = 10.0;
  long preemptedFrames = 0;
  // Frames whose own computation, on the thread's CPU, took longer than a
  // period: late by MillSim's doing on any host. A missed deadline may be the
  // host's (a late wake-up, a foreign servo thread called late); these are not.
  long overrunFrames = 0;
  double peakForce = 0.0, peakTorque = 0.0;
  int maxContacts = 0;
  long contactFrames = 0;
  long suppressed = 0;         // frames whose renderer output was non-finite
  double firstForceAt = -1.0;  // s; the first frame that sent more than 1 mN (-1: none)
  long torqueNotOutput = 0;    // frames with torque the device could not output (logged, not sent)
  bool outputsTorque = true;   // LoopSettings::outputsTorque
  double removedVolume = 0.0;  // m³
  SafetyCounters safety;
  DeviceCounters device;
  std::uint64_t recordsDropped = 0;
  bool realTimePriority = false;  // SCHED_FIFO was granted
  bool deviceServo = false;       // the device library's servo thread ran the frames (its priority is the library's)

  double meanRate() const { return elapsed > 0.0 && frames > 1 ? double(frames - 1) / elapsed : 0.0; }
  // The rate that 99 % of frames met or beat: 1 / (99th-percentile period).
  double p1Rate() const;
};

class HapticLoop {
public:
  HapticLoop(VoxelScene& scene, std::unique_ptr<HapticAlgorithm> algorithm, std::unique_ptr<DeviceDriver> driver,
             const LoopSettings& settings);
  ~HapticLoop();  // stops and joins a running thread
  HapticLoop(const HapticLoop&) = delete;
  HapticLoop& operator=(const HapticLoop&) = delete;

  // Before running: publish milled blocks of the scene's volume `index` into
  // `channel` (the graphics side drains it into its VolumeReplica; region
  // accounting counts from it). A volume may have several channels.
  void publishBlocks(std::size_t index, BlockChannel& channel);

  // Simulated time on this thread: the next frame at t = frame / rate.
  void stepSimulated();
  // Simulated time on this thread: the next frame `period` seconds after the
  // previous one, as a real-time loop sees a stall (the renderer steps over
  // frameDt, the device and the safety layer see the whole gap); later frames
  // keep the delay.
  void stepSimulatedAfter(double period);
  // Simulated time on this thread: a frame of a recorded run (RecordedRun),
  // with the world device pose, button, time and period its log holds. The
  // driver is written to but not read, and the calibration is not applied
  // (the log's pose is already calibrated), so the renderer gets exactly the
  // inputs it got in the run.
  void stepRecorded(double t, double periodUs, const Pose& device, bool button);
  // The time step a frame integrates over after `periodUs` of real time:
  // what really passed, within reason (a quarter to four periods).
  double frameDt(double periodUs) const;
  // Real time on a new thread, until `duration` seconds have passed, stop()
  // is called, or the device fails. Returns at once.
  // A driver whose library owns the servo loop (DeviceDriver::ownsServoLoop)
  // gets servoFrame() to call instead: no thread of MillSim's runs.
  void start(double duration);
  // A servo loop another library owns: startServo() on the scene thread,
  // then servoFrame() once per device tick on that library's thread, which
  // is the haptic thread from then on. The first call is t = 0; each frame
  // integrates over the time since the previous call, as the real-time
  // thread's do. Returns false once the run is over (`duration` passed,
  // stop(), the device failed, a frame threw): the loop has then finished
  // (the device released) and later calls do nothing.
  void startServo(double duration);
  bool servoFrame();
  // A servo loop that has made no frame for `seconds` (since startServo, or
  // since its last frame) while the run is not over: its library stopped
  // calling. Any thread; wait-free.
  bool servoSilentFor(double seconds) const;
  void stop() { stopRequested_.store(true, std::memory_order_relaxed); }
  // Waits for the run's end. A servo-driven run (startServo, or a driver
  // whose library owns the loop) gets up to 2 s after stop() for its next
  // call; then the library's loop is stopped, the device released here and
  // failure() says the servo loop stopped calling.
  void join();
  bool finished() const { return finished_.load(std::memory_order_acquire); }
  // Zeroes the device's output and releases it. The real-time thread does
  // this itself when it ends; call it after simulated runs (the destructor
  // does too). Idempotent.
  void finish();

  // One thread but the haptic one (the scene thread): the algorithm takes
  // over at the next frame, cross-faded (RendererSwitch). False, and `next`
  // untouched, if the previous swap is still pending. `tool` is the burr
  // `next` was compiled for: from the frame it takes over, the loop mills
  // with it and records it (a burr swap is a renderer swap with a new tool);
  // without one the current burr stays.
  bool replaceRenderer(std::unique_ptr<HapticAlgorithm>& next, const ToolGeometry* tool = nullptr);
  bool replaceRenderer(std::unique_ptr<HapticAlgorithm>&& next, const ToolGeometry* tool = nullptr) {
    return replaceRenderer(next, tool);
  }
  // The burr the loop mills with now, or will from the pending swap on (scene thread).
  const ToolGeometry& toolAfterSwaps() const { return sentTool_; }
  // Any thread but the haptic one: the device node's live fields (enabled,
  // forceLimit, torqueLimit), applied from the next frame on. Wait-free.
  void setLive(bool enabled, double forceLimit, double torqueLimit);

  // Scene thread: an algorithm the haptic thread has retired (or null), to be
  // kept for a later swap back or freed off the haptic thread.
  std::unique_ptr<HapticAlgorithm> takeRetired();
  void collectRetired() { takeRetired().reset(); }

  // The scene thread drains these; graphics reads the snapshot.
  SpscRing<FrameRecord>& records() { return records_; }
  TripleBuffer<FrameRecord>& newest() { return newest_; }

  // Complete after join() or between simulated frames.
  LoopStats stats() const;
  // The scene the loop steps and mills, for use between simulated frames on
  // the thread that steps them (a benchmark compiling a renderer against it).
  VoxelScene& scene() { return scene_; }
  // Why the device stopped the run (empty if it did not).
  const std::string& failure() const { return failure_; }
  const LoopSettings& settings() const { return settings_; }

private:
  void frame(double t, double dt, double periodUs);
  // When a frame started, on the wall and the thread's CPU clock (timing).
  struct FrameStart {
    std::chrono::steady_clock::time_point wall;
    double cpuUs = 0.0;
  };
  FrameStart frameStart() const;
  // Everything after reading the device: live fields, swap, step, milling,
  // safety, output, record.
  void advance(double t, double dt, double periodUs, const Pose& device, bool button, FrameStart begin);
  // After the device's stop(): logs the zero output it received.
  void recordStop();
  void runRealTime(double duration);
  // One frame at `now` of a wall-clock run that started at clockStart_
  // (the real-time thread and servoFrame); false when the run is over.
  bool timedFrame(std::chrono::steady_clock::time_point now);
  // After the last timed frame: releases the device and says so.
  void endTimedRun();

  VoxelScene& scene_;
  RendererSwitch switch_;
  std::unique_ptr<DeviceDriver> driver_;
  LoopSettings settings_;
  SafetyLayer safety_;
  LoopStats stats_;

  DeviceReading lastReading_;
  Pose lastDevice_;        // for the stop row
  HapticOutput lastOut_;
  bool haveReading_ = false;
  double sampleTime_ = 0.0;
  long nextFrame_ = 0;
  double stalled_ = 0.0;  // s; simulated time lost to stepSimulatedAfter's stalls
  double nextSimulatedTime() const { return double(nextFrame_) / settings_.rate + stalled_; }
  // Every consumer of milled blocks (graphics, region accounting), each with
  // the volume it follows and the mill epoch it last saw.
  struct Publisher {
    std::size_t volume;
    std::unique_ptr<BlockPublisher> publisher;
    std::uint64_t epoch;
  };
  std::vector<Publisher> publishers_;

  SpscRing<FrameRecord> records_;
  TripleBuffer<FrameRecord> newest_;
  // A swap in flight: the algorithm with its name and burr. Two slots used in
  // turn, so the scene thread never writes the slot the haptic thread may
  // still be reading (it reuses a slot only after the other one was taken,
  // which happens in a later frame than the read).
  struct Incoming {
    HapticAlgorithm* algorithm = nullptr;
    const char* name = "";
    ToolGeometry tool;
  };
  Incoming incomingSlots_[2];
  int nextSlot_ = 0;                       // scene thread
  ToolGeometry sentTool_;                  // scene thread: the burr of the newest swap sent
  std::atomic<Incoming*> incoming_{nullptr};
  std::atomic<HapticAlgorithm*> retired_{nullptr};
  ToolGeometry tool_;                      // haptic thread: the burr that mills
  std::unique_ptr<HapticAlgorithm> retiredHeld_;  // waiting for the retired mailbox to empty
  // Renderer names for FrameRecord::renderer: interned by the scene thread (a
  // deque never moves its strings), handed over with the algorithm.
  std::deque<std::string> names_;
  const char* currentName_ = "";

  // Live fields (setLive): written by the scene thread, read at each frame.
  std::atomic<bool> liveEnabled_{true};
  std::atomic<double> liveForceLimit_{0.0}, liveTorqueLimit_{0.0};
  std::atomic<std::uint32_t> liveVersion_{0};
  std::uint32_t liveSeen_ = 0;
  bool enabled_ = true;  // the haptic thread's copy

  // Wall-clock runs (real-time thread, servo): the haptic thread's own.
  std::chrono::steady_clock::time_point clockStart_, previousFrame_;
  double duration_ = 0.0;
  bool servoOver_ = false;
  bool servoRun_ = false;     // scene thread: startServo was called (join waits for the servo thread)
  bool driverServo_ = false;  // scene thread: the driver's library calls servoFrame
  // Steady-clock nanoseconds of the last servo frame (or startServo): servoSilentFor.
  std::atomic<std::int64_t> lastServoNs_{0};

  std::thread thread_;
  std::atomic<bool> stopRequested_{false};
  std::atomic<bool> finished_{false};
  std::string failure_;
  bool stopped_ = false;
};

}  // namespace millsim
