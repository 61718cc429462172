#include "measure/Stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include <glm/geometric.hpp>

#include "measure/AnalyticScene.h"

namespace millsim::measure {

namespace {

constexpr double kStabilityVoxel = 0.1e-3;  // voxel size of the stability scenes

// Half-spaces (material below y = 0): a long one to slide on, a deep one to strike.
AnalyticScene& slideScene() {
  static auto s = voxelise(halfSpace({-5e-3, -5e-3, -3e-3}, {35e-3, 1.5e-3, 3e-3}), kStabilityVoxel);
  return *s;
}
AnalyticScene& impactScene() {
  static auto s = voxelise(halfSpace({-4e-3, -45e-3, -4e-3}, {4e-3, 1.5e-3, 4e-3}), kStabilityVoxel);
  return *s;
}

double offsetFor(const RendererSpec& spec, const HapticsRendererNode& node) {
  static std::map<std::string, double> cache;
  auto it = cache.find(spec.label());
  if (it == cache.end()) it = cache.emplace(spec.label(), contactOffset(node, standardTool(), kStabilityVoxel)).first;
  return it->second;
}

TrajectorySample at(double t, double x, double y) { return {t, Pose{{x, y, 0.0}, {1, 0, 0, 0}}, false}; }

char buffer[256];
template <class... A> std::string format(const char* f, A... a) {
  std::snprintf(buffer, sizeof buffer, f, a...);
  return buffer;
}

}  // namespace

std::string Scenario::name() const {
  switch (kind) {
    case ScenarioKind::StaticPush: return "static-push";
    case ScenarioKind::Slide: return format("slide-%gmm/s", speed * 1e3);
    case ScenarioKind::Impact: return format("impact-%gm/s", speed);
    case ScenarioKind::Release: return "release";
  }
  return "?";
}

std::vector<Scenario> standardScenarios() {
  return {{ScenarioKind::StaticPush, 0.0}, {ScenarioKind::Slide, 0.01}, {ScenarioKind::Slide, 0.05},
          {ScenarioKind::Slide, 0.1},      {ScenarioKind::Impact, 0.1}, {ScenarioKind::Impact, 0.3},
          {ScenarioKind::Impact, 1.0},     {ScenarioKind::Release, 0.0}};
}

std::vector<HandModel> handGrid() {
  std::vector<HandModel> grid;
  for (double m : {0.1, 0.55})
    for (double b : {2.0, 6.5, 10.0})
      for (double k : {135.0, 500.0, 1000.0}) {
        HandModel h;
        h.handMass = m, h.handDamping = b, h.handStiffness = k;
        grid.push_back(h);
      }
  return grid;
}

std::vector<HandModel> handCorners() {
  std::vector<HandModel> out(3);
  out[0].handMass = 0.1, out[0].handDamping = 2.0, out[0].handStiffness = 135.0;
  out[1].handMass = 0.554, out[1].handDamping = 6.45, out[1].handStiffness = 135.0;
  out[2].handMass = 0.55, out[2].handDamping = 10.0, out[2].handStiffness = 1000.0;
  return out;
}

std::string describe(const HandModel& h) {
  return format("M=%gkg B=%gNs/m K=%gN/m", h.handMass, h.handDamping, h.handStiffness);
}

ScenarioResult runScenario(const RendererSpec& spec, const Scenario& sc, const HandModel& hand, double drop,
                           std::uint64_t seed, const StabilityThresholds& limits) {
  auto node = makeRenderer(spec);
  const double yc = offsetFor(spec, *node);
  AnalyticScene& scene = sc.kind == ScenarioKind::Impact ? impactScene() : slideScene();
  std::vector<TrajectorySample> ref;
  double release = -1.0;
  switch (sc.kind) {
    case ScenarioKind::StaticPush:
      ref = {at(0, 0, yc + 2e-3), at(0.3, 0, yc + 2e-3), at(0.6, 0, yc - 1e-3), at(3.5, 0, yc - 1e-3)};
      break;
    case ScenarioKind::Slide: {
      const double d = sc.speed * 0.3, t1 = 0.8 + 0.3;
      ref = {at(0, 0, yc + 2e-3), at(0.3, 0, yc + 2e-3), at(0.6, 0, yc - 0.5e-3), at(0.8, 0, yc - 0.5e-3),
             at(t1, d, yc - 0.5e-3), at(t1 + 2.5, d, yc - 0.5e-3)};
      break;
    }
    case ScenarioKind::Impact: {
      const double y0 = yc + std::max(2e-3, sc.speed * 0.3), y1 = yc - 1e-3, t1 = (y0 - y1) / sc.speed;
      ref = {at(0, 0, y0), at(t1, 0, y1), at(t1 + 3.0, 0, y1)};
      break;
    }
    case ScenarioKind::Release:
      ref = {at(0, 0, yc + 2e-3), at(0.3, 0, yc + 2e-3), at(0.6, 0, yc - 1e-3), at(2.5, 0, yc - 1e-3)};
      release = 1.5;
      break;
  }
  HandRun run{Trajectory(ref), hand};
  run.hand.releaseTime = release;
  run.seconds = ref.back().t;
  run.dropFraction = drop;
  run.seed = seed;
  Trace trace = runClosedLoop(*scene.scene, node->compile(standardTool(), *scene.scene), run);

  ScenarioResult r;
  r.renderer = spec.label();
  r.scenario = sc.name() + (drop > 0.0 ? format("+%g%%drop", drop * 100) : "");
  r.hand = describe(hand);
  r.seconds = run.seconds;
  r.minEnergy = trace.frames.empty() ? 0.0 : std::min_element(trace.frames.begin(), trace.frames.end(), [](auto& a, auto& b) {
                                                return a.energy < b.energy;
                                              })->energy;
  for (const auto& f : trace.frames) r.minEnergyZoh = std::min(r.minEnergyZoh, f.energyZoh);
  r.energyBound = limits.energyPerMinute * run.seconds / 60.0;
  r.finite = allFinite(trace);
  r.suppressed = trace.suppressed;
  const std::size_t n = trace.frames.size(), w = std::size_t(0.5 / trace.dt);
  double lowest = 1e300;
  bool touched = false;
  for (std::size_t i = 0; i < n; ++i) {
    const auto& f = trace.frames[i];
    r.peakForce = std::max(r.peakForce, glm::length(f.force));
    lowest = std::min(lowest, f.device.position.y);
    if (!touched && glm::length(f.out.force) > 0.0 && i > 0) {
      touched = true;
      r.contactSpeed = glm::length(f.device.position - trace.frames[i - 1].device.position) / trace.dt;
    }
  }
  r.maxPenetration = std::max(0.0, yc - lowest);

  if (sc.kind == ScenarioKind::Release) {
    const std::size_t k = std::size_t(release / trace.dt);
    r.releaseBefore = peakSpeed(trace, k, k + w);
    r.releaseAfter = peakSpeed(trace, k + w, k + 2 * w);
  } else {
    // Along the contact normal for slides (the hand's own sideways ringing is
    // not the renderer's); every axis otherwise.
    auto p2p = [&](std::size_t a, std::size_t b) {
      if (sc.kind != ScenarioKind::Slide) return peakToPeak(trace, a, b);
      double lo = 1e300, hi = -1e300;
      for (std::size_t i = a; i < b; ++i) lo = std::min(lo, trace.frames[i].device.position.y),
                                         hi = std::max(hi, trace.frames[i].device.position.y);
      return hi - lo;
    };
    r.limitCycle = p2p(n - w, n);
    r.previousWindow = p2p(n - 2 * w, n - w);
  }

  auto fail = [&](const std::string& why) {
    r.passed = false;
    r.failure += (r.failure.empty() ? "" : "; ") + why;
  };
  if (!r.finite) fail("non-finite output");
  if (r.minEnergy < -r.energyBound)
    fail(format("passivity: min E = %.3g J < -%.3g J (energy put into the hand)", r.minEnergy, r.energyBound));
  if (r.limitCycle > limits.limitCycle && r.limitCycle >= limits.sustained * r.previousWindow)
    fail(format("limit cycle: %.3g um p-p in the last 0.5 s (%.3g um before)", r.limitCycle * 1e6,
                r.previousWindow * 1e6));
  if (sc.kind == ScenarioKind::Release && r.releaseAfter > limits.releaseDecay * r.releaseBefore && r.releaseAfter > 1e-6)
    fail(format("release: speed envelope %.3g m/s then %.3g m/s (needs a 90%% decay)", r.releaseBefore,
                r.releaseAfter));
  return r;
}

StallResult runStall(const RendererSpec& spec, double stall) {
  auto node = makeRenderer(spec);
  const double yc = offsetFor(spec, *node);
  AnalyticScene& scene = slideScene();
  constexpr double kStallAt = 1.5, kAfter = 0.5;
  HandRun run{Trajectory({at(0, 0, yc + 2e-3), at(0.3, 0, yc + 2e-3), at(0.6, 0, yc - 1e-3), at(5.0, 0, yc - 1e-3)}),
              HandModel{}};
  run.seconds = kStallAt + kAfter;
  run.stalls = {{kStallAt, stall}};
  const Trace trace = runClosedLoop(*scene.scene, node->compile(standardTool(), *scene.scene), run);

  StallResult r;
  const auto stallFrame = std::size_t(std::lround(kStallAt * run.rate));
  const std::size_t before = std::size_t(0.1 * run.rate);
  double height = 0.0;
  for (std::size_t i = stallFrame - before; i < stallFrame; ++i) {
    r.heldForce += glm::length(trace.frames[i].force) / double(before);
    height += trace.frames[i].device.position.y / double(before);
  }
  const double resumed = trace.frames[stallFrame].t;
  r.recovery = -1.0;
  for (std::size_t i = stallFrame; i < trace.frames.size(); ++i) {
    const TraceFrame& f = trace.frames[i];
    const double force = glm::length(f.force);
    r.peakForce = std::max(r.peakForce, force);
    r.sink = std::max(r.sink, height - f.device.position.y);
    if (r.recovery < 0.0 && force >= 0.9 * r.heldForce) r.recovery = f.t - resumed;
  }
  if (r.recovery < 0.0) r.recovery = kAfter;
  return r;
}

}  // namespace millsim::measure
