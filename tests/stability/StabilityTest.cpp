// Numerical stability of every registered renderer, closed loop and open loop
// (docs/stability.md): passivity at the device port over hand grips and
// scenarios, fall-through of thin plates, and pose fuzzing. Thresholds live in
// measure/Stability.h and are explained in the docs. Tests whose names contain
// "Soak" are the long versions (ctest label soak); the rest run in CI.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "measure/FallThrough.h"
#include "measure/Fuzz.h"
#include "measure/Stability.h"
#include "measure/ZWidth.h"

using namespace millsim;
using namespace millsim::measure;

namespace {

// Proxy and coupling methods must never tunnel; penalty methods are measured.
// The renderer says which it is (RendererTraits::constrainsTool).
bool mustHold(const std::string& type) { return rendererTraits(type).constrainsTool; }

void print(const ScenarioResult& r) {
  std::cout << std::setprecision(3) << r.renderer << " | " << r.scenario << " | " << r.hand << " | minE "
            << r.minEnergy * 1e6 << " uJ (bound -" << r.energyBound * 1e6 << ") | minEzoh " << r.minEnergyZoh * 1e6
            << " uJ | p-p " << r.limitCycle * 1e6
            << " um | peak " << r.peakForce << " N | depth " << r.maxPenetration * 1e3 << " mm | contact "
            << r.contactSpeed << " m/s";
  if (r.releaseBefore > 0.0) std::cout << " | release " << r.releaseBefore << " -> " << r.releaseAfter << " m/s";
  std::cout << (r.passed ? "" : " | FAIL: " + r.failure) << "\n";
}

// Failures these tests exposed in the renderers, reported in docs/stability.md
// and left for their owners. Each waiver excuses ONE metric (the failure text's
// prefix, as runScenario writes it) of one renderer in one scenario (its exact
// name, "+5%drop" included) for the grips listed (M/B/K as kg, N·s/m, N/m), as
// measured with `stability_tests --gtest_filter='-*Soak*'` and
// `--gtest_filter='*SoakPassive*'`. Any other failure of the same run
// (passivity, non-finite output, release, another metric) still fails the
// test, and a waived check that passes is printed as
// "KNOWN ISSUE NO LONGER REPRODUCES" (then remove its grip here).
struct Waiver {
  const char* renderer;
  const char* metric;    // prefix of one failure item, e.g. "limit cycle:"
  const char* scenario;  // ScenarioResult::scenario
  const char* grips;     // "M/B/K M/B/K ..."
  const char* why;
};

constexpr const char* kRings =
    "a lightly damped grip (B = 2 N·s/m) rings against the contact stiffness for seconds: the Z-width bound "
    "b > K·T/2 is not met (docs/stability.md, 4)";

// SurfacePointRenderer's waivers (its lattice's sideways force on slides, its
// force held at about 2.5 N past half immersion, ringing on B = 2 N·s/m) went
// with its depth-linear force (issue 14); they were the paper's sum's, now
// deepestPoints FALSE (docs/stability.md, 1 and 2).
const std::vector<Waiver>& waivers() {
  static const std::vector<Waiver> w{
      // BarbicRenderer (#3): ringing on the heavy, lightly damped grip of the
      // soak grid while sliding at 50 mm/s, 11 and 13 µm p-p (the bound is
      // 10): rigidContact makes the felt stiffness the coupling's 2000 N/m
      // instead of about 1850 in series with the penalty points; with it
      // FALSE these rang at 5.0 and 5.6 µm. (The 100 mm/s slide with
      // dropped samples this waiver named before rings at 5.4 µm since the
      // scale-1 shell: no longer waived.)
      {"BarbicRenderer", "limit cycle:", "slide-50mm/s", "0.55/2/135", kRings},
      {"BarbicRenderer", "limit cycle:", "slide-50mm/s+5%drop", "0.55/2/135", kRings},
  };
  return w;
}

bool listsGrip(const char* grips, const HandModel& hand) {
  std::istringstream in(grips);
  std::string g;
  while (in >> g) {
    double m = 0, b = 0, k = 0;
    char s1 = 0, s2 = 0;
    std::istringstream one(g);
    if (!(one >> m >> s1 >> b >> s2 >> k) || s1 != '/' || s2 != '/') ADD_FAILURE() << "bad grip '" << g << "' in a waiver";
    if (std::abs(m - hand.handMass) < 1e-9 && std::abs(b - hand.handDamping) < 1e-9 &&
        std::abs(k - hand.handStiffness) < 1e-9)
      return true;
  }
  return false;
}

std::vector<std::string> failureItems(const std::string& failure) {
  std::vector<std::string> items;
  std::size_t from = 0;
  while (from < failure.size()) {
    const std::size_t end = std::min(failure.find("; ", from), failure.size());
    items.push_back(failure.substr(from, end - from));
    from = end + 2;
  }
  return items;
}

void expectStable(const std::vector<HandModel>& hands, const std::string& type, double drop, std::uint64_t seed) {
  for (const HandModel& hand : hands)
    for (const Scenario& sc : standardScenarios()) {
      const ScenarioResult r = runScenario({type, {}}, sc, hand, drop, seed);
      print(r);
      ASSERT_EQ(r.passed, r.failure.empty()) << "a failed run must say why: " << r.failure;
      std::vector<const Waiver*> applicable;
      for (const Waiver& w : waivers())
        if (type == w.renderer && r.scenario == w.scenario && listsGrip(w.grips, hand)) applicable.push_back(&w);
      std::string unexcused;
      std::set<const Waiver*> used;
      for (const std::string& item : failureItems(r.failure)) {
        const auto w = std::find_if(applicable.begin(), applicable.end(),
                                    [&](const Waiver* a) { return item.rfind(a->metric, 0) == 0; });
        if (w == applicable.end()) {
          unexcused += (unexcused.empty() ? "" : "; ") + item;
          continue;
        }
        used.insert(*w);
        std::cout << "KNOWN ISSUE (" << type << ", " << r.scenario << ", " << r.hand << "): " << item << ": "
                  << (*w)->why << "\n";
      }
      for (const Waiver* w : applicable)
        if (!used.count(w))
          std::cout << "KNOWN ISSUE NO LONGER REPRODUCES: " << type << ", " << r.scenario << ", " << r.hand
                    << ": the '" << w->metric << "' check passed; remove this grip from its waiver in " << __FILE__
                    << "\n";
      EXPECT_TRUE(unexcused.empty()) << r.renderer << ", " << r.scenario << ", " << r.hand << " (seed " << seed
                                     << "): " << unexcused;
    }
}

class Stability : public ::testing::TestWithParam<std::string> {};

std::string name(const ::testing::TestParamInfo<std::string>& info) { return info.param; }

}  // namespace

