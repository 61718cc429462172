#include "millsim/renderers/SurfacePointRenderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include "millsim/haptics/CutFront.h"
#include "millsim/haptics/HapticScene.h"

namespace millsim {

namespace {

class SurfacePointAlgorithm final : public HapticAlgorithm {
public:
  SurfacePointAlgorithm(const ToolGeometry& tool, int sphereVertices, int slices, int perSlice, double k,
                        double feedResistance)
      : k_(k), feed_{feedResistance, tool.tipRadius}, perSlice_(perSlice), heldSlice_(std::size_t(slices), glm::dvec3(0.0)) {
    // Sphere: a Fibonacci lattice spreads any number of points evenly.
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    if (tool.round()) {
      for (int i = 0; i < sphereVertices; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / sphereVertices;
        const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
        sphere_.push_back(tool.tipRadius * glm::dvec3(r * std::cos(golden * i), y, r * std::sin(golden * i)));
      }
    } else {
      headPoints(tool.head(), sphereVertices, golden);
    }
    // Slices cover the part of the shaft outside the burr head, evenly.
    const double y0 =
        tool.round() ? std::sqrt(std::max(0.0, tool.tipRadius * tool.tipRadius - tool.shaftRadius * tool.shaftRadius))
                     : std::min(0.5 * tool.tipLength, tool.shaftLength);
    for (int j = 0; j < slices; ++j) sliceY_.push_back(y0 + (tool.shaftLength - y0) * (j + 0.5) / slices);
    for (int v = 0; v < perSlice; ++v) {
      const double a = 2.0 * std::numbers::pi * v / perSlice;
      ring_.push_back(tool.shaftRadius * glm::dvec3(std::cos(a), 0.0, std::sin(a)));
    }
  }

  std::string name() const override { return "SurfacePointRenderer"; }

  void reset(const Pose& device) override {
    lastDrawn_ = device;
    cut_.reset(device.position);
    heldSphere_ = glm::dvec3(0.0);
    std::fill(heldSlice_.begin(), heldSlice_.end(), glm::dvec3(0.0));
  }

  void carryOver(const HapticAlgorithm& previous) override {
    const auto* p = dynamic_cast<const SurfacePointAlgorithm*>(&previous);
    if (!p || p->heldSlice_.size() != heldSlice_.size() || !(p->k_ > 0.0)) return;
    // The held forces are k · (penetration at entry): the same entry, the new k.
    const double scale = k_ / p->k_;
    lastDrawn_ = p->lastDrawn_;
    cut_ = p->cut_;
    heldSphere_ = p->heldSphere_ * scale;
    for (std::size_t j = 0; j < heldSlice_.size(); ++j) heldSlice_[j] = p->heldSlice_[j] * scale;
  }

