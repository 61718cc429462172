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
#include "millsim/math/Pose.h"
#include "millsim/renderers/ContactShares.h"
#include "millsim/renderers/DeepestPoint.h"

namespace millsim {

namespace {

class SurfacePointAlgorithm final : public HapticAlgorithm {
  // The deepest-points force (deepestPoints): the last frame's contacts, where to look first.
  struct Track {
    bool shaft = false;
    glm::dvec3 u{0.0};       // burr: centre towards material (its deepest line)
    glm::dvec3 normal{0.0};  // burr: the contact's normal (held while the centre is inside)
    double y = 0.0, phi = 0.0;  // shaft: the radial line's height and angle
    double t = 0.0;          // where the line met material
  };

public:
  SurfacePointAlgorithm(const ToolGeometry& tool, int sphereVertices, int slices, int perSlice, double k,
                        double feedResistance, bool deepest)
      : k_(k), headReach_(tool.head().boundingRadius()), feed_{feedResistance, tool.tipRadius}, perSlice_(perSlice) {
    s_.heldSlice.assign(std::size_t(slices), glm::dvec3(0.0));
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
    deepest_ = deepest;
    if (deepest_) prepareDeepest(tool, y0);
  }

  std::string name() const override { return "SurfacePointRenderer"; }

  void reset(const Pose& device) override { s_.resetAt(device); }

  void carryOver(const HapticAlgorithm& previous) override {
    const auto* p = dynamic_cast<const SurfacePointAlgorithm*>(&previous);
    if (!p || p->s_.heldSlice.size() != s_.heldSlice.size() || !(p->k_ > 0.0) || p->deepest_ != deepest_) return;
    s_ = p->s_;  // the same size: no allocation
    // The held forces are k · (penetration at entry): the same entry, the
    // new k. The contacts are geometry: the same whatever k.
    const double scale = k_ / p->k_;
    s_.heldSphere *= scale;
    for (glm::dvec3& f : s_.heldSlice) f *= scale;
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
    const glm::dmat3 R = glm::mat3_cast(device.orientation);
    const double h = scene.voxelSize();
    // The burr's points and their contacts' searches lie within its reach
    // and a couple of voxels: the scene keeps a dense copy of the voxels there.
    scene.focus(c, headReach_ + 2.0 * h);
    if (deepest_) {
      stepDeepest(scene, c, R, out);
      return finish(scene, in, out);
    }

    // Eq. 14–17: the burr sphere.
    if (scene.inside(c)) {
      out.force = s_.heldSphere;  // eq. 17: past half immersion the sum would shrink and flip
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
      s_.heldSphere = out.force;
    }

    // Eq. 18–21: slices of the shaft.
    const glm::dvec3 axis = R * glm::dvec3(0.0, 1.0, 0.0);
    for (std::size_t j = 0; j < sliceY_.size(); ++j) {
      const glm::dvec3 centre = c + axis * sliceY_[j];
      glm::dvec3 reaction(0.0);
      if (scene.inside(centre)) {
        reaction = s_.heldSlice[j];  // eq. 19
        out.flags |= kFlagHeldForce;
      } else {
        for (const glm::dvec3& offset : ring_) {
          const glm::dvec3 v = centre + R * offset;
          if (!scene.inside(v)) continue;
          reaction += penetration(scene, v, centre, h);
          ++out.contacts;
        }
        reaction *= k_ / double(perSlice_);  // eq. 14's weighting, per slice (eq. 18)
        s_.heldSlice[j] = reaction;
      }
      out.torque += glm::cross(centre - c, reaction) / double(sliceY_.size());  // eq. 20–21
    }
    return finish(scene, in, out);
  }

private:
  // Past half immersion (the burr centre in material) the held line turns,
  // kHeldTurn a frame, towards where the centre's way out is shorter by
  // more than 0.002 voxels, measured 0.05 rad to either side of it in two
  // directions (0.02 voxels stalled it 22° off: near a face's normal a
  // turn gains only 1.5 µm). Pushed past a convex edge straight down its
  // bisector the held line stayed on the bisector, a saddle (the way out is
  // longest there among its neighbours), where a rigid burr slides onto a
  // face: 45° off on those poses. Elsewhere the held line is where the way
  // out is shortest, and it stays put. `t.t` is the held line's crossing (≤ 0).
  void turnHeldLine(const HapticScene& scene, const glm::dvec3& c, double h, Track& t) const {
    constexpr double kHeldTurn = 0.05;  // rad a frame, as sphereContact's tracked lines
    const Tangents basis = tangentsOf(t.u);
    const glm::dvec3 t1 = basis.t1, t2 = basis.t2;
    double best = t.t + 0.002 * h;  // a crossing nearer zero is a shorter way out
    glm::dvec3 to(0.0);
    double at = t.t;
    for (const glm::dvec3& e : {t1, -t1, t2, -t2}) {
      const glm::dvec3 u = glm::normalize(t.u + std::tan(kHeldTurn) * e);
      const double crossing = lineCrossing(scene, c, u, t.t, -1.0, r_);
      if (crossing > best) best = crossing, to = u, at = crossing;
    }
    if (to == glm::dvec3(0.0)) return;
    t.u = to, t.normal = -to, t.t = at;
  }

