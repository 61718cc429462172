#include "measure/ClosedLoop.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

namespace millsim::measure {

namespace {

// Passes the hand's samples through, marking some invalid, and remembers the
// true pose of each frame for the passivity observer.
class DroppingDriver final : public DeviceDriver {
public:
  DroppingDriver(std::unique_ptr<DeviceDriver> inner, double fraction, std::uint64_t seed, Pose& truePose)
      : inner_(std::move(inner)), fraction_(fraction), rng_(seed), truePose_(truePose) {}
  DeviceReading read(double t, double dt) override {
    DeviceReading r = inner_->read(t, dt);
    truePose_ = r.pose;
    if (fraction_ > 0.0 && std::uniform_real_distribution<double>(0.0, 1.0)(rng_) < fraction_) r.valid = false;
    return r;
  }
  void write(const glm::dvec3& f, const glm::dvec3& t) override { inner_->write(f, t); }
  double naturalDuration() const override { return inner_->naturalDuration(); }

private:
  std::unique_ptr<DeviceDriver> inner_;
  double fraction_;
  std::mt19937_64 rng_;
  Pose& truePose_;
};

}  // namespace

glm::dvec3 rotationVector(glm::dquat q) {
  if (q.w < 0.0) q = -q;
  const glm::dvec3 v(q.x, q.y, q.z);
  const double s = glm::length(v);
  if (s < 1e-12) return 2.0 * v;
  return v * (2.0 * std::atan2(s, q.w) / s);
}

Trace runClosedLoop(VoxelScene& scene, std::unique_ptr<HapticAlgorithm> algorithm, const HandRun& run) {
  LoopSettings s;
  s.rate = run.rate;
  s.timing = false;  // simulated time: bit-reproducible
  s.logCapacity = 8;
  s.limits.deviceHold = run.hand.outputHold;
  Pose truePose;
  auto driver = std::make_unique<DroppingDriver>(makeHandDriver(run.reference, run.hand, false), run.dropFraction,
                                                 run.seed, truePose);
  HapticLoop loop(scene, std::move(algorithm), std::move(driver), s);
  Trace trace;
  trace.dt = 1.0 / run.rate;
  const long frames = long(std::lround(run.seconds * run.rate));
  trace.frames.reserve(std::size_t(frames));
  std::vector<long> stallFrames;
  for (const HandRun::Stall& st : run.stalls) stallFrames.push_back(std::lround(st.at * run.rate));
  for (long n = 0; n < frames; ++n) {
    const auto stall = std::find(stallFrames.begin(), stallFrames.end(), n);
    if (stall == stallFrames.end())
      loop.stepSimulated();
    else
      loop.stepSimulatedAfter(run.stalls[std::size_t(stall - stallFrames.begin())].length);
    loop.records().drain([&](const FrameRecord& r) {
      trace.frames.push_back(TraceFrame{r.t, truePose, r.force, r.torque, r.out, 0.0});
    });
  }
  trace.suppressed = loop.stats().suppressed;
  loop.finish();
  passivityEnergy(trace);
  return trace;
}

double passivityEnergy(Trace& trace) {
  double e = 0.0, ezoh = 0.0, lowest = 0.0;
  for (std::size_t k = 1; k < trace.frames.size(); ++k) {
    const TraceFrame& a = trace.frames[k - 1];
    TraceFrame& b = trace.frames[k];
    const glm::dvec3 dx = b.device.position - a.device.position;
    const glm::dvec3 dtheta = rotationVector(b.device.orientation * glm::conjugate(a.device.orientation));
    e -= glm::dot(b.force, dx) + glm::dot(b.torque, dtheta);
    ezoh -= glm::dot(a.force, dx) + glm::dot(a.torque, dtheta);
    b.energy = e;
    b.energyZoh = ezoh;
    lowest = std::min(lowest, e);
  }
  return lowest;
}

double peakToPeak(const Trace& trace, std::size_t a, std::size_t b) {
  b = std::min(b, trace.frames.size());
  if (a >= b) return 0.0;
  glm::dvec3 lo(1e300), hi(-1e300);
  for (std::size_t i = a; i < b; ++i) {
    lo = glm::min(lo, trace.frames[i].device.position);
    hi = glm::max(hi, trace.frames[i].device.position);
  }
  const glm::dvec3 d = hi - lo;
  return std::max({d.x, d.y, d.z});
}

double peakSpeed(const Trace& trace, std::size_t a, std::size_t b) {
  b = std::min(b, trace.frames.size());
  double best = 0.0;
  for (std::size_t i = std::max<std::size_t>(a, 1); i < b; ++i)
    best = std::max(best, glm::length(trace.frames[i].device.position - trace.frames[i - 1].device.position) / trace.dt);
  return best;
}

bool allFinite(const Trace& trace) {
  for (const auto& f : trace.frames)
    if (!isFinite(f.force) || !isFinite(f.torque) || !isFinite(f.out.force) || !isFinite(f.out.torque) ||
        !isFinite(f.out.drawnTool))
      return false;
  return true;
}

}  // namespace millsim::measure
