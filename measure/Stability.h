#pragma once
// Closed-loop stability scenarios (docs/stability.md): a simulated hand
// presses, slides, strikes and lets go of the tool on a voxelised half-space
// under any renderer, and the passivity observer, limit-cycle and release
// checks judge the run against the thresholds below.
#include <string>
#include <vector>

#include "measure/ClosedLoop.h"
#include "measure/Renderers.h"

namespace millsim::measure {

// Pass/fail thresholds (docs/stability.md explains each).
struct StabilityThresholds {
  double energyPerMinute = 1e-3;  // J: min E ≥ −1 mJ per 60 s, scaled to the run's length
  double limitCycle = 10e-6;      // m: a sustained oscillation larger than this fails
  double sustained = 0.8;         // ...sustained: the last window's p-p ≥ this × the window before
  double releaseDecay = 0.1;      // the speed envelope 0.5–1 s after release ≤ this × 0–0.5 s
};

enum class ScenarioKind { StaticPush, Slide, Impact, Release };

struct Scenario {
  ScenarioKind kind = ScenarioKind::StaticPush;
  double speed = 0.0;  // m/s: sliding speed or impact (reference) speed
  std::string name() const;
};

// The scenarios of the notes' protocol: static push, sliding at 10/50/100
// mm/s, impacts at 0.1/0.3/1 m/s, release in contact.
std::vector<Scenario> standardScenarios();

// The notes' hand grid: M ∈ {0.1, 0.55} kg × B ∈ {2, 6.5, 10} N·s/m × K ∈ {135, 500, 1000} N/m.
std::vector<HandModel> handGrid();
// Three grips spanning it: loose (0.1, 2, 135), the measured arm (0.554, 6.45, 135), firm (0.55, 10, 1000).
std::vector<HandModel> handCorners();
std::string describe(const HandModel& hand);

struct ScenarioResult {
  std::string renderer, scenario, hand;
  double seconds = 0.0;
  double minEnergy = 0.0, energyBound = 0.0;  // J; pass needs minEnergy ≥ −energyBound
  double minEnergyZoh = 0.0;                  // J, measured (ClosedLoop.h), not judged
  double limitCycle = 0.0, previousWindow = 0.0;  // m, p-p over the last 0.5 s and the 0.5 s before
  double releaseBefore = 0.0, releaseAfter = 0.0;  // m/s, speed envelopes (Release only)
  double peakForce = 0.0;      // N, sent
  double maxPenetration = 0.0; // m, deepest burr-centre position below its first-contact height
  double contactSpeed = 0.0;   // m/s, device speed at the first frame with force
  long suppressed = 0;
  bool finite = true;
  bool passed = true;
  std::string failure;  // what failed, with the numbers
};

ScenarioResult runScenario(const RendererSpec& renderer, const Scenario& scenario, const HandModel& hand,
                           double dropFraction = 0.0, std::uint64_t seed = 1,
                           const StabilityThresholds& limits = StabilityThresholds{});

// A stall while pressing: the default hand holds the tool on the half-space,
// its reference 1 mm below first contact (about 0.4 N through the grip), for
// 1.5 s; then the loop stalls for `stall` seconds (a late frame for the
// safety layer; the simulated device drops its wrench after its 10 ms hold)
// and runs on for 0.5 s.
struct StallResult {
  double heldForce = 0.0;  // N, mean force sent over the 0.1 s before the stall
  double recovery = 0.0;   // s from the end of the stall until the force sent is back to 90 % of heldForce
  double peakForce = 0.0;  // N, largest force sent after the stall
  double sink = 0.0;       // m, how far the device went below its mean height before the stall
};
StallResult runStall(const RendererSpec& renderer, double stall);

}  // namespace millsim::measure
