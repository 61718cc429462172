#include "measure/PhysicalScenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace millsim::measure {

namespace {

constexpr double kBallR = 2e-3, kBowlR = 2e-3, kPlate = 0.4e-3, kHoleR = 0.6e-3, kHoleDepth = 1.5e-3;

// The slab y < 0 minus a ball of radius R at the origin: exact outside too
// (above the opening the nearest material is the rim circle).
double bowlDistance(const glm::dvec3& p) {
  const double r = glm::length(p), rxz = std::hypot(p.x, p.z);
  if (p.y > 0.0) return rxz >= kBowlR ? p.y : std::hypot(kBowlR - rxz, p.y);
  if (r < kBowlR) return kBowlR - r;
  return -std::min(-p.y, r - kBowlR);
}

// The slab y < 0 with the hole's wall: material where y < 0 and r ≥ R_h (r about the Y axis).
double holeWallDistance(const glm::dvec3& p) {
  const double r = std::hypot(p.x, p.z);
  if (r >= kHoleR) return p.y > 0.0 ? p.y : -std::min(-p.y, r - kHoleR);
  return p.y > 0.0 ? std::hypot(kHoleR - r, p.y) : kHoleR - r;
}
double holeBottomDistance(const glm::dvec3& p) { return p.y + kHoleDepth; }

// The slab y < 0 with a flat-bottomed hole of radius R_h and depth D drilled along −Y.
double holeDistance(const glm::dvec3& p) {
  const double r = std::hypot(p.x, p.z);
  const bool inHole = r < kHoleR && p.y > -kHoleDepth;
  if (p.y >= 0.0 || inHole) return std::min(holeWallDistance(p), holeBottomDistance(p));
  // Inside material: the nearer of the top face and the hole's surface.
  const double toHole = p.y > -kHoleDepth ? r - kHoleR
                        : r < kHoleR     ? -kHoleDepth - p.y
                                         : std::hypot(r - kHoleR, -kHoleDepth - p.y);
  return -std::min(-p.y, toHole);
}

}  // namespace

std::vector<std::string> physicalSceneNames() {
  return {"half-space", "ball", "bowl", "edge", "plate", "shaft-on-edge", "hole"};
}

PhysicalScene physicalScene(const std::string& name) {
  using Fn = std::function<double(const glm::dvec3&)>;
  auto one = [](const Shape& s) { return Material{{s.distance}}; };
  if (name == "half-space") {
    Shape s = halfSpace({-3e-3, -2e-3, -3e-3}, {3e-3, 1.5e-3, 3e-3});
    return {name, s, one(s)};
  }
  if (name == "ball") {
    Shape s = ball(kBallR);
    return {name, s, one(s)};
  }
  if (name == "bowl") {
    Shape s{"bowl", bowlDistance, {-3.5e-3, -3.5e-3, -3.5e-3}, {3.5e-3, 1e-3, 3.5e-3}};
    return {name, s, one(s)};
  }
  if (name == "edge") {
    Shape s = edge({-2e-3, -2e-3, -1.5e-3}, {1.5e-3, 1.5e-3, 1.5e-3});
    return {name, s, one(s)};
  }
  if (name == "plate") {
    Shape s = plate(kPlate, {-3e-3, -1.5e-3, -3e-3}, {3e-3, 1.5e-3, 3e-3});
    return {name, s, one(s)};
  }
  if (name == "shaft-on-edge") {
    Shape s = edge({-2e-3, -3.2e-3, -1.5e-3}, {3e-3, 1e-3, 1.5e-3});
    return {name, s, one(s), true};
  }
  if (name == "hole") {
    Shape s{"hole", holeDistance, {-2e-3, -2.5e-3, -2e-3}, {2e-3, 1e-3, 2e-3}};
    return {name, s, Material{{Fn(holeWallDistance), Fn(holeBottomDistance)}}};
  }
  throw std::runtime_error("unknown physical scene '" + name +
                           "' (half-space, ball, bowl, edge, plate, shaft-on-edge, hole)");
}

