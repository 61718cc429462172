#include "millsim/renderers/LineProxyRenderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "millsim/haptics/HapticScene.h"
#include "millsim/renderers/ContactShares.h"
#include "millsim/renderers/DeepestPoint.h"
#include "millsim/renderers/FreeStart.h"
#include "millsim/renderers/ProxyPoint.h"
#include "millsim/renderers/WholeToolField.h"

namespace millsim {

namespace {

// How far the burr's proxy may slide in a frame beyond the hand's own motion
// (ProxyPoint::Params::maxSlipVoxels): a fifth of a voxel, 0.04 N a frame at
// the default stiffness and 0.1 mm voxels. Unlimited, a proxy held by refused
// slides slipped up to 0.2 mm at once (0.21 N) in 25 of 33 §8.2 replays at
// 984–1016 Hz while milling and in 18 while leaning; limited so, in none
// while milling and in 1 each leaning and holding (0.12 N); a quarter voxel
// let 0.058 N steps through in the lean (docs/algorithms.md, #1).
constexpr double kBurrSlipVoxels = 0.2;

// holdWholeTool: a part of the tool within this many voxels of the surface
// touches (the proxy's projection settles to 1e-3 of a voxel).
constexpr double kTouch = 0.02;

// holdWholeTool: what a tracked shaft line's move must gain (voxels). A shaft
// across a round rim is about as deep along many lines; followed freely, its
// plane turned ±7° frame to frame and moved a wedged proxy 0.02 mm.
constexpr double kShaftGain = 0.02;

class LineProxyAlgorithm final : public HapticAlgorithm {
public:
  // The shaft's tracked deepest line (shaftSurface): its height on the axis,
  // angle round it and where it crosses into material (from the axis).
  struct ShaftLine {
    double y = 0.0, phi = 0.0, t = 0.0;
    bool active = false;
  };
  struct Params {
    int vertices;
    int translationSteps;
    int rotationSteps;
    double k;
    double feedResistance;
    ToolGeometry tool;
    bool burrSurface;  // the tip proxy keeps the burr's surface out (else the paper's centre vertex)
    bool shaftSurface;  // the shaft's deepest line pushes, force and torque (else the paper's torque only)
    bool wholeTool;     // the burr's proxy holds the shaft out too (needs burrSurface and shaftSurface)
  };

  LineProxyAlgorithm(const Params& p, int proxyIterations)
      : p_(p),
        tip_(ProxyPoint::Params{.slideIterations = proxyIterations,
                                .maxSlideVoxels = 2.0,
                                .recedeTowardsProbe = p.burrSurface,
                                .refuseSinkingSlides = p.burrSurface,
                                .slideAlongCreases = p.burrSurface,
                                .descentOnly = p.burrSurface,
                                .maxSlipVoxels = p.burrSurface ? kBurrSlipVoxels
                                                               : std::numeric_limits<double>::infinity(),
                                .leaveSaddles = p.burrSurface}),
        shaft_(ProxyPoint::Params{.slideIterations = proxyIterations, .maxSlideVoxels = 2.0}),
        burr_(p.tool.tipRadius),
        before_(std::size_t(p.vertices)),
        after_(std::size_t(p.vertices)) {
    // Shaft vertices inside the burr sphere are the burr's to feel: one there
    // would "collide" with the wall of the burr's own hole, and the drawn shaft,
    // offset by its radius from an intersection closer to the tip than that
    // radius, would swing tens of degrees (seen in the §8.2 procedure).
    while (firstShaftVertex_ < p.vertices - 1 &&
           p.tool.shaftLength * double(firstShaftVertex_) / double(p.vertices - 1) < p.tool.tipRadius)
      ++firstShaftVertex_;
    // The shaft's surface: from where it leaves the burr sphere to its end.
    const double r = p.tool.tipRadius, rho = p.tool.shaftRadius;
    shaftY0_ = std::min(std::sqrt(std::max(0.0, r * r - rho * rho)), p.tool.shaftLength);
    // The seeds are kRing points round each centreline vertex, on a cylinder
    // grown so that a face touching the shaft anywhere between two vertices and
    // two ring points is inside one of them (as SurfacePointRenderer's seeds).
    const double along = 0.5 * p.tool.shaftLength / double(std::max(1, p.vertices - 1));
    shaftGrow_ = (rho + along) / std::cos(std::numbers::pi / kRing) - rho;
    for (int j = 0; j < kRing; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / kRing;
      ring_[std::size_t(j)] = {phi, glm::dvec3(std::cos(phi), 0.0, std::sin(phi))};
    }
  }

