#include "measure/ZWidth.h"

#include <cmath>
#include <stdexcept>

namespace millsim::measure {

double defaultStiffness(const std::string& type) {
  auto probe = makeRenderer({type, {}});
  const std::string name = probe->traits().stiffnessField;
  if (name.empty())
    throw std::runtime_error("renderer type '" + type + "' declares no stiffness field (RendererTraits::stiffnessField)");
  const Field* f = probe->field(name);
  if (!f) throw std::runtime_error(type + " has no field '" + name + "'");
  return std::stod(f->toString());
}

std::vector<double> sqrt2Steps(double from, double to) {
  std::vector<double> out;
  for (int i = 0;; ++i) {
    double v = from * std::pow(std::sqrt(2.0), i);
    const double scale = std::pow(10.0, std::floor(std::log10(v)) - 2);
    v = std::round(v / scale) * scale;
    if (v > to * 1.0001) break;
    out.push_back(v);
  }
  return out;
}

std::vector<Scenario> zWidthScenarios() {
  return {{ScenarioKind::StaticPush, 0.0}, {ScenarioKind::Impact, 0.1}, {ScenarioKind::Release, 0.0}};
}

ZWidthResult zWidthSweep(const std::string& type, const HandModel& hand, const std::vector<double>& values) {
  ZWidthResult r;
  r.renderer = type;
  r.field = rendererTraits(type).stiffnessField;
  r.hand = describe(hand);
  r.defaultStiffness = defaultStiffness(type);
  r.renderedAtDefault = renderedStiffness(*makeRenderer({type, {}}), standardTool(), 0.1e-3);
  for (double k : values) {
    const RendererSpec spec{type, {{r.field, std::to_string(k)}}};
    ZWidthPoint p{k, true, ""};
    for (const Scenario& sc : zWidthScenarios()) {
      const ScenarioResult s = runScenario(spec, sc, hand);
      if (!s.passed) {
        p.stable = false;
        p.failure = s.scenario + ": " + s.failure;
        break;
      }
    }
    r.points.push_back(p);
    if (!p.stable) {
      r.firstUnstable = k;
      break;
    }
    r.largestStable = k;
  }
  if (r.largestStable > 0.0)
    r.renderedAtLargest =
        renderedStiffness(*makeRenderer({type, {{r.field, std::to_string(r.largestStable)}}}), standardTool(), 0.1e-3);
  return r;
}

}  // namespace millsim::measure