  HapticOutput finish(HapticScene& scene, const HapticInput& in, HapticOutput& out) {
    const Pose& device = in.device;
    const glm::dvec3 c = device.position;
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
    if (touching && !(push > 0.0) && scene.inside(c)) push = (deepest_ ? 1.0 : 0.5) * k_ * glm::length(c - s_.cut.centre());
    s_.cut.step(scene, feed_, c, c, touching, in.milling, push, in.dt);
    out.burrCentre = s_.cut.centre();
    out.cutHardness = s_.cut.hardness();
    sanitize(out, device);
    s_.lastDrawn = out.drawnTool;
    s_.fresh = false;
    return out;
  }

  // ---- the default force: the tool's deepest points (deepestPoints TRUE) ----

  // Every contact is a line through the tool where it is locally deepest in
  // material (DeepestPoint.h); each pushes k times its depth along its
  // normal, and the torque is those pushes' moment. The surface points only find where
  // to look: each is tested on a surface grown by the largest gap between
  // points (a flat face the burr or shaft touches anywhere reaches one of
  // them). The burr's first contact starts along the sum of its points'
  // penetrations; a point in material that no contact explains seeds another
  // (a face more than 60° from the burr's first, or a shaft contact). Every
  // contact is then tracked from frame to frame, also through a gap of up to
  // a voxel, so that it comes and goes at zero depth.
  void prepareDeepest(const ToolGeometry& tool, double y0) {
    r_ = tool.tipRadius, rho_ = tool.shaftRadius, y0_ = y0, y1_ = tool.shaftLength;
    // The largest angle from any direction to its nearest sphere point, over 4000 directions.
    double gap = 0.0;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < 4000; ++i) {
      const double y = 1.0 - 2.0 * (i + 0.5) / 4000, rr = std::sqrt(std::max(0.0, 1.0 - y * y));
      const glm::dvec3 d(rr * std::cos(golden * i), y, rr * std::sin(golden * i));
      double best = -1.0;
      for (const glm::dvec3& p : sphere_) best = std::max(best, glm::dot(d, p) / tool.tipRadius);
      gap = std::max(gap, std::acos(std::clamp(best, -1.0, 1.0)));
    }
    sphereGrow_ = tool.tipRadius * (1.0 / std::cos(gap) - 1.0);
    // The shaft's: a 90° edge across the shaft touching it half-way between two
    // slices and two of a slice's points must reach one of them.
    const double along = sliceY_.size() > 1 ? 0.5 * (sliceY_[1] - sliceY_[0]) : 0.5 * (tool.shaftLength - y0);
    shaftGrow_ = (tool.shaftRadius + along) / std::cos(std::numbers::pi / perSlice_) - tool.shaftRadius;
    inside_.assign(sphere_.size() + sliceY_.size() * ring_.size(), 0);
  }