  std::string name() const override { return "LineProxyRenderer"; }

  void reset(const Pose& device) override {
    tip_.reset(device.position);
    shaft_.reset(device.position);
    s_ = State::at(device);
  }

  void carryOver(const HapticAlgorithm& previous) override {
    const auto* p = dynamic_cast<const LineProxyAlgorithm*>(&previous);
    if (!p) return;
    // The proxies stay where they were held; only the parameters change.
    tip_.setState(p->tip_.state());
    shaft_.setState(p->shaft_.state());
    s_ = p->s_;
  }

  HapticOutput step(HapticScene& scene, const HapticInput& in) override {
    HapticOutput out;
    const Pose& device = in.device;
    if (!isFinite(device)) {
      out.drawnTool = s_.lastDrawn;  // a bad pose changes nothing and draws the last good one
      return out;
    }
    out.drawnTool = device;
    const glm::dvec3 c = device.position;
    const glm::dvec3 dir = device.shaftDirection();

    // §4.2 and eq. 6: the burr centre vertex and its proxy. By default the
    // proxy is held against the scene dilated by the burr sphere (BurrField),
    // so the burr's surface, not its centre, meets the material; the paper's
    // variant holds the centre vertex itself on the surface.
    burr_.bind(scene);
    // The burr's proxy samples the scene within its radius and a couple of
    // voxels of where it is held: the scene keeps a dense copy of the voxels there.
    scene.focus(s_.startFree ? c : tip_.position(), p_.tool.tipRadius + 2.0 * scene.voxelSize());
    if (s_.startFree) {  // the first frame after a reset: the tip's proxy out of material along the axis (FreeStart.h)
      s_.startFree = false;
      const double h = scene.voxelSize();
      auto inside = [&](double d) { return p_.burrSurface ? burr_.value(c + dir * d) > 0.0 : scene.inside(c + dir * d); };
      const double s = firstFreeAlong(inside, h, p_.tool.shaftLength + p_.tool.tipRadius, 0.05 * h);
      if (s > 0.0) tip_.reset(c + dir * s);
    }
    const glm::dmat3 R = glm::mat3_cast(device.orientation);
    if (p_.wholeTool) {
      holdShaftPlane(scene, R);
      tip_.update(tool_, c);
    } else if (p_.burrSurface) {
      tip_.update(burr_, c);
    } else {
      tip_.update(scene, c);
    }
    const bool tipContact = tip_.inContact();
    // Held by the shaft alone, the burr touches nothing: it neither cuts nor
    // advances (holdWholeTool).
    const bool burrTouches = tipContact && (!p_.wholeTool || tool_.burrDepth(tip_.position()) > -kTouch * scene.voxelSize());
    const glm::dvec3 proxyPoint = tipContact ? tip_.position() : c;
    // The outward contact normal at the tip proxy: where the burr touches
    // (BurrField), or at the centre vertex's proxy (paper).
    glm::dvec3 tipNormal(0.0);
    if (tipContact) {
      tipNormal = p_.burrSurface ? burr_.outwardNormal(proxyPoint) : scene.outwardNormal(proxyPoint);
      if (p_.burrSurface && tipNormal == glm::dvec3(0.0) && glm::length(proxyPoint - c) > 0.0) tipNormal = glm::normalize(proxyPoint - c);
    }
    if (tipContact) {
      out.force = p_.k * (proxyPoint - c);
      out.hasProxy = true;
      out.proxy = proxyPoint;
      out.contacts = 1;
    }

    // §4.5, eq. 12–13: the drawn burr. With BurrField the proxy already is
    // the burr's centre; the paper's centre vertex sits on the surface and the
    // burr is drawn a radius out. The shaft is translated to the tip's proxy
    // (t_offset in Fig. 6).
    glm::dvec3 drawTip = c;
    if (tipContact) drawTip = p_.burrSurface ? proxyPoint : proxyPoint + tipNormal * p_.tool.tipRadius;
    const glm::dvec3 drawDir = p_.wholeTool      ? shaftReaction(scene, R, proxyPoint, out)
                               : p_.shaftSurface ? shaftSurface(scene, device, R, proxyPoint, out)
                                                 : shaftCentreline(scene, proxyPoint, dir, drawTip, out);
    out.drawnTool.position = drawTip;
    out.drawnTool.orientation = rotationBetween(dir, drawDir) * device.orientation;
    // Only the burr of a tip in contact cuts: a free burr is drawn at the
    // device, where it overlaps material its centre vertex cannot feel, and
    // cutting there would clear the surface before the proxy ever met it. In
    // contact the burr advances into the surface at the feed speed
    // |F| / (feedResistance · hardness), never deeper than the probe.
    // The advance accumulates while milling: the coverage stamp is
    // idempotent, so a burr that only ever reached one frame's feed past the
    // tangent position would stop cutting once that thin layer is gone.
    out.burrCuts = burrTouches;
    out.burrCentre = drawTip;
    // Depth is measured from the current tangent position, so when the
    // proxy follows the receding surface the burr does not advance twice.
    if (burrTouches && in.milling) {
      // The burr advances the way the hand pushes it (the spring's direction),
      // not along the contact normal: in the burr's own round pit the normal
      // hops between points of the rim, and measured along it the advance so
      // far read as none (the proxy slid up the pit's side), so #1 cut one
      // frame's feed and no more: 0.007 mm³ in the default lesson's milling.
      const double pushed = glm::length(proxyPoint - c);
      const glm::dvec3 n = pushed > 0.0 ? (proxyPoint - c) / pushed : tipNormal;
      const double previous = s_.cutting ? std::max(0.0, glm::dot(drawTip - s_.cutCentre, n)) : 0.0;
      // Harder tissue at the burr's leading point gives way more slowly.
      const double hardness =
          scene.hardness(drawTip - n * (previous + p_.tool.tipRadius + 0.5 * scene.voxelSize()));
      const double feed = hardness > 0.0 ? glm::length(out.force) / (p_.feedResistance * hardness) * in.dt : 0.0;
      out.cutHardness = hardness;
      const double depth = std::min(previous + feed, glm::length(proxyPoint - c));
      out.burrCentre = drawTip - n * depth;
      s_.cutCentre = out.burrCentre;
      s_.cutting = true;
    } else {
      s_.cutting = false;
    }

    s_.prevTip = proxyPoint;
    s_.prevDir = dir;
    sanitize(out, device);
    s_.lastDrawn = out.drawnTool;
    return out;
  }

private:
  // The paper's shaft (§4.3): centreline vertices; their intersection point,
  // found by the fraction method (eq. 1–4) on first contact and then tracked
  // by the probe–proxy algorithm, gives torque only (eq. 7–11). Returns the
  // drawn shaft's direction: offset by the shaft radius along the normal at
  // the intersection (§4.5, eq. 12–13).
  glm::dvec3 shaftCentreline(const HapticScene& scene, const glm::dvec3& proxyPoint, const glm::dvec3& dir,
                             const glm::dvec3& drawTip, HapticOutput& out) {
    int colliding = 0;
    double deepest = 0.0;
    glm::dvec3 deepestVertex(0.0);
    for (int i = firstShaftVertex_; i < p_.vertices; ++i) {
      const glm::dvec3 v = vertex(proxyPoint, dir, i);
      const double s = scene.field(v);
      if (s > 0.0) {
        ++colliding;
        if (s > deepest) deepest = s, deepestVertex = v;
      }
    }
    if (colliding == 0) {
      s_.shaftContact = false;
    } else if (!s_.shaftContact) {
      // §4.3.1: no collision at t−1: the fraction method along the motion.
      glm::dvec3 ip;
      if (!firstContact(scene, s_.prevTip, s_.prevDir, proxyPoint, dir, ip)) ip = deepestVertex;
      shaft_.placeInContact(ip);
      s_.shaftContact = true;
    } else {
      // §4.3.2: collision at t−1: the deepest vertex is the probe of the
      // probe–proxy algorithm, the last intersection point its proxy.
      shaft_.update(scene, deepestVertex);
    }
    if (!s_.shaftContact) return dir;
    const glm::dvec3 ip = shaft_.position();
    const glm::dvec3 r = ip - proxyPoint;                                    // eq. 7
    const glm::dvec3 ipProbe = proxyPoint + glm::length(r) * dir;            // eq. 8
    const glm::dvec3 g = ip - ipProbe;                                       // eq. 9
    const glm::dvec3 reaction = p_.k * g;                                    // eq. 10
    out.torque = glm::cross(r, reaction);                                    // eq. 11
    out.hasIntersection = true;
    out.intersection = ip;
    out.contacts += colliding;
    const glm::dvec3 ipOffset = ip + scene.outwardNormal(ip) * p_.tool.shaftRadius;
    const glm::dvec3 axis = ipOffset - drawTip;
    return glm::length(axis) > 1e-9 ? glm::normalize(axis) : dir;
  }