// ---- passivity, limit cycles, release --------------------------------------

TEST_P(Stability, PassiveAcrossScenariosForThreeGrips) { expectStable(handCorners(), GetParam(), 0.0, 1); }

TEST_P(Stability, PassiveWithFivePercentDroppedSamples) { expectStable({HandModel{}}, GetParam(), 0.05, 7); }

TEST_P(Stability, SoakPassiveOverTheWholeHandGrid) {
  expectStable(handGrid(), GetParam(), 0.0, 1);
  expectStable(handGrid(), GetParam(), 0.05, 11);
}

// ---- Z-width -------------------------------------------------------------------

// The defaults must leave room: every renderer stays stable at twice its
// default stiffness for all three grips (the measured limits, in
// docs/results.md, are 2x to 13x). Colgate's bound K < 2b/T is 6 kN/m for the
// loose grip (B = 2 N·s/m plus the device's 1), so #1's 2 kN/m proxy spring
// has exactly this margin there.
TEST_P(Stability, DefaultStiffnessHasTwofoldMargin) {
  const std::string type = GetParam();
  ASSERT_FALSE(rendererTraits(type).stiffnessField.empty())
      << type << ": declare its stiffness field in traits() (RendererTraits::stiffnessField)";
  for (const HandModel& hand : handCorners()) {
    const double k = defaultStiffness(type);
    const ZWidthResult r = zWidthSweep(type, hand, {k, 2.0 * k});
    std::cout << type << " | " << r.hand << " | " << r.field << " " << k << " and " << 2.0 * k << " N/m | "
              << (r.firstUnstable > 0.0 ? "unstable at " + std::to_string(r.firstUnstable) + ": " +
                                              r.points.back().failure
                                        : "stable")
              << "\n";
    EXPECT_EQ(r.largestStable, 2.0 * k) << type << ", " << r.hand << ": " << r.points.back().failure;
  }
}

// The sweep must see instability where theory puts it: a 16 kN/m proxy spring
// against the loose grip is 2.7x Colgate's 6 kN/m bound and must ring.
TEST(ZWidth, DetectsTheRingingBeyondColgatesBound) {
  HandModel loose = handCorners()[0];
  const ZWidthResult r = zWidthSweep("LineProxyRenderer", loose, {16000.0});
  ASSERT_EQ(r.points.size(), 1u);
  EXPECT_FALSE(r.points[0].stable) << "16 kN/m against a 2 N·s/m grip passed every scenario";
  EXPECT_NE(r.points[0].failure.find("limit cycle"), std::string::npos) << r.points[0].failure;
}

// ---- a late frame --------------------------------------------------------------