  void stepDeepest(HapticScene& scene, const glm::dvec3& c, const glm::dmat3& R, HapticOutput& out) {
    const double h = scene.voxelSize();
    PointContact contacts[kMaxPointContacts];
    Track found[kMaxPointContacts];
    int n = 0;
    bool seedBurr = false;  // the round burr outside material looks for new faces
    auto add = [&](const Track& t, const PointContact& pc) {
      // A contact within a voxel of touching stays tracked (the same contact
      // when it touches again, entering at depth 0).
      if (pc.depth <= -h) return false;
      // The same contact found again, or another line into the same face: a
      // burr in its own round pit is about as deep along many lines, and
      // contacts that came and went among them would shake the hand. The
      // burr keeps its first contact and adds only faces more than 60° away;
      // a shaft contact within 30° and 4 voxels of another is the same one.
      for (int j = 0; j < n; ++j)
        if (found[j].shaft == t.shaft &&
            (t.shaft ? glm::dot(contacts[j].normal, pc.normal) > 0.866 && glm::length(contacts[j].point - pc.point) < 4.0 * h
                     : glm::dot(contacts[j].normal, pc.normal) > 0.5))
          return false;
      int slot = n;
      if (n == kMaxPointContacts) {
        // Full: the new contact takes the place of the one that pushes least
        // (never the first), if it would push more. Faces of the burr's own
        // pit that only came near filled all six places in the §8.2 replay
        // while the shaft leaned into the rim, and the shaft's contact came
        // in 73 µm deep (0.17 N in one frame) when one of them left.
        const int first = firstBurr(found, n);
        const PointContact* firstContact = first >= 0 && !t.shaft ? &contacts[first] : nullptr;
        slot = leastPushing(found, contacts, n);
        if (slot < 0 || !(pushDepth(pc, firstContact) > pushDepth(found, contacts, first, slot))) return false;
      } else {
        ++n;
      }
      found[slot] = t, contacts[slot] = pc;
      return true;
    };
    auto shaft = [&](Track t) {
      t.t = deepestOnShaft(scene, c, R, rho_, y0_, y1_, t.y, t.phi, t.t);
      const glm::dvec3 w = R * glm::dvec3(std::cos(t.phi), 0.0, std::sin(t.phi));
      return add(t, {c + t.y * (R * glm::dvec3(0, 1, 0)) + t.t * w, -w, rho_ - t.t});
    };
    if (!roundHead_) {
      // A non-round head: its points' penetrations towards their targets
      // (headPoints), the deepest one's length along their sum; held while
      // the centre is inside (eq. 17).
      PointContact head;
      if (scene.inside(c)) out.flags |= kFlagHeldForce, head = s_.heldHead;
      else head = headContact(scene, c, R, h);
      Track t;
      if (add(t, head)) s_.heldHead = head;
      else s_.heldHead = PointContact{};
    } else if (scene.inside(c)) {
      // Past half immersion the burr's lines would find the far side: keep
      // the last direction (eq. 17 holds the whole force) and measure along it.
      out.flags |= kFlagHeldForce;
      Track t;
      for (int j = 0; j < s_.tracked; ++j)
        if (!s_.track[j].shaft) {
          t = s_.track[j];
          break;
        }
      if (t.u == glm::dvec3(0.0) && glm::length(c - s_.cut.centre()) > 0.0)
        t.u = glm::normalize(c - s_.cut.centre()), t.normal = -t.u, t.t = 0.0;
      // The first frame after a reset inside material (a run that starts
      // there, or a swap mid-press): no line to hold. The burr came in along
      // its axis, the way it comes out of the hole it is in (FreeStart.h).
      if (t.u == glm::dvec3(0.0) && s_.fresh) {
        const glm::dvec3 axis = R * glm::dvec3(0.0, 1.0, 0.0);
        t.u = -axis, t.normal = axis, t.t = 0.0;
      }
      if (t.u != glm::dvec3(0.0)) {
        // No cap on the depth: a force that stopped growing would let the
        // hand push on for free and take more back on the way out.
        t.t = lineCrossing(scene, c, t.u, std::min(t.t, 0.0), -1.0, r_);
        turnHeldLine(scene, c, h, t);
        const double depth = r_ - glm::dot(t.t * t.u, -t.normal);
        add(t, {c - (r_ - depth) * t.normal, t.normal, depth});
      }
    } else {
      // The burr: one contact, along the sum of its points' penetrations (eq.
      // 14's a_i, on the grown sphere): a point enters at zero, so the line
      // turns continuously — also for a burr in its own round pit, where the
      // material is about as deep along many lines — and the contact's normal
      // and depth are measured where it meets the surface (sphereContact).
      // A tracked line is searched near where it was (sphereContact's
      // tracking mode, t < r), also when it had lifted off.
      auto tracked = [&](Track t) {
        t.t = std::min(t.t, 0.999 * r_);
        return t;
      };
      Track t;
      int firstTracked = -1;
      for (int j = 0; j < s_.tracked; ++j)
        if (!s_.track[j].shaft) {
          t = tracked(s_.track[j]), firstTracked = j;  // in contact: from the last frame's first line
          break;
        }
      if (t.u == glm::dvec3(0.0) && scene.mayHaveMaterialNear(c, r_ + sphereGrow_)) {
        glm::dvec3 sum(0.0);
        for (const glm::dvec3& offset : sphere_) {
          const glm::dvec3 v = c + (1.0 + sphereGrow_ / r_) * (R * offset);
          if (scene.inside(v)) sum += penetration(scene, v, c, h);
        }
        if (glm::length(sum) > 0.0) t.t = r_, t.u = -glm::normalize(sum);
      }
      if (t.u != glm::dvec3(0.0)) {
        const PointContact pc = burrContact(scene, c, t);
        add(t, pc);
      }
      // Second faces more than 60° from the first (a hole's wall and bottom):
      // last frame's again, then any new one. Found afresh each frame they
      // came and went with the seeds, 0.07 mm deep, while the burr milled
      // its own pit.
      for (int j = firstTracked + 1; firstTracked >= 0 && j < s_.tracked; ++j)
        if (!s_.track[j].shaft) {
          Track face = tracked(s_.track[j]);
          add(face, burrContact(scene, c, face));
        }
      seedBurr = true;
    }
    // Every tracked contact before any new one: a new face of the burr's
    // took the last place from the leaning shaft's contact, 67 µm deep, in
    // the §8.2 replay (0.17 N in one frame).
    for (int j = 0; j < s_.tracked; ++j)
      if (s_.track[j].shaft) shaft(s_.track[j]);
    if (seedBurr)
      seed(scene, c, R, found, contacts, n, false, [&](std::size_t i) {
        Track face;
        face.u = R * sphere_[i] / r_, face.t = r_;
        const PointContact pc = burrContact(scene, c, face);
        return add(face, pc);
      });
    seed(scene, c, R, found, contacts, n, true, [&](std::size_t i) {
      Track t;
      t.shaft = true, t.y = sliceY_[i / ring_.size()];
      const glm::dvec3& v = ring_[i % ring_.size()];
      t.phi = std::atan2(v.z, v.x), t.t = rho_;
      return shaft(t);
    });
    // The contacts push together as a rigid tool is pushed out of them, no
    // contact harder than k times its own depth (ContactShares.h): contacts
    // less than 90° apart share one push, contacts at right angles or beyond
    // push k times their depths each. Not the rigid tool's whole answer in a
    // wedge: where the burr is on one wall and the leaning shaft on the
    // opposite rim, its shares grow many times the depths and every ripple of
    // the contacts' normals came through as a jolt (1.4 N frame to frame in
    // the §8.2 lean).
    glm::dvec3 normals[kMaxPointContacts]{};  // zeroed: GCC cannot see that only the first n are read
    double depths[kMaxPointContacts]{}, shares[kMaxPointContacts];
    out.contacts = 0;
    const PointContact* burr = nullptr;  // the burr's first contact, touching or near
    for (int j = 0; j < n; ++j) {
      const bool first = !found[j].shaft && !burr;
      if (first) burr = &contacts[j];
      normals[j] = contacts[j].normal, depths[j] = contacts[j].depth;
      if (!(contacts[j].depth > 0.0)) continue;  // near, not touching
      ++out.contacts;
      if (!found[j].shaft && !first) depths[j] *= secondFaceWeight(*burr, contacts[j]);
    }
    contactShares(normals, depths, n, shares);
    for (int j = 0; j < n; ++j) {
      const glm::dvec3 f = k_ * shares[j] * contacts[j].normal;
      out.force += f;
      out.torque += glm::cross(contacts[j].point - c, f);
    }
    s_.tracked = n;
    std::copy(found, found + n, s_.track);
  }