  // The shaft felt at its surface (the default; docs/algorithms.md, Algorithm
  // #1): its deepest line in material — the radial line out of the axis where
  // material comes nearest the axis, found from the vertices' ring seeds and
  // tracked from frame to frame — pushes the tool out by k times the depth,
  // force and torque, as the shaft of a rigid tool pressed on a rim is pushed.
  // The paper's centreline met material only once the shaft had sunk its
  // radius, and its reaction turned the hand without pushing it (100 % force
  // error with the shaft on an edge). Returns the drawn shaft's direction:
  // the device's. The push is felt, not drawn: turning the drawn tool about
  // its tip until the shaft is out (eq. 12–13) divides the depth by the
  // contact's height, and a contact just above the burr, on its own pit's rim,
  // turned the drawn tool 7.6° in a frame in the §8.2 procedure.
  glm::dvec3 shaftSurface(const HapticScene& scene, const Pose& device, const glm::dmat3& R, const glm::dvec3& tip,
                          HapticOutput& out) {
    const glm::dvec3 axis = R * glm::dvec3(0, 1, 0);
    const double rho = p_.tool.shaftRadius;
    const ShaftLine& line = findShaftLine(scene, R, tip);
    const double depth = rho - line.t;
    s_.shaftContact = line.active && depth > 0.0;
    if (!s_.shaftContact) return device.shaftDirection();
    const glm::dvec3 w = R * glm::dvec3(std::cos(line.phi), 0.0, std::sin(line.phi));
    const glm::dvec3 point = tip + line.y * axis + line.t * w;  // on the material's surface
    // The burr's push (tip proxy − device) and the shaft's share one push as
    // a rigid tool's (ContactShares.h). Summed, a shaft on a bowl's rim and
    // the burr in its wall pushed twice where one push clears both; at right
    // angles or beyond each pushes its own depth.
    const glm::dvec3 burrPush = tip - device.position;
    const BurrShaftShares shares = burrAndShaftShares(burrPush, -w, depth);
    out.force = shares.burr > 0.0 ? p_.k * shares.burr * (burrPush / glm::length(burrPush)) : glm::dvec3(0.0);
    const glm::dvec3 push = p_.k * shares.shaft * -w;
    out.force += push;
    out.torque += glm::cross(point - tip, push);
    out.hasIntersection = true;
    out.intersection = point;
    out.contacts += 1;
    return axis;
  }

