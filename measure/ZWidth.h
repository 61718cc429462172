#pragma once
// The Z-width sweep (Colgate & Brown 1994): the largest virtual stiffness a
// renderer renders stably on the closed 1 kHz loop, for a given grip. The
// renderer's stiffness field is raised in √2 steps; each value must pass the
// stability scenarios (static push, impact at 0.1 m/s, release in contact)
// under the thresholds of docs/stability.md. The sweep stops at the first value
// that fails, so "largest stable" means every value up to it passed.
#include <string>
#include <vector>

#include "measure/Stability.h"

namespace millsim::measure {

struct ZWidthPoint {
  double stiffness = 0.0;  // the field's value, N/m
  bool stable = false;
  std::string failure;     // the first failing scenario and why
};

struct ZWidthResult {
  std::string renderer, field, hand;
  double defaultStiffness = 0.0;
  double largestStable = 0.0;     // 0 if even the first value failed
  double firstUnstable = 0.0;     // 0 if none in the range failed
  double renderedAtDefault = 0.0; // N/m the device meets at the default (renderedStiffness, h = 0.1 mm)
  double renderedAtLargest = 0.0; // N/m the device meets at largestStable
  std::vector<ZWidthPoint> points;
};

// The field swept is the one the renderer declares as its stiffness
// (RendererTraits::stiffnessField): the proxy spring of #1, the penalty spring
// of #2, the virtual coupling of #3.

// The value of that field on a default node of `type`; throws for unknown
// types and for types that declare no stiffness field.
double defaultStiffness(const std::string& type);

// from, from·√2, from·2, ... up to and including `to` (rounded to 3 significant digits).
std::vector<double> sqrt2Steps(double from, double to);

// The scenarios every value must pass.
std::vector<Scenario> zWidthScenarios();

ZWidthResult zWidthSweep(const std::string& type, const HandModel& hand, const std::vector<double>& values);

}  // namespace millsim::measure