  // A second face of the burr's is a face only more than 60° from its first
  // contact (closer, it is the same face), so it pushes weighted from 0 at
  // 60° to whole at 90°: not at once as it turns past 60°.
  static double secondFaceWeight(const PointContact& first, const PointContact& face) {
    const double angle = std::acos(std::clamp(glm::dot(first.normal, face.normal), -1.0, 1.0));
    return std::clamp((angle - std::numbers::pi / 3.0) / (std::numbers::pi / 6.0), 0.0, 1.0);
  }
  // The burr's first contact among the found ones (the first that is not the shaft's), −1 if none.
  static int firstBurr(const Track* found, int n) {
    for (int j = 0; j < n; ++j)
      if (!found[j].shaft) return j;
    return -1;
  }
  // How deep a contact pushes: its depth, a burr's second face weighted
  // against the burr's first contact (`first`; null for the first itself and
  // the shaft's contacts); the depth (≤ 0) of one that does not touch, so
  // that of two such the nearer ranks higher.
  static double pushDepth(const PointContact& pc, const PointContact* first) {
    return pc.depth > 0.0 && first ? pc.depth * secondFaceWeight(*first, pc) : pc.depth;
  }
  // The same for the found contact in `slot`; `first` is firstBurr's answer.
  static double pushDepth(const Track* found, const PointContact* contacts, int first, int slot) {
    return pushDepth(contacts[slot], found[slot].shaft || slot == first || first < 0 ? nullptr : &contacts[first]);
  }
  // The contact that pushes least when all places are taken, never the
  // burr's first (the one its second faces are weighed against).
  static int leastPushing(const Track* found, const PointContact* contacts, int n) {
    const int first = firstBurr(found, n);
    int slot = -1;
    for (int j = 0; j < n; ++j)
      if (j != first && (slot < 0 || pushDepth(found, contacts, first, j) < pushDepth(found, contacts, first, slot)))
        slot = j;
    return slot;
  }