  // The shaft's deepest line with the burr centre at `tip` (the tool turned
  // by R): the tracked one searched near where it was, else seeded from the
  // ring point deepest in material. Kept in s_.shaftLine (active: within a
  // voxel of touching).
  const ShaftLine& findShaftLine(const HapticScene& scene, const glm::dmat3& R, const glm::dvec3& tip) {
    const glm::dvec3 axis = R * glm::dvec3(0, 1, 0);
    const double h = scene.voxelSize(), rho = p_.tool.shaftRadius, y1 = p_.tool.shaftLength;
    auto refine = [&](ShaftLine line) {
      line.t = deepestOnShaft(scene, tip, R, rho, shaftY0_, y1, line.y, line.phi, line.t);
      line.active = rho - line.t > -h;  // within a voxel of touching: still tracked
      return line;
    };
    // The tracked line first, searched near where it was (tracking mode, t < rho).
    ShaftLine line;
    if (s_.shaftLine.active) {
      line = s_.shaftLine;
      line.t = std::min(line.t, 0.999 * rho);
      line = refine(line);
      // holdWholeTool: the line keeps its angle unless turning gains more
      // than kShaftGain voxels of depth at its new height (the angle of the
      // whole tool's plane; docs/algorithms.md, Algorithm #1).
      if (p_.wholeTool && line.active && line.t > 0.0 && line.phi != s_.shaftLine.phi) {
        const double kept = lineCrossing(scene, tip + std::clamp(line.y, shaftY0_, y1) * axis,
                                          R * glm::dvec3(std::cos(s_.shaftLine.phi), 0.0, std::sin(s_.shaftLine.phi)),
                                          line.t, -rho, rho + 4.0 * h);
        if (kept - line.t < kShaftGain * h) line.phi = s_.shaftLine.phi, line.t = kept;
      }
    }
    // Not touching: seed from the ring point deepest in material, if any.
    if (!(line.active && rho - line.t > 0.0)) {
      double best = 0.0;
      ShaftLine seed;
      for (int i = firstShaftVertex_; i < p_.vertices; ++i) {
        const double y = p_.tool.shaftLength * double(i) / double(p_.vertices - 1);
        if (y < shaftY0_) continue;
        // Most of the shaft is far from everything: one lookup skips its ring.
        if (!scene.mayHaveMaterialNear(tip + y * axis, rho + shaftGrow_)) continue;
        for (const RingSeed& r : ring_) {
          const double s = scene.field(tip + y * axis + (rho + shaftGrow_) * (R * r.local));
          if (s > best) best = s, seed = ShaftLine{y, r.phi, rho, true};
        }
      }
      if (seed.active) {
        seed = refine(seed);
        if (seed.active && (!line.active || seed.t < line.t)) line = seed;
      }
    }
    s_.shaftLine = line;
    return s_.shaftLine;
  }