std::vector<PhysicalProbe> physicalProbes(const PhysicalScene& scene, const ToolGeometry& tool, double h, int phases) {
  std::vector<PhysicalProbe> out;
  // 0.6 mm puts the burr centre itself 0.1 mm inside, where a centre-point method first feels anything.
  const std::vector<double> burrDepths{0.05e-3, 0.1e-3, 0.2e-3, 0.3e-3, 0.6e-3}, holeDepths{0.05e-3, 0.1e-3, 0.2e-3, 0.3e-3},
      shaftDepths{0.05e-3, 0.1e-3, 0.15e-3, 0.2e-3};
  const glm::dvec3 phaseDir = glm::normalize(glm::dvec3(1.0, 0.0, 0.5));
  for (int ph = 0; ph < std::max(1, phases); ++ph) {
    const glm::dvec3 shift = phaseDir * (h * ph / std::max(1, phases));
    if (scene.name == "shaft-on-edge") {
      // The shaft leans over the edge (the Z axis), its axis `d` inside its radius 2.5 mm from the burr centre.
      for (double d : shaftDepths)
        for (double deg : {20.0, 40.0, 60.0}) {
          const double th = deg * kRadiansPerDegree, s0 = 2.5e-3;
          const glm::dvec3 dir(-std::sin(th), std::cos(th), 0.0), n(std::cos(th), std::sin(th), 0.0);
          const glm::dvec3 c = n * (tool.shaftRadius - d) - dir * s0 + glm::dvec3(0, 0, shift.z);
          out.push_back({Pose{c, rotationBetween({0, 1, 0}, dir)}, c + n * 1.5e-3, d});
        }
      continue;
    }
    if (scene.name == "hole") {
      // Tilted toward +x, the burr pushed d into the −x wall and the bottom; at 30° the shaft also meets
      // the far rim. The phase shifts along Z (the wall curves away a little).
      for (double d : holeDepths)
        for (double deg : {15.0, 30.0}) {
          const double th = deg * kRadiansPerDegree;
          const glm::dvec3 dir(std::sin(th), std::cos(th), 0.0);
          const glm::dvec3 c = glm::dvec3(-(kHoleR - tool.tipRadius) - d, -kHoleDepth + tool.tipRadius - d, shift.x);
          out.push_back({Pose{c, rotationBetween({0, 1, 0}, dir)}, glm::dvec3(0.0, 1e-3, shift.x), d});
        }
      continue;
    }
    glm::dvec3 n, contact;  // outward normal of the material and the touched surface point
    if (scene.name == "half-space") n = {0, 1, 0}, contact = {0, 0, 0};
    else if (scene.name == "plate") n = {0, 1, 0}, contact = {0, 0.5 * kPlate, 0};
    else if (scene.name == "ball") n = glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), contact = kBallR * n;
    else if (scene.name == "bowl") n = -glm::normalize(glm::dvec3(0.35, -1.0, 0.0)), contact = -kBowlR * n;
    else if (scene.name == "edge") n = glm::normalize(glm::dvec3(1.0, 1.0, 0.0)), contact = {0, 0, 0};
    else throw std::runtime_error("no probes for scene '" + scene.name + "'");
    const glm::dvec3 t = glm::normalize(glm::cross(n, glm::dvec3(0, 0, 1)));
    for (double d : burrDepths)
      for (double deg : {0.0, 30.0, 60.0}) {
        const glm::dvec3 dir = std::cos(deg * kRadiansPerDegree) * n + std::sin(deg * kRadiansPerDegree) * t;
        // Along the edge the phase shifts along Z only (elsewhere the pose would leave the edge).
        const glm::dvec3 c = contact + n * (tool.tipRadius - d) +
                             (scene.name == "edge" ? glm::dvec3(0, 0, glm::length(shift)) : shift);
        out.push_back({Pose{c, rotationBetween({0, 1, 0}, dir)}, c + n * (d + 1.5e-3), d});
      }
  }
  return out;
}

}  // namespace millsim::measure
