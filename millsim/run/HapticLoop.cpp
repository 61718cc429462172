#include "millsim/run/HapticLoop.h"

#include <pthread.h>
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "millsim/devices/HapticsDevice.h"
#include "millsim/run/ThreadCpuTime.h"
#include "millsim/volume/BlockChannel.h"
#include "millsim/volume/VoxelScene.h"

namespace millsim {

namespace {

using Clock = std::chrono::steady_clock;

double microseconds(Clock::duration d) { return std::chrono::duration<double, std::micro>(d).count(); }

bool finitePose(const Pose& p) {
  return std::isfinite(p.position.x) && std::isfinite(p.position.y) && std::isfinite(p.position.z) &&
         std::isfinite(p.orientation.w) && std::isfinite(p.orientation.x) && std::isfinite(p.orientation.y) &&
         std::isfinite(p.orientation.z);
}

// Real-time priority if the process may have it (root, CAP_SYS_NICE or an
// rtprio limit); otherwise the loop runs at normal priority and says so.
bool requestRealTimePriority() {
  sched_param param{};
  param.sched_priority = std::max(1, sched_get_priority_max(SCHED_FIFO) - 1);
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

// Sleeps until shortly before `deadline`, then spins: the kernel's wake-up
// latency (tens to hundreds of µs) is larger than the accuracy a 1 kHz loop
// needs, and spinning the last stretch removes it.
void waitUntil(Clock::time_point deadline) {
  constexpr auto kSpin = std::chrono::microseconds(200);
  const auto sleepUntil = deadline - kSpin;
  if (Clock::now() < sleepUntil) {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(sleepUntil.time_since_epoch()).count();
    timespec ts{static_cast<time_t>(ns / 1000000000), static_cast<long>(ns % 1000000000)};
    // steady_clock is CLOCK_MONOTONIC on Linux (libstdc++).
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
  while (Clock::now() < deadline) {
  }
}

}  // namespace

LoopSettings LoopSettings::from(const HapticsDevice& device, const ToolGeometry& tool) {
  LoopSettings s;
  s.rate = double(device.desiredHapticsRate.get());
  s.calibrationRotation = glm::normalize(glm::dquat(device.orientationCalibration.get().quat()));
  s.calibrationOffset = glm::dvec3(device.positionCalibration.get());
  s.positionScale = double(device.positionScale.get());
  s.limits.forceLimit = device.forceLimit.get();
  s.limits.torqueLimit = device.torqueLimit.get();
  // From the node, not the opened driver: a review of a recorded run (which
  // opens no device) then repeats the run's safety decisions.
  s.limits.deviceHold = device.outputHoldTime();
  s.enabled = device.enabled.get();
  s.tool = tool;
  return s;
}

double LoopStats::p1Rate() const {
  const double p99 = periodUs.percentile(0.99);
  return p99 > 0.0 ? 1e6 / p99 : 0.0;
}

HapticLoop::HapticLoop(VoxelScene& scene, std::unique_ptr<HapticAlgorithm> algorithm,
                       std::unique_ptr<DeviceDriver> driver, const LoopSettings& settings)
    : scene_(scene),
      switch_(std::move(algorithm)),
      driver_(std::move(driver)),
      settings_(settings),
      safety_([&] {
        if (!(settings.rate > 0.0) || !std::isfinite(settings.rate))
          throw std::invalid_argument("the haptic rate must be a positive number of Hz");
        // A slow loop (replay at a low rate) must not trip the watchdog every frame.
        SafetyLimits l = settings.limits;
        l.watchdogTimeout = std::max(l.watchdogTimeout, 2.5 / settings.rate);
        return l;
      }()),
      records_(settings.logCapacity) {
  if (!driver_) throw std::invalid_argument("HapticLoop needs a device driver");
  enabled_ = settings.enabled;
  liveEnabled_.store(settings.enabled);
  liveForceLimit_.store(settings.limits.forceLimit);
  liveTorqueLimit_.store(settings.limits.torqueLimit);
  names_.push_back(switch_.current().name());
  currentName_ = names_.back().c_str();
  tool_ = sentTool_ = settings.tool;
  stats_.outputsTorque = settings.outputsTorque;
  if (!(settings.positionScale > 0.0) || !std::isfinite(settings.positionScale))
    throw std::invalid_argument("the device's positionScale must be a positive number");
}

HapticLoop::~HapticLoop() {
  stop();
  join();
  finish();
  collectRetired();
  if (Incoming* pending = incoming_.exchange(nullptr)) delete pending->algorithm;
}

void HapticLoop::publishBlocks(std::size_t index, BlockChannel& channel) {
  if (index >= scene_.volumeCount()) throw std::out_of_range("publishBlocks: no volume " + std::to_string(index));
  publishers_.push_back(Publisher{index, std::make_unique<BlockPublisher>(*scene_.volume(index).voxels, channel),
                                  scene_.volume(index).millEpoch});
}

bool HapticLoop::replaceRenderer(std::unique_ptr<HapticAlgorithm>& next, const ToolGeometry* tool) {
  if (!next) throw std::invalid_argument("HapticLoop::replaceRenderer: no algorithm");
  // Only this thread fills the mailbox, so an empty one stays empty until the
  // store below; the slot is written first, and the mailbox's release publishes it.
  if (incoming_.load(std::memory_order_acquire) != nullptr) return false;
  const std::string name = next->name();
  auto known = std::find(names_.begin(), names_.end(), name);
  if (known == names_.end()) known = names_.insert(names_.end(), name);
  if (tool) sentTool_ = *tool;
  Incoming& slot = incomingSlots_[nextSlot_];
  nextSlot_ ^= 1;
  slot.name = known->c_str();
  slot.tool = sentTool_;
  slot.algorithm = next.release();
  incoming_.store(&slot, std::memory_order_release);
  return true;
}

std::unique_ptr<HapticAlgorithm> HapticLoop::takeRetired() {
  return std::unique_ptr<HapticAlgorithm>(retired_.exchange(nullptr, std::memory_order_acq_rel));
}

void HapticLoop::setLive(bool enabled, double forceLimit, double torqueLimit) {
  liveEnabled_.store(enabled, std::memory_order_relaxed);
  liveForceLimit_.store(forceLimit, std::memory_order_relaxed);
  liveTorqueLimit_.store(torqueLimit, std::memory_order_relaxed);
  liveVersion_.fetch_add(1, std::memory_order_release);
}

void HapticLoop::frame(double t, double dt, double periodUs) {
  const FrameStart begin = frameStart();
  const DeviceReading reading = driver_->read(t, dt);
  // A missing or corrupt sample keeps the last good pose; the watchdog sees its age.
  if (reading.valid && finitePose(reading.pose)) {
    lastReading_ = reading;
    lastReading_.pose.orientation = glm::normalize(reading.pose.orientation);
    haveReading_ = true;
    sampleTime_ = t;
  }
  const Pose device{settings_.positionScale * (settings_.calibrationRotation * lastReading_.pose.position) +
                        settings_.calibrationOffset,
                    settings_.calibrationRotation * lastReading_.pose.orientation};
  advance(t, dt, periodUs, device, haveReading_ && lastReading_.button, begin);
}

void HapticLoop::stepRecorded(double t, double periodUs, const Pose& device, bool button) {
  const FrameStart begin = frameStart();
  haveReading_ = true;
  sampleTime_ = t;
  advance(t, frameDt(periodUs), periodUs, device, button, begin);
  stats_.elapsed = t;
}

double HapticLoop::frameDt(double periodUs) const {
  return std::clamp(periodUs * 1e-6, 0.25 / settings_.rate, 4.0 / settings_.rate);
}

HapticLoop::FrameStart HapticLoop::frameStart() const {
  return settings_.timing ? FrameStart{Clock::now(), threadCpuMicros()} : FrameStart{};
}

void HapticLoop::advance(double t, double dt, double periodUs, const Pose& device, bool button, FrameStart begin) {
  if (const std::uint32_t v = liveVersion_.load(std::memory_order_acquire); v != liveSeen_) {
    liveSeen_ = v;
    enabled_ = liveEnabled_.load(std::memory_order_relaxed);
    safety_.setLimits(liveForceLimit_.load(std::memory_order_relaxed), liveTorqueLimit_.load(std::memory_order_relaxed));
  }
  lastDevice_ = device;
  if (nextFrame_ == 0) switch_.current().reset(device);
  if (Incoming* next = incoming_.exchange(nullptr, std::memory_order_acq_rel)) {
    currentName_ = next->name;
    tool_ = next->tool;
    switch_.replace(std::unique_ptr<HapticAlgorithm>(next->algorithm), device);
  }

  HapticOutput out = switch_.step(scene_, HapticInput{device, dt, button});
  // Retired algorithms are freed by the scene thread, never here.
  if (!retiredHeld_) retiredHeld_ = switch_.takeRetired();
  if (retiredHeld_ && retired_.load(std::memory_order_acquire) == nullptr)
    retired_.store(retiredHeld_.release(), std::memory_order_release);

  // A non-round head mills along the drawn tool's axis (the pose the renderer shows and holds).
  if (button && out.burrCuts)
    stats_.removedVolume += tool_.round() ? scene_.mill(out.burrCentre, tool_.tipRadius)
                                          : scene_.mill(out.burrCentre, out.drawnTool.orientation, tool_.head());
  else  // the stamps a volume's millingBudget left for the next frames
    stats_.removedVolume += scene_.continueMilling();
  for (Publisher& p : publishers_) {
    const auto& v = scene_.volume(p.volume);
    static const std::vector<BlockOrigin> kNone;
    const bool fresh = v.millEpoch != p.epoch;
    p.epoch = v.millEpoch;
    // Publishing with nothing new retries blocks the full channel refused earlier.
    if (fresh || p.publisher->pending() > 0) p.publisher->publish(fresh ? v.changed.origins() : kNone);
  }

  SafeWrench w;
  if (enabled_ && haveReading_) {
    // Limits and ramps act on what the device gets: the scaled force.
    w = safety_.filter(settings_.positionScale * out.force, out.torque, t, sampleTime_);
  } else if (!haveReading_) {
    w.events = kSafetyWatchdog;  // nothing from the device yet: send nothing
  }
  const bool torqueHeld = !settings_.outputsTorque && w.torque != glm::dvec3(0.0);
  if (torqueHeld) w.events |= kSafetyTorqueNotOutput;
  out.flags |= w.events;
  const glm::dquat toRaw = glm::conjugate(settings_.calibrationRotation);
  driver_->write(toRaw * w.force, settings_.outputsTorque ? toRaw * w.torque : glm::dvec3(0.0));

  FrameRecord& r = newest_.back();
  r.frame = nextFrame_++;
  r.t = t;
  r.device = device;
  r.button = button;
  r.force = w.force;
  r.torque = w.torque;
  r.out = out;
  lastOut_ = out;
  r.cpuUs = settings_.timing ? threadCpuMicros() - begin.cpuUs : 0.0;
  r.computeUs = settings_.timing ? microseconds(Clock::now() - begin.wall) : 0.0;
  r.periodUs = periodUs;
  r.removedVolume = stats_.removedVolume;
  r.tool = tool_;
  r.renderer = currentName_;
  records_.push(r);
  newest_.publish();

  ++stats_.frames;
  stats_.periodUs.add(periodUs);
  stats_.computeUs.add(r.computeUs);
  stats_.computeCpuUs.add(r.cpuUs);
  stats_.preemptedFrames += r.computeUs - r.cpuUs > LoopStats::kPreemptedUs;
  stats_.overrunFrames += settings_.timing && r.cpuUs > 1e6 / settings_.rate;
  stats_.peakForce = std::max(stats_.peakForce, glm::length(w.force));
  stats_.peakTorque = std::max(stats_.peakTorque, glm::length(w.torque));
  stats_.maxContacts = std::max(stats_.maxContacts, out.contacts);
  stats_.contactFrames += out.contacts > 0;
  stats_.suppressed += (out.flags & kFlagNonFiniteSuppressed) != 0;
  stats_.torqueNotOutput += torqueHeld;
  if (stats_.firstForceAt < 0.0 && glm::length(w.force) > 1e-3) stats_.firstForceAt = t;  // felt, not rounding noise
}

void HapticLoop::stepSimulated() {
  const double dt = 1.0 / settings_.rate;
  const double t = nextSimulatedTime();
  frame(t, dt, dt * 1e6);
  stats_.elapsed = t;
}

void HapticLoop::stepSimulatedAfter(double period) {
  if (!(period > 0.0) || !std::isfinite(period))
    throw std::invalid_argument("HapticLoop::stepSimulatedAfter: the period must be a positive number of seconds");
  if (nextFrame_ > 0) stalled_ += period - 1.0 / settings_.rate;
  const double t = nextSimulatedTime();
  frame(t, frameDt(period * 1e6), period * 1e6);
  stats_.elapsed = t;
}

void HapticLoop::start(double duration) {
  if (thread_.joinable() || driverServo_) throw std::logic_error("HapticLoop::start: already running");
  finished_.store(false, std::memory_order_release);
  if (driver_->ownsServoLoop()) {
    startServo(duration);
    driverServo_ = true;
    stats_.deviceServo = true;
    driver_->startServo([this] { return servoFrame(); });
    return;
  }
  scene_.setLoopRunning(true);
  thread_ = std::thread([this, duration] { runRealTime(duration); });
}

void HapticLoop::join() {
  if (thread_.joinable()) thread_.join();
  if (!servoRun_) {
    scene_.setLoopRunning(false);
    return;
  }
  // A servo thread ends the run at its next call after stop(); one that
  // stopped calling gets no more calls (its library's contract, and the
  // driver's stopServo for a library MillSim started), so the device is
  // released here.
  const auto until = Clock::now() + std::chrono::seconds(2);
  while (!finished() && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  if (driverServo_) driver_->stopServo();
  if (!finished()) {
    if (failure_.empty()) failure_ = "the device's servo loop stopped calling before the run ended";
    endTimedRun();
  }
  servoRun_ = driverServo_ = false;
  scene_.setLoopRunning(false);
}

bool HapticLoop::servoSilentFor(double seconds) const {
  const auto now = Clock::now().time_since_epoch();
  const std::int64_t last = lastServoNs_.load(std::memory_order_relaxed);
  if (last == 0) return false;  // not a servo-driven run
  return !finished() && std::chrono::nanoseconds(now).count() - last > std::int64_t(seconds * 1e9);
}

void HapticLoop::runRealTime(double duration) {
  stats_.realTimePriority = requestRealTimePriority();
  duration_ = duration;
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / settings_.rate));
  clockStart_ = Clock::now();
  auto deadline = clockStart_;
  while (true) {
    waitUntil(deadline);
    const auto now = Clock::now();
    if (now - deadline > period / 2) ++stats_.missedDeadlines;
    if (!timedFrame(now)) break;
    deadline += period;
    // Fallen more than a period behind: skip the lost slots (counted as
    // missed) instead of bursting frames to catch up.
    const auto after = Clock::now();
    if (after > deadline + period) {
      const auto lost = (after - deadline) / period;
      stats_.missedDeadlines += long(lost);
      deadline += lost * period;
    }
  }
  endTimedRun();
}

bool HapticLoop::timedFrame(Clock::time_point now) {
  if (stopRequested_.load(std::memory_order_relaxed)) return false;
  const double t = std::chrono::duration<double>(now - clockStart_).count();
  if (t > duration_) return false;
  const double nominalUs = 1e6 / settings_.rate;
  const double periodUs = nextFrame_ == 0 ? nominalUs : microseconds(now - previousFrame_);
  previousFrame_ = now;
  try {
    frame(t, frameDt(periodUs), periodUs);
  } catch (const std::exception& e) {  // a renderer or driver bug must still stop the device cleanly
    failure_ = std::string("haptic frame failed: ") + e.what();
    return false;
  }
  stats_.elapsed = t;
  if (driver_->failed()) {
    failure_ = driver_->failure();
    return false;
  }
  return true;
}

void HapticLoop::endTimedRun() {
  finish();
  finished_.store(true, std::memory_order_release);
}

void HapticLoop::startServo(double duration) {
  if (thread_.joinable()) throw std::logic_error("HapticLoop::startServo: its own thread is running");
  duration_ = duration;
  servoOver_ = false;
  servoRun_ = true;
  scene_.setLoopRunning(true);
  lastServoNs_.store(std::chrono::nanoseconds(Clock::now().time_since_epoch()).count(), std::memory_order_relaxed);
  finished_.store(false, std::memory_order_release);
}

bool HapticLoop::servoFrame() {
  if (servoOver_) return false;
  const auto now = Clock::now();
  lastServoNs_.store(std::chrono::nanoseconds(now.time_since_epoch()).count(), std::memory_order_relaxed);
  if (nextFrame_ == 0) clockStart_ = now;
  // The library's scheduler keeps the time; a tick later than half a period is a missed deadline.
  else if (microseconds(now - previousFrame_) > 1.5e6 / settings_.rate) ++stats_.missedDeadlines;
  if (timedFrame(now)) return true;
  servoOver_ = true;
  endTimedRun();
  return false;
}

void HapticLoop::finish() {
  if (stopped_) return;
  stopped_ = true;
  driver_->stop();
  if (failure_.empty() && driver_->failed()) failure_ = driver_->failure();
  recordStop();
}

void HapticLoop::recordStop() {
  if (nextFrame_ == 0) return;  // nothing was ever sent
  FrameRecord& r = newest_.back();
  r.frame = nextFrame_++;
  r.t = stats_.elapsed;
  r.device = lastDevice_;
  r.button = false;
  r.force = glm::dvec3(0.0);
  r.torque = glm::dvec3(0.0);
  // The renderer's last state (graphics keep drawing the tool there), with
  // what the device really got: nothing.
  r.out = lastOut_;
  r.out.force = glm::dvec3(0.0);
  r.out.torque = glm::dvec3(0.0);
  r.out.flags = kSafetyStopped;
  r.out.burrCuts = false;
  r.computeUs = 0.0;
  r.cpuUs = 0.0;
  r.periodUs = 0.0;
  r.removedVolume = stats_.removedVolume;
  r.tool = tool_;
  r.renderer = currentName_;
  records_.push(r);
  newest_.publish();
}

LoopStats HapticLoop::stats() const {
  LoopStats s = stats_;
  s.safety = safety_.counters();
  s.device = driver_->counters();
  s.recordsDropped = records_.dropped();
  return s;
}

}  // namespace millsim