  // holdWholeTool: the shaft's deepest line where the tool rested last frame
  // (the burr centre at its proxy, out of material), as the plane the proxy
  // is held out of this frame (WholeToolField). A shaft found already in
  // material — the hand moved it more than a voxel past a rim in one frame,
  // or the plane's first-order step missed the rim's curve — puts the proxy
  // out along the plane's normal first, and the proxy's own projection then
  // settles the burr and the shaft together.
  void holdShaftPlane(const HapticScene& scene, const glm::dmat3& R) {
    tool_.clearShaftPlane();
    const glm::dvec3 at = tip_.position();
    const ShaftLine& line = findShaftLine(scene, R, at);
    if (!line.active) return;
    const double depth = p_.tool.shaftRadius - line.t;
    const glm::dvec3 w = R * glm::dvec3(std::cos(line.phi), 0.0, std::sin(line.phi));
    tool_.setShaftPlane(at, w, depth);
    if (depth > 0.0) tip_.placeInContact(tool_.projectToSurface(at, 2.0 * scene.voxelSize()));
  }

  // holdWholeTool: the torque of the force the whole tool's proxy holds, F =
  // k·(proxy − device). Where the burr and the shaft both touch, F is split
  // between their normals (least squares, neither share pulling), where the
  // shaft alone touches it is all the shaft's; the shaft's part acts at its
  // contact point, the burr's through the burr centre. The drawn tool keeps
  // the device's orientation, translated with the proxy.
  glm::dvec3 shaftReaction(const HapticScene& scene, const glm::dmat3& R, const glm::dvec3& tip, HapticOutput& out) {
    const glm::dvec3 axis = R * glm::dvec3(0, 1, 0);
    const double tolerance = kTouch * scene.voxelSize();
    s_.shaftContact = tip_.inContact() && tool_.hasShaftPlane() && tool_.shaftDepth(tip) > -tolerance;
    if (!s_.shaftContact) return axis;
    const ShaftLine& line = s_.shaftLine;
    const glm::dvec3 w = R * glm::dvec3(std::cos(line.phi), 0.0, std::sin(line.phi));
    const glm::dvec3 point = tip + line.y * axis + (p_.tool.shaftRadius - tool_.shaftDepth(tip)) * w;  // on the plane
    const glm::dvec3 ns = tool_.shaftNormal();
    glm::dvec3 shaftForce = out.force;
    if (tool_.burrDepth(tip) > -tolerance) {
      const glm::dvec3 nb = burr_.contactNormal(tip);
      const double g = glm::dot(nb, ns), fb = glm::dot(out.force, nb), fs = glm::dot(out.force, ns);
      const double det = 1.0 - g * g;
      double share = det > 1e-6 ? (fs - g * fb) / det : 0.5 * fs;  // the shaft's, along ns
      if (det > 1e-6 && (fb - g * fs) / det < 0.0) share = fs;      // the burr's would pull: the shaft's alone
      shaftForce = std::max(share, 0.0) * ns;
    }
    out.torque += glm::cross(point - tip, shaftForce);
    out.hasIntersection = true;
    out.intersection = point;
    out.contacts += 1;
    return axis;
  }