  HapticOutput step(HapticScene& scene, const HapticInput& in) override {
    HapticOutput out;
    const Pose& device = in.device;
    if (!isFinite(device)) {
      out.drawnTool = lastDrawn_;  // a bad pose changes nothing and draws the last good one
      return out;
    }
    out.drawnTool = device;
    const glm::dvec3 c = device.position;
    const glm::dmat3 R = glm::mat3_cast(device.orientation);
    const double h = scene.voxelSize();

    // Eq. 14–17: the burr sphere.
    if (scene.inside(c)) {
      out.force = heldSphere_;  // eq. 17: past half immersion the sum would shrink and flip
      out.flags |= kFlagHeldForce;
    } else {
      glm::dvec3 f(0.0);
      for (const glm::dvec3& offset : sphere_) {
        const glm::dvec3 v = c + R * offset;
        if (!scene.inside(v)) continue;
        if (roundHead_) {
          f += penetration(scene, v, c, h);
        } else {
          const glm::dvec3 a = penetration(scene, v, c + R * target_[std::size_t(&offset - sphere_.data())], h);
          f += a;
          // A non-round head is not symmetric about its centre: its points turn it too.
          out.torque += glm::cross(v - c, a) * (k_ / double(sphere_.size()));
        }
        ++out.contacts;
      }
      out.force = k_ * f / double(sphere_.size());  // eq. 14, summed (eq. 16)
      heldSphere_ = out.force;
    }

    // Eq. 18–21: slices of the shaft.
    const glm::dvec3 axis = R * glm::dvec3(0.0, 1.0, 0.0);
    for (std::size_t j = 0; j < sliceY_.size(); ++j) {
      const glm::dvec3 centre = c + axis * sliceY_[j];
      glm::dvec3 reaction(0.0);
      if (scene.inside(centre)) {
        reaction = heldSlice_[j];  // eq. 19
        out.flags |= kFlagHeldForce;
      } else {
        for (const glm::dvec3& offset : ring_) {
          const glm::dvec3 v = centre + R * offset;
          if (!scene.inside(v)) continue;
          reaction += penetration(scene, v, centre, h);
          ++out.contacts;
        }
        reaction *= k_ / double(perSlice_);  // eq. 14's weighting, per slice (eq. 18)
        heldSlice_[j] = reaction;
      }
      out.torque += glm::cross(centre - c, reaction) / double(sliceY_.size());  // eq. 20–21
    }
    // Milling (MillSim's removal model; the paper's #2 cuts at the device at
    // once, which lets the hand push through any tissue unopposed): the cut
    // front advances towards the device at the feed speed, and the penalty
    // force meets what is not cut yet.
    // Past half immersion the force is held (eq. 17); a device that jumped in
    // (the mouse does) holds zero and would never cut: the feed then takes
    // the penalty of the burr's distance past the cut front, k/2 per metre
    // (about half the burr's points collide there).
    const bool touching = out.contacts > 0 || (out.flags & kFlagHeldForce) != 0;
    double push = glm::length(out.force);
    if (touching && !(push > 0.0) && scene.inside(c)) push = 0.5 * k_ * glm::length(c - cut_.centre());
    cut_.step(scene, feed_, c, c, touching, in.milling, push, in.dt);
    out.burrCentre = cut_.centre();
    out.cutHardness = cut_.hardness();
    sanitize(out, device);
    lastDrawn_ = out.drawnTool;
    return out;
  }

private:
  // A non-round head: `count` points over its surface (cutting-end disc, side,
  // shank-end disc), shared by area; each disc a sunflower spiral, the side
  // rings of evenly spaced points (so a ring wholly in material pushes no net
  // sideways), so each point stands for about the same area. Each point's
  // penetration (eq. 14) is measured towards its own target inside the head
  // rather than the centre: a disc point straight along the axis to the head's
  // middle plane, a side point straight to the axis — along the face normal
  // (the side's up to its slope), so a flat face pressed on a flat surface
  // pushes along that surface's normal.
  void headPoints(const BurrHead& b, int count, double golden) {
    roundHead_ = false;
    const double h = 0.5 * b.length, r0 = b.cuttingEndRadius(), r1 = b.shankEndRadius();
    const double a0 = std::numbers::pi * r0 * r0, a1 = std::numbers::pi * r1 * r1;
    const double slant = std::hypot(r1 - r0, b.length);
    const double side = std::numbers::pi * (r0 + r1) * slant;
    const double total = a0 + a1 + side;
    const int n0 = r0 > 0.0 ? std::max(1, int(std::lround(count * a0 / total))) : 0;
    const int n1 = r1 > 0.0 ? std::max(1, int(std::lround(count * a1 / total))) : 0;
    const int ns = std::max(3, count - n0 - n1);
    auto disc = [&](int n, double r, double y) {
      for (int i = 0; i < n; ++i) {
        const double rr = r * std::sqrt((i + 0.5) / n);
        sphere_.push_back({rr * std::cos(golden * i), y, rr * std::sin(golden * i)});
        target_.push_back({sphere_.back().x, 0.0, sphere_.back().z});
      }
    };
    disc(n0, r0, -h);
    const int rings = std::max(1, int(std::lround(std::sqrt(ns * slant / (std::numbers::pi * (r0 + r1))))));
    const int perRing = std::max(3, ns / rings);
    const double dr = r1 - r0;
    for (int j = 0; j < rings; ++j) {
      // Uniform in area along the slant: the area up to t grows as r0 t + (r1 − r0) t²/2.
      const double u = (j + 0.5) / rings;
      const double t = std::abs(dr) < 1e-15 ? u : (-r0 + std::sqrt(r0 * r0 + 2.0 * dr * u * (r0 + 0.5 * dr))) / dr;
      const double r = r0 + dr * t, y = -h + b.length * t;
      for (int i = 0; i < perRing; ++i) {
        const double a = 2.0 * std::numbers::pi * i / perRing + golden * j;
        sphere_.push_back({r * std::cos(a), y, r * std::sin(a)});
        target_.push_back({0.0, y, 0.0});
      }
    }
    disc(n1, r1, h);
  }