// One 6 ms preemption of the haptic thread while the hand presses the tool on
// a surface: a late frame for the safety layer, within the device's 10 ms
// hold. The wall must not go away: zeroed and soft-started over 0.25 s (the
// old rule), the hand, still pushing, fell 0.55 mm in and was kicked out.
TEST_P(Stability, AStallWhilePressingDoesNotLetTheHandFallIn) {
  const StallResult r = runStall({GetParam(), {}}, 0.006);
  std::cout << GetParam() << " | 6 ms stall | held " << r.heldForce << " N | back to 90 % after " << r.recovery * 1e3
            << " ms | peak " << r.peakForce << " N | sank " << r.sink * 1e6 << " um\n";
  ASSERT_GT(r.heldForce, 0.2) << "the hand must press the surface before the stall";
  EXPECT_LE(r.recovery, 0.04) << "the force stayed away after a 6 ms stall";
  EXPECT_LE(r.peakForce, 1.25 * r.heldForce) << "the force kicked back after a 6 ms stall";
  EXPECT_LE(r.sink, 50e-6) << "the hand fell into the surface during a 6 ms stall";
  // 26 ms: the device has dropped the wrench after 10 ms (as ARES does) and
  // the hand falls until the force is back, so it must come back soon: a
  // ramp as long as the outage let it sink 0.27 mm and kick back at 2.3-2.6x.
  const StallResult lost = runStall({GetParam(), {}}, 0.026);
  std::cout << GetParam() << " | 26 ms stall | held " << lost.heldForce << " N | back to 90 % after "
            << lost.recovery * 1e3 << " ms | peak " << lost.peakForce << " N | sank " << lost.sink * 1e6 << " um\n";
  EXPECT_LE(lost.recovery, 0.03) << "the force stayed away after a 26 ms stall";
  EXPECT_LE(lost.sink, 200e-6) << "the hand fell into the surface after a 26 ms stall";
  EXPECT_LE(lost.peakForce, 2.2 * lost.heldForce) << "the force kicked back after a 26 ms stall";
}

// ---- fall-through -------------------------------------------------------------

TEST_P(Stability, ThinPlatesAtUpToOneMetrePerSecond) {
  const std::string type = GetParam();
  for (double t : plateThicknesses(fallThroughVoxelSize())) {
    double safe = 0.0;
    bool stillSafe = true;
    for (double v : fallThroughSpeeds()) {
      const FallThroughResult r = fallThrough({type, {}}, t, v);
      std::cout << type << " | plate " << t * 1e3 << " mm | " << v << " m/s | held " << r.held << " | detected "
                << r.detected << " | resist " << r.minPeakResist << " N | lowest proxy " << r.lowestProxy * 1e3 << " mm" << (r.firstFailure.empty() ? "" : " | ")
                << r.firstFailure << "\n";
      if (stillSafe && (mustHold(type) ? r.held : r.detected)) {
        safe = v;
      } else {
        stillSafe = false;
      }
      if (mustHold(type) && v <= 1.0) {
        EXPECT_TRUE(r.held) << type << " tunnelled through a " << t * 1e3 << " mm plate at " << v
                            << " m/s: " << r.firstFailure;
      }
      // Half a voxel per frame samples any plate at least a voxel thick: every
      // renderer must feel it on the near side.
      if (v <= 0.05) {
        EXPECT_TRUE(r.detected) << type << " missed a " << t * 1e3 << " mm plate at " << v << " m/s: "
                                << r.firstFailure;
      }
    }
    std::cout << type << " | plate " << t * 1e3 << " mm | highest safe speed " << safe << " m/s"
              << (stillSafe ? " (all speeds tried)" : "") << "\n";
  }
}

// ---- fuzz ---------------------------------------------------------------------

void expectClean(const FuzzResult& r, const std::string& type, std::uint64_t seed, const char* path) {
  std::cout << type << " | fuzz " << path << " | " << r.frames << " frames | " << r.nonFinite << " non-finite | "
            << r.suppressed << " suppressed\n";
  EXPECT_EQ(r.nonFinite, 0) << type << " (" << path << "): first non-finite output at frame " << r.firstBad << " ("
                            << r.firstBadWhat << "); reproduce with seed " << seed;
}

TEST_P(Stability, FuzzedPosesGiveFiniteOutput) {
  for (std::uint64_t seed : {1u, 2u}) {
    expectClean(fuzzThroughLoop({GetParam(), {}}, 10000, seed), GetParam(), seed, "loop");
    expectClean(fuzzDirect({GetParam(), {}}, 10000, seed), GetParam(), seed, "direct");
  }
}

TEST_P(Stability, SoakFuzzAMillionFrames) {
  const std::uint64_t seed = 1000;
  for (int part = 0; part < 10; ++part) {
    expectClean(fuzzThroughLoop({GetParam(), {}}, 50000, seed + part), GetParam(), seed + part, "loop");
    expectClean(fuzzDirect({GetParam(), {}}, 50000, seed + part), GetParam(), seed + part, "direct");
  }
}

INSTANTIATE_TEST_SUITE_P(Renderers, Stability, ::testing::ValuesIn(registeredRenderers()), name);