  glm::dvec3 vertex(const glm::dvec3& tip, const glm::dvec3& dir, int i) const {
    return tip + dir * (p_.tool.shaftLength * double(i) / double(p_.vertices - 1));
  }

  // Samples the shaft vertices of a line into `values`; true if any collides.
  bool sample(const HapticScene& scene, const glm::dvec3& tip, const glm::dvec3& dir, std::vector<double>& values) const {
    bool any = false;
    for (int i = firstShaftVertex_; i < p_.vertices; ++i) {
      values[std::size_t(i)] = scene.field(vertex(tip, dir, i));
      any |= values[std::size_t(i)] > 0.0;
    }
    return any;
  }

  // Eq. 1–2 between two consecutive search poses: the most active vertex (the
  // smallest density fraction) gives the intersection point.
  glm::dvec3 intersection(const glm::dvec3& tipA, const glm::dvec3& dirA, const glm::dvec3& tipB,
                          const glm::dvec3& dirB) const {
    double best = 2.0;
    glm::dvec3 ip(0.0);
    for (int i = firstShaftVertex_; i < p_.vertices; ++i) {
      const double a = before_[std::size_t(i)], b = after_[std::size_t(i)];
      if (b <= 0.0) continue;  // not active
      const double fraction = a >= 0.0 ? 0.0 : std::clamp((0.0 - a) / (b - a), 0.0, 1.0);
      if (fraction < best) {
        best = fraction;
        ip = vertex(tipA, dirA, i) * (1.0 - fraction) + vertex(tipB, dirB, i) * fraction;
      }
    }
    return ip;
  }

