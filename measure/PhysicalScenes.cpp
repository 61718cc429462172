#include "measure/PhysicalScenes.h"

#include <algorithm>
#include <cmath>
#include <map>
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
  if (name == "ball" || name == "mesh-ball") {
    Shape s = ball(kBallR);
    PhysicalScene out{name, s, one(s)};
    out.fromMesh = name == "mesh-ball";
    return out;
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
                           "' (half-space, ball, bowl, edge, plate, shaft-on-edge, hole; mesh-ball)");
}

bool isPhysicalSceneName(const std::string& name) {
  const std::vector<std::string> names = physicalSceneNames();
  return name == "mesh-ball" || std::find(names.begin(), names.end(), name) != names.end();
}

MeshPart icosphere(double R, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> v;
  for (const glm::dvec3& p : {glm::dvec3(-1, t, 0), {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                              {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}})
    v.push_back(glm::normalize(p));
  std::vector<glm::uvec3> f{{0, 11, 5}, {0, 5, 1}, {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<unsigned, unsigned>, unsigned> middle;
    auto mid = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      if (const auto it = middle.find(key); it != middle.end()) return it->second;
      v.push_back(glm::normalize(v[a] + v[b]));
      return middle[key] = unsigned(v.size() - 1);
    };
    std::vector<glm::uvec3> next;
    for (const glm::uvec3& g : f) {
      const unsigned ab = mid(g.x, g.y), bc = mid(g.y, g.z), ca = mid(g.z, g.x);
      next.insert(next.end(), {{g.x, ab, ca}, {g.y, bc, ab}, {g.z, ca, bc}, {ab, bc, ca}});
    }
    f = std::move(next);
  }
  MeshPart part;
  part.name = "ball";
  for (const glm::dvec3& p : v) part.vertices.push_back(glm::vec3(R * p));
  part.triangles = std::move(f);
  return part;
}

std::unique_ptr<AnalyticScene> voxelisePhysical(const PhysicalScene& scene, double h) {
  if (!scene.fromMesh) return voxelise(scene.shape, h);
  SurfaceMesh mesh;
  mesh.format = "test";
  mesh.parts.push_back(icosphere(kBallR, 5));
  return voxeliseMesh(scene.shape, mesh, h);
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
    else if (scene.name == "ball" || scene.name == "mesh-ball") n = glm::normalize(glm::dvec3(0.3, 1.0, 0.2)), contact = kBallR * n;
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
