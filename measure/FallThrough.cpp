#include "measure/FallThrough.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include <glm/geometric.hpp>

#include "measure/AnalyticScene.h"

namespace millsim::measure {

namespace {
constexpr double kFallThroughVoxel = 0.1e-3;

AnalyticScene& plateScene(double t) {
  static std::map<double, std::unique_ptr<AnalyticScene>> cache;
  auto& s = cache[t];
  if (!s) s = voxelise(plate(t, {-4e-3, -4e-3, -4e-3}, {4e-3, 4e-3, 4e-3}), kFallThroughVoxel);
  return *s;
}
}  // namespace

double fallThroughVoxelSize() { return kFallThroughVoxel; }
std::vector<double> plateThicknesses(double h) { return {h, 2 * h, 4 * h, 1e-3}; }
std::vector<double> fallThroughSpeeds() { return {0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.75, 1.0, 1.5, 2.0}; }

FallThroughResult fallThrough(const RendererSpec& spec, double t, double v, int phases) {
  auto node = makeRenderer(spec);
  const ToolGeometry tool = standardTool();
  AnalyticScene& s = plateScene(t);
  const double dt = 1e-3, step = v * dt;
  const glm::dvec3 u(0.0, -1.0, 0.0);  // motion: down through the plate, shaft trailing
  // Start and end well clear of the plate for any felt offset (up to the tool's radius).
  const double y0 = 0.5 * t + 2.0 * tool.tipRadius + 1e-3, y1 = -y0;
  FallThroughResult r;
  r.renderer = spec.label(), r.thickness = t, r.speed = v, r.phases = phases;
  r.minPeakResist = 1e300;
  r.lowestProxy = std::numeric_limits<double>::quiet_NaN();
  for (int ph = 0; ph < phases; ++ph) {
    auto algorithm = node->compile(tool, *s.scene);
    const double start = y0 + step * ph / phases;
    algorithm->reset(Pose{{0.0, start, 0.0}, {1, 0, 0, 0}});
    bool seen = false, held = true, detected = true;
    double peak = 0.0;
    HapticOutput out;
    long frame = 0;
    for (double y = start; y > y1; y -= step, ++frame) {
      out = algorithm->step(*s.scene, HapticInput{Pose{{0.0, y, 0.0}, {1, 0, 0, 0}}, dt});
      const double along = glm::dot(out.force, u);
      if (glm::length(out.force) > 0.0 && !seen) {
        seen = true;
        if (!(along < 0.0)) detected = false;
      }
      if (seen && along > 1e-9 && held) {
        held = false;
        if (r.firstFailure.empty()) {
          char b[160];
          std::snprintf(b, sizeof b, "phase %d frame %ld: force pushes through (%.3g N) at y = %.4g mm", ph, frame,
                        along, y * 1e3);
          r.firstFailure = b;
        }
      }
      if (y > 0.0) peak = std::max(peak, -along);
      if (out.hasProxy) {
        r.lowestProxy = std::isnan(r.lowestProxy) ? out.proxy.y : std::min(r.lowestProxy, out.proxy.y);
        if (out.proxy.y < 0.0 && held) {
          held = false;
          if (r.firstFailure.empty()) {
            char b[160];
            std::snprintf(b, sizeof b, "phase %d frame %ld: the proxy crossed the midplane (y = %.4g mm)", ph, frame,
                          out.proxy.y * 1e3);
            r.firstFailure = b;
          }
        }
      }
    }
    if (!seen) detected = false, held = false;
    if (held && !(glm::dot(out.force, u) < 0.0)) {
      held = false;
      if (r.firstFailure.empty())
        r.firstFailure = "phase " + std::to_string(ph) + ": no resisting force once past the plate (tunnelled)";
    }
    if (!detected && r.firstFailure.empty())
      r.firstFailure = "phase " + std::to_string(ph) + (seen ? ": first force pushes through" : ": plate never felt");
    r.held = r.held && held;
    r.detected = r.detected && detected;
    r.minPeakResist = std::min(r.minPeakResist, peak);
  }
  return r;
}

}  // namespace millsim::measure