  // §4.3.1, Fig. 6: translate step by step from t−1 to t (eq. 3), then rotate
  // step by step (eq. 4), stopping at the first step where a vertex collides.
  bool firstContact(const HapticScene& scene, const glm::dvec3& fromTip, const glm::dvec3& fromDir,
                    const glm::dvec3& toTip, const glm::dvec3& toDir, glm::dvec3& ip) {
    sample(scene, fromTip, fromDir, before_);
    const glm::dvec3 d = toTip - fromTip;
    glm::dvec3 tipA = fromTip;
    for (int n = 1; n <= p_.translationSteps; ++n) {
      const glm::dvec3 tipB = fromTip + d * (double(n) / p_.translationSteps);
      if (sample(scene, tipB, fromDir, after_)) {
        ip = intersection(tipA, fromDir, tipB, fromDir);
        return true;
      }
      std::swap(before_, after_);
      tipA = tipB;
    }
    const glm::dquat q = rotationBetween(fromDir, toDir);
    glm::dvec3 dirA = fromDir;
    for (int n = 1; n <= p_.rotationSteps; ++n) {
      const glm::dvec3 dirB =
          glm::normalize(glm::slerp(glm::dquat(1, 0, 0, 0), q, double(n) / p_.rotationSteps) * fromDir);
      if (sample(scene, toTip, dirB, after_)) {
        ip = intersection(toTip, dirA, toTip, dirB);
        return true;
      }
      std::swap(before_, after_);
      dirA = dirB;
    }
    return false;
  }

