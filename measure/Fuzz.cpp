#include "measure/Fuzz.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include "measure/AnalyticScene.h"
#include "millsim/run/HapticLoop.h"

namespace millsim::measure {

namespace {

constexpr double kFuzzVoxel = 0.1e-3;

// A slab (y < 0), a ball of radius 1.5 mm above it and a one-voxel plate at
// y = 3.5 mm, as one union: flat, curved and thin features in one field.
Shape fuzzShape() {
  return {"fuzz",
          [](const glm::dvec3& p) {
            const double slab = p.y, ball = glm::length(p - glm::dvec3(1.5e-3, 1.5e-3, 0.0)) - 1.5e-3,
                         sheet = std::abs(p.y - 3.5e-3) - 0.5 * kFuzzVoxel;
            return std::min({slab, ball, sheet});
          },
          {-4e-3, -3e-3, -4e-3}, {4e-3, 5e-3, 4e-3}};
}

class PoseSource {
public:
  explicit PoseSource(std::uint64_t seed) : rng_(seed) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }

  // The next device pose; `what` says which kind (for the failure message).
  Pose next(const char*& what) {
    const double r = uniform(0.0, 1.0);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    if (r < 0.45) {
      what = "random walk";
      pose_.position += glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * (2.0 * kFuzzVoxel);
      pose_.orientation = glm::normalize(glm::angleAxis(uniform(-0.05, 0.05), randomAxis()) * pose_.orientation);
      pose_.position = glm::clamp(pose_.position, glm::dvec3(-3.5e-3, -2.5e-3, -3.5e-3), glm::dvec3(3.5e-3, 4.5e-3, 3.5e-3));
    } else if (r < 0.55) {
      what = "on the iso-surface";
      const double choice = uniform(0.0, 1.0);
      if (choice < 0.5) pose_.position = {uniform(-3e-3, 3e-3), 0.0, uniform(-3e-3, 3e-3)};
      else pose_.position = glm::dvec3(1.5e-3, 1.5e-3, 0.0) + 1.5e-3 * randomAxis();
    } else if (r < 0.62) {
      what = "deep inside (zero gradient)";
      pose_.position = {uniform(-3e-3, 3e-3), uniform(-2.5e-3, -1e-3), uniform(-3e-3, 3e-3)};
    } else if (r < 0.67) {
      what = "180-degree flip";
      pose_.orientation = glm::normalize(glm::angleAxis(std::numbers::pi, randomAxis()) * pose_.orientation);
    } else if (r < 0.72) {
      what = "huge jump";
      pose_.position = glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)) * std::pow(10.0, uniform(-2.0, 0.0));
    } else if (r < 0.75) {
      what = "back from a jump into material";
      pose_.position = {uniform(-1e-3, 1e-3), uniform(-1e-3, 0.0), uniform(-1e-3, 1e-3)};
    } else if (r < 0.77) {
      what = "NaN position";
      Pose p = pose_;
      p.position.x = nan;
      return p;
    } else if (r < 0.78) {
      what = "Inf position";
      Pose p = pose_;
      p.position.y = -inf;
      return p;
    } else if (r < 0.79) {
      what = "NaN quaternion";
      Pose p = pose_;
      p.orientation.w = nan;
      return p;
    } else if (r < 0.80) {
      what = "zero quaternion";
      Pose p = pose_;
      p.orientation = glm::dquat(0, 0, 0, 0);
      return p;
    } else {
      what = "near the surface";
      pose_.position = {uniform(-3e-3, 3e-3), uniform(-1e-3, 1e-3), uniform(-3e-3, 3e-3)};
      pose_.orientation = glm::normalize(glm::dquat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
    }
    return pose_;
  }
  bool button() { return uniform(0.0, 1.0) < 0.2; }
  bool drop(double fraction) { return uniform(0.0, 1.0) < fraction; }

private:
  glm::dvec3 randomAxis() {
    glm::dvec3 a;
    do a = {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
    while (glm::length(a) < 0.1 || glm::length(a) > 1.0);
    return glm::normalize(a);
  }
  std::mt19937_64 rng_;
  Pose pose_{{0.0, 1e-3, 0.0}, {1, 0, 0, 0}};
};

bool finiteOutput(const HapticOutput& o) {
  return isFinite(o.force) && isFinite(o.torque) && isFinite(o.drawnTool) && isFinite(o.proxy) &&
         isFinite(o.intersection) && isFinite(o.burrCentre);
}

class FuzzDriver final : public DeviceDriver {
public:
  FuzzDriver(PoseSource& source, double drop, const char*& what) : source_(source), drop_(drop), what_(what) {}
  DeviceReading read(double, double) override {
    DeviceReading r{source_.next(what_), source_.button(), true};
    if (source_.drop(drop_)) r.valid = false;
    return r;
  }
  void write(const glm::dvec3&, const glm::dvec3&) override {}

private:
  PoseSource& source_;
  double drop_;
  const char*& what_;
};

void note(FuzzResult& r, long frame, const char* what) {
  ++r.nonFinite;
  if (r.firstBad < 0) r.firstBad = frame, r.firstBadWhat = what;
}

}  // namespace

FuzzResult fuzzThroughLoop(const RendererSpec& spec, long frames, std::uint64_t seed, double drop) {
  auto scene = voxelise(fuzzShape(), kFuzzVoxel);  // fresh: the run mills it
  auto node = makeRenderer(spec);
  PoseSource source(seed);
  const char* what = "";
  LoopSettings s;
  s.timing = false;
  s.logCapacity = 8;
  s.tool = standardTool();
  HapticLoop loop(*scene->scene, node->compile(standardTool(), *scene->scene),
                  std::make_unique<FuzzDriver>(source, drop, what), s);
  FuzzResult r;
  for (long n = 0; n < frames; ++n) {
    loop.stepSimulated();
    loop.records().drain([&](const FrameRecord& f) {
      if (!isFinite(f.force) || !isFinite(f.torque) || !finiteOutput(f.out)) note(r, f.frame, what);
    });
  }
  r.frames = frames;
  r.suppressed = loop.stats().suppressed;
  loop.finish();
  return r;
}

FuzzResult fuzzDirect(const RendererSpec& spec, long frames, std::uint64_t seed) {
  auto scene = voxelise(fuzzShape(), kFuzzVoxel);
  auto node = makeRenderer(spec);
  auto algorithm = node->compile(standardTool(), *scene->scene);
  PoseSource source(seed);
  const char* what = "";
  algorithm->reset(Pose{{0.0, 1e-3, 0.0}, {1, 0, 0, 0}});
  FuzzResult r;
  for (long n = 0; n < frames; ++n) {
    const Pose p = source.next(what);
    const double dt = source.drop(0.05) ? 2e-3 : 1e-3;  // a dropped frame doubles the step
    const HapticOutput out = algorithm->step(*scene->scene, HapticInput{p, dt, source.button()});
    if (!finiteOutput(out)) note(r, n, what);
    r.suppressed += (out.flags & kFlagNonFiniteSuppressed) != 0;
    if (source.button() && out.burrCuts && isFinite(out.burrCentre)) scene->scene->mill(out.burrCentre, 0.5e-3);
  }
  r.frames = frames;
  return r;
}

}  // namespace millsim::measure