  // a_i of eq. 14: from a colliding vertex to where the segment towards the
  // centre leaves the material, found by half-voxel steps and the density
  // fraction of eq. 1 between the last two samples (the paper's eq. 15).
  static glm::dvec3 penetration(const HapticScene& scene, const glm::dvec3& v, const glm::dvec3& centre, double h) {
    const glm::dvec3 d = centre - v;
    const double len = glm::length(d);
    if (len <= 0.0) return glm::dvec3(0.0);
    const int steps = std::max(1, int(std::ceil(len / (0.5 * h))));
    double sPrev = scene.field(v);
    glm::dvec3 prev = v;
    for (int i = 1; i <= steps; ++i) {
      const glm::dvec3 p = v + d * (double(i) / steps);
      const double s = scene.field(p);
      if (s <= 0.0) {
        const double f = sPrev - s > 0.0 ? std::clamp(sPrev / (sPrev - s), 0.0, 1.0) : 1.0;
        return prev + (p - prev) * f - v;
      }
      prev = p;
      sPrev = s;
    }
    return d;  // inside all the way (cannot happen while the centre is outside)
  }

  double k_;
  FeedLaw feed_;
  CutFront cut_;  // where the burr cuts
  int perSlice_;
  std::vector<glm::dvec3> sphere_, ring_;  // sphere_: the head's points (a sphere for the round burr)
  std::vector<glm::dvec3> target_;  // a non-round head's points: where each one's penetration is measured towards
  bool roundHead_ = true;
  std::vector<double> sliceY_;
  glm::dvec3 heldSphere_{0.0};
  Pose lastDrawn_;
  std::vector<glm::dvec3> heldSlice_;
};

}  // namespace

const NodeType& SurfacePointRenderer::type() {
  static const NodeType t = makeNodeType<SurfacePointRenderer>(
      "SurfacePointRenderer", "hapticsRenderer", "MillSim haptics",
      "Algorithm #2: penalty force and torque from points on the tool's surface.");
  return t;
}

std::unique_ptr<HapticAlgorithm> SurfacePointRenderer::compile(const ToolGeometry& tool, HapticScene&) const {
  return std::make_unique<SurfacePointAlgorithm>(tool, sphereVertices.get(), slices.get(), verticesPerSlice.get(),
                                                 double(springConstant.get()), double(feedResistance.get()));
}

// Penalty forces on points of the tool: the stiffness is the shared spring,
// the resolutions the burr and shaft points; nothing holds the tool outside.
// Cost model (`millsim check`): every frame samples the field (and, in
// contact, its gradient) at every tool point, so a frame costs
// points x kNsPerPoint. Measured with `millsim bench rates --renderer
// SurfacePointRenderer` on the tooth phantom (2-core AMD EPYC VM shared with
// a build, release): sphereVertices 24 -> 1000 took 14.9 -> 149 us a frame,
// 137 ns per added point (in contact: field and gradient); slices 20 -> 200
// 15.5 -> 123 us, 75 ns per added shaft point (mostly free). The model takes
// the contact figure, rounded up. docs/algorithms.md, "Frame cost model".
FrameCostEstimate SurfacePointRenderer::estimateFrameCost(const FrameCostContext&) const {
  constexpr double kNsPerPoint = 140.0;
  const long points = long(sphereVertices.get()) + long(slices.get()) * long(verticesPerSlice.get());
  return {double(points) * kNsPerPoint * 1e-9,
          std::to_string(points) + " points (sphereVertices + slices x verticesPerSlice) x " +
              formatNumber(kNsPerPoint) + " ns",
          "lower sphereVertices, slices or verticesPerSlice"};
}

RendererTraits SurfacePointRenderer::traits() const {
  RendererTraits t;
  t.stiffnessField = "springConstant";
  t.resolutionSweeps = {{"sphereVertices", {"8", "16", "24", "48", "96", "192"}},
                        {"slices", {"5", "10", "20", "50", "100"}}};
  t.reference = ReferenceKind::Penalty;
  t.constrainsTool = false;
  t.compilesWithoutScene = true;
  return t;
}

}  // namespace millsim