  // The burr's contact near t.u (updates t). Its point is on the line
  // through the centre along the normal: a sphere's contact force passes
  // through its centre, so the burr alone gives no torque.
  PointContact burrContact(const HapticScene& scene, const glm::dvec3& c, Track& t) const {
    PointContact pc;
    t.t = sphereContact(scene, c, r_, t.u, t.t, pc.normal, pc.depth);
    pc.point = c - (r_ - pc.depth) * pc.normal, t.normal = pc.normal;
    return pc;
  }

  PointContact headContact(const HapticScene& scene, const glm::dvec3& c, const glm::dmat3& R, double h) const {
    glm::dvec3 sum(0.0);
    PointContact pc;
    for (std::size_t i = 0; i < sphere_.size(); ++i) {
      const glm::dvec3 v = c + R * sphere_[i];
      if (!scene.inside(v)) continue;
      const glm::dvec3 a = penetration(scene, v, c + R * target_[i], h);
      sum += a;
      if (glm::length(a) > pc.depth) pc.depth = glm::length(a), pc.point = v + a;
    }
    if (glm::length(sum) > 0.0) pc.normal = glm::normalize(sum);
    else pc.depth = 0.0;
    return pc;
  }

  // Tests the burr's (or shaft's) points on the grown surface and, while some
  // point in material is not explained by a contact (not inside its tangent
  // plane, give or take the growth and half its depth: a concave surface
  // curls up past the plane; for the burr, within 60° of a contact's
  // normal), starts a contact from the unexplained point nearest their
  // centroid. The burr's points are explained by the burr's contacts only
  // (the shaft's are found first, and by their planes the hole's 30° poses
  // lost the burr's wall).
  template <class Start>
  void seed(const HapticScene& scene, const glm::dvec3& c, const glm::dmat3& R, const Track* found,
            const PointContact* contacts, int& n, bool onShaft, const Start& start) {
    const std::size_t count = onShaft ? sliceY_.size() * ring_.size() : sphere_.size();
    const double grow = onShaft ? shaftGrow_ : sphereGrow_, h = scene.voxelSize();
    auto point = [&](std::size_t i) {
      if (!onShaft) return c + (1.0 + grow / r_) * (R * sphere_[i]);
      const glm::dvec3& v = ring_[i % ring_.size()];
      return c + R * (glm::dvec3(0.0, sliceY_[i / ring_.size()], 0.0) + (1.0 + grow / rho_) * v);
    };
    char* inside = inside_.data() + (onShaft ? sphere_.size() : 0);
    // Most of the shaft, and a burr in the air, are far from everything: one
    // lookup per slice (or for the whole sphere) skips its points.
    const std::size_t group = onShaft ? ring_.size() : count;
    for (std::size_t g = 0; g < count; g += group) {
      const glm::dvec3 centre = onShaft ? c + R * glm::dvec3(0.0, sliceY_[g / group], 0.0) : c;
      const bool near = scene.mayHaveMaterialNear(centre, onShaft ? rho_ + grow : r_ + grow);
      for (std::size_t i = g; i < g + group; ++i) inside[i] = near && scene.inside(point(i));
    }
    for (int attempt = 0; attempt < 3; ++attempt) {
      glm::dvec3 sum(0.0);
      int left = 0;
      for (std::size_t i = 0; i < count; ++i) {
        if (!inside[i]) continue;
        const glm::dvec3 p = point(i);
        for (int j = 0; j < n && inside[i]; ++j) {
          if (!onShaft && found[j].shaft) continue;  // the burr's points by the burr's contacts only
          if (glm::dot(p - contacts[j].point, contacts[j].normal) < grow + 0.5 * contacts[j].depth + h ||
              (!onShaft && glm::dot(glm::normalize(p - c), contacts[j].normal) < -0.5))
            inside[i] = 0;
        }
        if (inside[i]) sum += p, ++left;
      }
      if (left == 0) return;
      std::size_t best = count;
      double nearest = 1e300;
      for (std::size_t i = 0; i < count; ++i)
        if (inside[i] && glm::length(point(i) - sum / double(left)) < nearest)
          nearest = glm::length(point(i) - sum / double(left)), best = i;
      inside[best] = 0;
      if (!start(best)) return;  // the nearest candidate found nothing: the rest would not either
    }
  }

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
  double headReach_;  // the burr's points lie within this of its centre (m)
  FeedLaw feed_;
  int perSlice_;
  std::vector<glm::dvec3> sphere_, ring_;  // sphere_: the head's points (a sphere for the round burr)
  std::vector<glm::dvec3> target_;  // a non-round head's points: where each one's penetration is measured towards
  bool roundHead_ = true;
  bool deepest_ = false;
  double r_ = 0.0, rho_ = 0.0, y0_ = 0.0, y1_ = 0.0, sphereGrow_ = 0.0, shaftGrow_ = 0.0;
  std::vector<char> inside_;  // per surface point: in material on the grown surface (sized at compile)
  std::vector<double> sliceY_;
  // What moves frame to frame: a plain struct (a cross-fade copies it; its
  // vector is sized at compile, so neither a copy nor a reset allocates).
  struct State {
    Pose lastDrawn;
    CutFront cut;  // where the burr cuts
    glm::dvec3 heldSphere{0.0};
    std::vector<glm::dvec3> heldSlice;
    Track track[kMaxPointContacts];
    int tracked = 0;
    PointContact heldHead;  // a non-round head's last contact (held while its centre is inside)
    bool fresh = true;      // no step since the last reset (a burr centre inside then holds along the axis)
    void resetAt(const Pose& device) {
      lastDrawn = device;
      cut.reset(device.position);
      heldSphere = glm::dvec3(0.0);
      std::fill(heldSlice.begin(), heldSlice.end(), glm::dvec3(0.0));
      tracked = 0;
      heldHead = PointContact{};
      fresh = true;
    }
  };
  State s_;
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
                                                 double(springConstant.get()), double(feedResistance.get()),
                                                 deepestPoints.get());
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
// With deepestPoints each tracked contact's line search adds about
// kUsPerContact: the §8.2 procedure's lean (`millsim bench procedure`, same
// VM) took 54 us p50 with about two contacts, against 21 us for the paper's
// sum; the model takes the most contacts a frame tracks.
FrameCostEstimate SurfacePointRenderer::estimateFrameCost(const FrameCostContext&) const {
  constexpr double kNsPerPoint = 140.0, kUsPerContact = 16.0;
  const long points = long(sphereVertices.get()) + long(slices.get()) * long(verticesPerSlice.get());
  const double contacts = deepestPoints.get() ? double(kMaxPointContacts) : 0.0;
  std::string model = std::to_string(points) + " points (sphereVertices + slices x verticesPerSlice) x " +
                      formatNumber(kNsPerPoint) + " ns";
  if (contacts > 0.0)
    model += " + up to " + formatNumber(contacts) + " contacts x " + formatNumber(kUsPerContact) + " us";
  return {double(points) * kNsPerPoint * 1e-9 + contacts * kUsPerContact * 1e-6, model,
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