  Params p_;
  int firstShaftVertex_ = 1;  // the first vertex above the burr sphere
  ProxyPoint tip_;
  ProxyPoint shaft_;
  BurrField burr_;  // the scene dilated by the burr sphere (p_.burrSurface)
  WholeToolField tool_{burr_};  // burr_ and the shaft's plane of this frame (p_.wholeTool)
  // What moves frame to frame besides the two proxies: a plain struct (a
  // cross-fade copies it; a reset is a fresh one).
  struct State {
    glm::dvec3 prevTip{0.0};
    bool cutting = false;    // the burr cut last frame, at cutCentre
    bool startFree = true;   // the next step first moves a tip proxy that starts in material out of it
    glm::dvec3 cutCentre{0.0};
    glm::dvec3 prevDir{0.0, 1.0, 0.0};
    bool shaftContact = false;
    ShaftLine shaftLine;
    Pose lastDrawn;
    static State at(const Pose& device) {
      State s;
      s.prevTip = device.position;
      s.prevDir = device.shaftDirection();
      s.lastDrawn = device;
      return s;
    }
  };
  State s_;
  static constexpr int kRing = 8;  // seeds round each centreline vertex
  struct RingSeed {
    double phi;
    glm::dvec3 local;  // (cos phi, 0, sin phi): the radial direction in the tool's frame
  };
  std::array<RingSeed, kRing> ring_{};
  double shaftY0_ = 0.0, shaftGrow_ = 0.0;
  std::vector<double> before_, after_;  // vertex values at search steps n−1 and n (preallocated)
};

}  // namespace

const NodeType& LineProxyRenderer::type() {
  static const NodeType t = makeNodeType<LineProxyRenderer>(
      "LineProxyRenderer", "hapticsRenderer", "MillSim haptics",
      "Algorithm #1: proxy-based force and torque with the tool as a line of vertices.");
  return t;
}

// The burr is a sphere about the tip vertex (its proxy keeps the tip
// tipRadius off the surface, eq. 3-4): no other head can be represented.
std::string LineProxyRenderer::cannotCarry(const ToolGeometry& tool) const {
  if (tool.round()) return {};
  return "LineProxyRenderer cannot represent the MillTool shape \"" + std::string(burrShapeName(tool.shape)) +
         "\": it models the burr as a sphere about its tip vertex; use shape \"round\", or SurfacePointRenderer "
         "or BarbicRenderer";
}

std::unique_ptr<HapticAlgorithm> LineProxyRenderer::compile(const ToolGeometry& tool, HapticScene&) const {
  if (const std::string why = cannotCarry(tool); !why.empty()) throw std::runtime_error(why);
  return std::make_unique<LineProxyAlgorithm>(
      LineProxyAlgorithm::Params{
          .vertices = vertexCount.get(),
          .translationSteps = translationSteps.get(),
          .rotationSteps = rotationSteps.get(),
          .k = double(springConstant.get()),
          .feedResistance = double(feedResistance.get()),
          .tool = tool,
          .burrSurface = feelBurrSurface.get(),
          .shaftSurface = feelShaftSurface.get(),
          .wholeTool = feelBurrSurface.get() && feelShaftSurface.get() && holdWholeTool.get()},
      proxyIterations.get());
}

// A proxy on a spring: the stiffness is its spring, the resolution its
// centreline vertices, and the proxy never enters material.
// Cost model (`millsim check`, docs/algorithms.md "Frame cost model"): the
// worst frame is the burr's proxy at its most (a surface entry, then every
// tangent-plane step refused and tried twice halved: about 10 + 12 per step
// field evaluations, each some 45 samples with feelBurrSurface's BurrField)
// plus the shaft: the surface shaft's ring seeds (8 a vertex) and deepest
// line (about 200), or the paper's first-contact search (eq. 3–4, vertexCount
// x (1 + translationSteps + rotationSteps)); 55 ns a sample (`bench rates`,
// the paper's shaft: vertexCount 51 -> 1000 took 5.23 -> 57.7 us a frame).
// At the defaults (bench procedure, §8.2): milling frames p99 97 µs, worst
// 204 µs, against an estimate of 236 µs.
FrameCostEstimate LineProxyRenderer::estimateFrameCost(const FrameCostContext&) const {
  constexpr double kNsPerSample = 55.0;
  const long perEvaluation = feelBurrSurface.get() ? 45 : 1;
  // Each tangent-plane step: three tries of a projection of up to 4 Newton
  // steps; holdWholeTool's projection out of the burr and the shaft's plane
  // takes up to 6 (WholeToolField::projectToSurface).
  const bool wholeTool = feelBurrSurface.get() && feelShaftSurface.get() && holdWholeTool.get();
  const long burr = perEvaluation * (10L + (wholeTool ? 18L : 12L) * proxyIterations.get());
  const long shaft = feelShaftSurface.get() ? long(vertexCount.get()) * 8L + 200L
                                            : long(vertexCount.get()) * (1L + translationSteps.get() + rotationSteps.get());
  const std::string shaftModel = feelShaftSurface.get() ? "vertexCount x 8 ring seeds + 200 for the shaft's deepest line"
                                                        : "vertexCount x (1 + translationSteps + rotationSteps) for a "
                                                          "first shaft contact";
  return {double(burr + shaft) * kNsPerSample * 1e-9,
          std::to_string(burr + shaft) + " samples (" + std::to_string(burr) + " for the burr's proxy: " +
              std::to_string(perEvaluation) + " per evaluation x (10 + " + (wholeTool ? "18" : "12") +
              " x proxyIterations); " + shaftModel + ") x " +
              formatNumber(kNsPerSample) + " ns",
          feelShaftSurface.get() ? "lower proxyIterations or vertexCount" : "lower vertexCount, translationSteps or rotationSteps"};
}

RendererTraits LineProxyRenderer::traits() const {
  RendererTraits t;
  t.stiffnessField = "springConstant";
  t.resolutionSweeps = {{"vertexCount", {"6", "11", "26", "51", "101", "251"}}};
  t.reference = ReferenceKind::Proxy;
  t.constrainsTool = true;
  t.compilesWithoutScene = true;
  return t;
}

}  // namespace millsim
