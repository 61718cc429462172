#include "millsim/renderers/BarbicRenderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include "millsim/haptics/CutFront.h"
#include "millsim/haptics/HapticScene.h"
#include "millsim/math/LeastCostExit.h"
#include "millsim/renderers/BarbicSolve.h"
#include "millsim/renderers/FreeStart.h"
#include "millsim/renderers/Obb.h"
#include "millsim/renderers/ToolSdf.h"
#include "millsim/haptics/PointShellQuery.h"

namespace millsim {

namespace {

// How far (voxels) the tool moves in the step that loses all its contacts (below).
constexpr double kLostContactStepVoxels = 0.1;
// rigidContact: the longest way out of a wedge that is felt, in depths of the deeper contact (feelRigid).
constexpr double kWedgeLift = 6.0;

struct BarbicParams {
  int scale;
  double contactK, feedResistance, maxStep;
  Coupling coupling;
  bool sampled, culling;
  bool rigidContact;
  std::size_t maxTested, maxContacts;
};

class BarbicAlgorithm final : public HapticAlgorithm {
public:
  BarbicAlgorithm(const BarbicParams& p, const ToolGeometry& tool, double sdfVoxel, HapticScene& scene)
      : p_(p), sdf_(tool, sdfVoxel), reach_(std::max(tool.shaftLength, tool.head().boundingRadius())),
        reachTip_(tool.head().boundingRadius()) {
    // The scene builds the shells on first request: here, on the scene thread,
    // not in step(). Shells that exist are left to the haptic thread, which
    // may be milling with them now (a burr swap compiles while running).
    shells_.resize(scene.volumeCount());
    for (std::size_t i = 0; i < shells_.size(); ++i) {
      shells_[i].placement = &scene.placement(i);
      shells_[i].fine = &scene.preparePointShell(i, p_.scale);
      scene.preparePointShell(i, 2 * p_.scale);
      // A shell's bucket grid is fixed: step() never grows this list.
      candidates_.reserve(std::max(candidates_.capacity(), shells_[i].fine->bucketCount()));
    }
  }

  std::string name() const override { return "BarbicRenderer"; }

  void reset(const Pose& device) override { s_ = State::at(device); }

  // The coupled tool stays where it was held, moving as it was: only the
  // parameters change (a field applied live, a swap back to #3).
  void carryOver(const HapticAlgorithm& previous) override {
    if (const auto* p = dynamic_cast<const BarbicAlgorithm*>(&previous)) s_ = p->s_;
  }

  HapticOutput step(HapticScene& scene, const HapticInput& in) override {
    HapticOutput out;
    if (!isFinite(in.device)) {  // a bad pose changes nothing: hold the tool, feel nothing
      out.drawnTool = s_.tool;
      out.hasProxy = true, out.proxy = s_.tool.position, out.burrCentre = s_.tool.position, out.burrCuts = false;
      return out;
    }
    const Pose device{in.device.position, glm::normalize(in.device.orientation)};
    const double dt = in.dt > 1e-6 && std::isfinite(in.dt) ? in.dt : 1e-3;
    followMilling(scene);
    if (s_.startFree) {  // the first frame after a reset: out of material along the axis (FreeStart.h)
      s_.startFree = false;
      const glm::dvec3 axis = s_.tool.shaftDirection();
      const double h = scene.voxelSize();
      const double s = firstFreeAlong([&](double d) { return penetrates({s_.tool.position + axis * d, s_.tool.orientation}); },
                                      h, reach_ + reachTip_, 0.05 * h);
      if (s > 0.0) s_.tool.position += axis * s;
    }

    // 1–2. Contacts at the current tool pose, and the coupling spring.
    acc_.clear();
    addCouplingSpring(acc_, p_.coupling, s_.tool, device);
    out.contacts = gatherContacts(scene, out.flags);

    // 3. The 6×6 solve (quasi-static: net wrench zero after the step).
    Vec6 deviceVelocity;
    const glm::dvec3 vd = (device.position - s_.lastDevice.position) / dt;
    const glm::dvec3 wd = rotationError(s_.lastDevice.orientation, device.orientation) / dt;
    deviceVelocity << vd.x, vd.y, vd.z, wd.x, wd.y, wd.z;
    SolveResult solved = solveStep(acc_, p_.coupling, deviceVelocity, dt);
    Vec6 step = solved.step;

    // Never tunnel: a step longer than maxStep is cut to maxStep if any shell
    // point lies within the box the tool sweeps.
    // In the frame its contacts were all lost the tool moves at most a tenth
    // of a voxel: the cut front leads the tool by about 10 µm, so when the
    // shell under the burr is refreshed none of its points is inside the
    // tool for a frame, and the solve took the tool the whole way to the
    // device (93 µm at 0.18 N; the force dropped to zero and came back at
    // 0.23 N). A tenth of a voxel: 0.038 N, the same removed volume.
    const double sweep = step.head<3>().norm() + step.tail<3>().norm() * reach_;
    const double limit =
        out.contacts == 0 && s_.touched ? std::min(p_.maxStep, kLostContactStepVoxels * scene.voxelSize()) : p_.maxStep;
    if (sweep > limit && materialWithin(sweep)) step *= limit / sweep;
    s_.touched = out.contacts > 0;
    s_.tool = applyStep(s_.tool, step);
    Vec6 toolVelocity = step / dt;
    if (!isFinite(s_.tool)) s_.tool = device, toolVelocity.setZero();

    // 4. What the user feels: the coupling between the new tool pose and the device.
    const glm::dvec3 vt(toolVelocity(0), toolVelocity(1), toolVelocity(2));
    const glm::dvec3 wt(toolVelocity(3), toolVelocity(4), toolVelocity(5));
    out.force = p_.coupling.k * (s_.tool.position - device.position) + p_.coupling.b * (vt - vd);
    out.torque = -p_.coupling.kr * rotationError(s_.tool.orientation, device.orientation) + p_.coupling.br * (wt - wd);
    if (p_.rigidContact && out.contacts > 0) feelRigid(out);
    out.drawnTool = s_.tool;
    out.hasProxy = true;
    out.proxy = s_.tool.position;
    // Milling: free of contact the burr cuts where it is drawn; in contact
    // the cut front starts there and advances towards the device at the feed
    // speed |F| / (feedResistance · hardness), never past it. Not at the tool
    // itself: the coupled tool rests a penalty depth inside the surface, and
    // cutting there lets the surface recede by that depth every frame
    // whatever the force or tissue (docs/algorithms.md, "Tissue hardness").
    out.burrCentre = s_.cut.step(scene, FeedLaw{p_.feedResistance, reachTip_}, s_.tool.position, device.position,
                               out.contacts > 0, in.milling, glm::length(out.force), dt);
    out.cutHardness = s_.cut.hardness();
    out.burrCuts = true;
    s_.lastDevice = device;
    s_.toolVelocity = toolVelocity;
    sanitize(out, device);
    return out;
  }

private:
  // rigidContact: the wrench a tool held at the surface would give. The
  // penalty contacts let the coupled tool rest inside the surface, and a
  // rigid tool would rest further from the device by the translation that
  // takes it out of them, so the coupling's force is short by k times that
  // (the physical suite at h = 0.1 mm: 11.9 % RMS force error, most of it at
  // light contact, where few points carry the force; docs/algorithms.md,
  // Algorithm #3). The contacts are taken as two, the burr's and the
  // shaft's, each its deepest penetration along its points' net push: a
  // conformal contact has many points and a shaft on a rim few, so taken as
  // one the correction leaned towards the burr's (3.5° off in the bowl). The
  // rigid tool is moved out of both at least cost to the coupling's springs
  // (k, kr: it may turn as well as lift, as the physical reference's tool
  // does; LeastCostExit.h), and the springs' extra wrench is felt.
  // In a wedge (the burr on a hole's wall, the shaft on the far rim) the way
  // out is several times the depths. Translated out, capped at the deeper
  // depth, the hole's wedge was 16.6 % RMS off; at 3 depths and more, 3.45 %;
  // moved out in the springs' metric, 1.2 % (its torque 0.14 → 0.10). The
  // springs' stretch is capped at six depths: a cap that binds in the §8.2 pit
  // makes the force follow the deepest point, which jumps as the tool slides
  // over the shell (at 2 depths 0.050 N a frame leaning, at 3 0.032 N holding,
  // over 985–1015 Hz; at 4 to 8, 0.018 N at most), and uncapped, a near-jam
  // there asked for a 9 N step. Scaled down where one contact point could not
  // carry the coupling's force at the deeper depth (|F|/k_point): at a 1 m/s
  // impact, millimetres deep, the whole depth rang at 79 µm p-p (the
  // stability suite's firm grip), and with the part beyond the depth left
  // unscaled the milled pit buzzed at 0.19 N and 40 Hz.
  void feelRigid(HapticOutput& out) const {
    glm::dvec3 normals[2], arms[2];
    double depths[2];
    int n = 0;
    for (const Part& part : parts_) {
      const double push = glm::length(part.push);
      if (!(part.depth > 0.0) || !(push > 0.0) || !std::isfinite(push)) continue;
      normals[n] = -part.push / push, depths[n] = part.depth, arms[n] = part.arm, ++n;
    }
    if (n == 0) return;
    const int deeper = n == 2 && depths[1] > depths[0] ? 1 : 0;
    const double k = p_.coupling.k, kr = p_.coupling.kr;
    glm::dvec3 moments[2];
    double gram[2][2] = {};
    for (int i = 0; i < n; ++i) moments[i] = glm::cross(arms[i], normals[i]);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) gram[i][j] = glm::dot(normals[i], normals[j]) / k + glm::dot(moments[i], moments[j]) / kr;
    double pushes[2] = {0.0, 0.0};
    if (!pushesOut(gram, depths, n, pushes)) {  // a jam: out of the deeper alone, by translation
      pushes[1 - deeper] = 0.0;
      pushes[deeper] = k * depths[deeper];
    }
    glm::dvec3 force(0.0), torque(0.0);
    for (int i = 0; i < n; ++i) force += pushes[i] * normals[i], torque += pushes[i] * moments[i];
    const double length = glm::length(force) / k;  // how far the springs are stretched further
    const double carried = std::min(1.0, glm::length(out.force) / (pointK_ * depths[deeper]));
    const double longest = carried * std::min(length, kWedgeLift * depths[deeper]);
    if (!(longest > 0.0) || !std::isfinite(longest)) return;
    const double scale = std::min(1.0, longest / length);
    out.force += scale * force;
    out.torque += scale * torque;
  }

  struct Shells {
    const HapticScene::Placement* placement = nullptr;
    const PointShellQuery* fine = nullptr;
  };

  // Every volume's shell, brought up to date with the milling since the last
  // frame. The coarse fallback shell (scale 2s) is asked for only in a frame
  // that falls back to it: the scene keeps it current then, and a milling
  // frame does not pay for a shell it does not use.
  void followMilling(HapticScene& scene) {
    for (std::size_t i = 0; i < shells_.size(); ++i) {
      shells_[i].placement = &scene.placement(i);
      shells_[i].fine = &scene.pointShell(i, p_.scale);
    }
  }

  // The tool's oriented bounding box in a volume's local frame, grown by `margin` (world m).
  Obb toolBox(const HapticScene::Placement& v, const Pose& tool, double margin) const {
    const glm::dmat3 R = glm::mat3_cast(tool.orientation);
    const glm::dvec3 lo = sdf_.boxLo() - margin, hi = sdf_.boxHi() + margin;
    const glm::dmat3 lin(v.worldToLocal);
    const glm::dvec3 axes[3] = {glm::normalize(lin * R[0]), glm::normalize(lin * R[1]), glm::normalize(lin * R[2])};
    return Obb(glm::dvec3(v.worldToLocal * glm::dvec4(tool.position + R * ((lo + hi) * 0.5), 1.0)), axes,
               (hi - lo) * 0.5 / v.worldPerLocal);
  }

  // Penalty contacts of every shell point inside the tool, into acc_. Uses
  // the coarse shell when the fine one would exceed the budgets.
  int gatherContacts(HapticScene& scene, std::uint32_t& flags) {
    const glm::dmat3 R = glm::mat3_cast(s_.tool.orientation), Rt = glm::transpose(R);
    int contacts = 0;
    // The contacts are summed in the tool's frame, where the tool's distance
    // field gives them, and turned into the world once (addRotated): turning
    // each contact's normal and Hessian (R·H·Rᵀ, two out-of-line 3×3
    // products) and its point was 7 % of the frames' instructions over the
    // §8.2 replay.
    accTool_.clear();
    parts_[0] = parts_[1] = Part{};
    for (std::size_t i = 0; i < shells_.size(); ++i) {
      const Shells& s = shells_[i];
      auto coarse = [&] { return &scene.pointShell(i, 2 * p_.scale); };
      const auto& v = *s.placement;
      const Obb box = toolBox(v, s_.tool, 0.0);
      // Volume-local point to the tool's frame in one affine map.
      const glm::dmat3 toTool = Rt * glm::dmat3(v.localToWorld);
      const glm::dvec3 toToolOrigin = Rt * (glm::dvec3(v.localToWorld[3]) - s_.tool.position);
      auto overlaps = [&](const Aabb& b) { return box.overlaps(b); };
      const PointShellQuery* shell = s.fine;
      // The fine shell's candidates, listed once for the budget and the visit.
      if (p_.culling && shell->collectCandidates(overlaps, candidates_) > p_.maxTested)
        shell = coarse(), flags |= kFlagCoarseFallback;
      for (int attempt = 0; attempt < 2; ++attempt) {
        const double k = p_.contactK * double(shell->scale() * shell->scale());
        pointK_ = k;
        const Wrench6 before = accTool_;
        const Part partsBefore[2] = {parts_[0], parts_[1]};
        int n = 0;
        bool full = false;
        auto test = [&](const ShellPoint& sp) {
          if (full) return;
          // Cheap exact reject first: outside the tool's hull (its bounding
          // cylinder about the axis, narrowed to the shaft above the head; a
          // round burr: its ball and its shaft) the exact distance is
          // positive. Most candidates of a fine shell end here (at scale 1 in
          // the §8.2 procedure, 850 of 930 a frame). Not for the sampled
          // grid, which rounds the creases and can be negative just outside.
          const glm::dvec3 q = toTool * glm::dvec3(sp.position) + toToolOrigin;
          if (!p_.sampled) {
            const double radial = q.x * q.x + q.z * q.z;
            if (radial > hull_.outer2 || q.y < hull_.lo || q.y > hull_.hi ||
                (q.y > hull_.headTop && radial > hull_.shaft2))
              return;
            if (hull_.round && radial + q.y * q.y > hull_.outer2 && (q.y < -hull_.eps || radial > hull_.shaft2)) return;
          }
          // The hull test leaves almost only contacts: one analytic evaluation, not a distance first.
          if (p_.sampled && !(sdf_.sampledDistance(q) < 0.0)) return;
          const SdfSample sm = p_.sampled ? sdf_.sampled(q) : sdf_.analytic(q, true);
          if (!(sm.distance < 0.0)) return;
          addContact(accTool_, q, sm.distance, sm.gradient, sm.hessian, k);
          if (p_.rigidContact) addToParts(q, -sm.distance, sm.gradient);
          full = ++n >= int(p_.maxContacts);
        };
        if (!p_.culling) shell->forEach(test);
        else if (shell == s.fine) shell->forEachIn(candidates_, test);
        else shell->forEachCandidate(overlaps, test);
        if (full && shell == s.fine) {
          accTool_ = before;  // too many contacts: redo with the coarse shell
          parts_[0] = partsBefore[0], parts_[1] = partsBefore[1];
          shell = coarse();
          flags |= kFlagCoarseFallback;
          continue;
        }
        if (full) flags |= kFlagCoarseFallback;  // still too many: contacts past the budget were left out
        contacts += n;
        break;
      }
    }
    addRotated(acc_, accTool_, R);
    for (Part& part : parts_)  // the tool's frame to the world's
      part.push = R * part.push, part.arm = part.weight > 0.0 ? R * (part.arm / part.weight) : glm::dvec3(0.0);
    return contacts;
  }

  // Whether any shell point is inside the tool at `pose` (the contact test of
  // gatherContacts, stopping at the first).
  bool penetrates(const Pose& pose) const {
    const glm::dmat3 Rt = glm::transpose(glm::mat3_cast(pose.orientation));
    for (const Shells& s : shells_) {
      const auto& v = *s.placement;
      const Obb box = toolBox(v, pose, 0.0);
      if (s.fine->anyCandidate([&](const Aabb& b) { return box.overlaps(b); }, [&](const ShellPoint& sp) {
            const glm::dvec3 q = Rt * (glm::dvec3(v.localToWorld * glm::dvec4(glm::dvec3(sp.position), 1.0)) - pose.position);
            return (p_.sampled ? sdf_.sampledDistance(q) : sdf_.distance(q)) < 0.0;
          }))
        return true;
    }
    return false;
  }

  // Whether any shell point lies within `margin` of the tool's box.
  bool materialWithin(double margin) const {
    for (const Shells& s : shells_) {
      const Obb box = toolBox(*s.placement, s_.tool, margin);
      if (s.fine->anyCandidate([&](const Aabb& b) { return box.overlaps(b); },
                               [&](const ShellPoint& p) { return box.contains(glm::dvec3(p.position)); }))
        return true;
    }
    return false;
  }

  // The tool's hull in its own frame, squared radii with a margin, so that the
  // cheap reject never drops a point the exact distance would keep.
  struct Hull {
    double outer2, shaft2, lo, hi, headTop, eps;
    bool round;  // the head is the ball of radius √outer2 (less the margin)
  };
  static Hull hullOf(const ToolSdf& sdf) {
    const double eps = 1e-9;  // m: far above the rounding of the two transforms
    const double outer = sdf.boxHi().x + eps, shaft = sdf.tool().shaftRadius + eps;
    return {outer * outer, shaft * shaft, sdf.boxLo().y - eps, sdf.boxHi().y + eps, -sdf.boxLo().y + eps, eps,
            sdf.tool().round() && sdf.tool().tipRadius >= sdf.tool().shaftRadius};
  }

  BarbicParams p_;
  ToolSdf sdf_;
  Hull hull_ = hullOf(sdf_);
  double reach_;
  double reachTip_;  // the burr's radius: its leading point is this far ahead of its centre
  std::vector<Shells> shells_;
  std::vector<int> candidates_;  // the fine shell's buckets gatherContacts visits
  Wrench6 acc_;
  Wrench6 accTool_;  // the contacts' part of acc_, in the tool's frame (gatherContacts)
  // rigidContact: the burr's contact and the shaft's this frame (gatherContacts;
  // in the tool's frame while gathering, then the world's).
  struct Part {
    double depth = 0.0;    // the deepest point's penetration (m)
    glm::dvec3 push{0.0};  // Σ depth × the tool's distance gradient: the points' net push, reversed
    glm::dvec3 arm{0.0};   // Σ depth × point, from the burr centre; then over Σ depth: the centre of pressure
    double weight = 0.0;   // Σ depth
  };
  Part parts_[2];  // the burr's, the shaft's
  double pointK_ = 1.0;  // the penalty stiffness of one shell point this frame (N/m)
  // A contact point's share in the two parts: the burr's below three quarters
  // of the head's top, the shaft's above the top, blended between, so that a
  // point moving along the tool moves its depth from one part to the other
  // continuously.
  void addToParts(const glm::dvec3& q, double depth, const glm::dvec3& gradient) {
    const double top = hull_.headTop;
    const double shaft = std::clamp((q.y - 0.75 * top) / (0.25 * top), 0.0, 1.0);
    const double weight[2] = {1.0 - shaft, shaft};
    for (int i = 0; i < 2; ++i) {
      const double d = depth * weight[i];
      if (!(d > 0.0)) continue;
      parts_[i].depth = std::max(parts_[i].depth, d);
      parts_[i].push += d * gradient;
      parts_[i].arm += d * q;
      parts_[i].weight += d;
    }
  }
  // What moves frame to frame: a plain struct (a cross-fade copies it; a
  // reset is a fresh one).
  struct State {
    Pose tool, lastDevice;
    bool touched = false;    // the last step had contacts (a step that loses them all is held short)
    bool startFree = true;   // the next step first moves a tool that starts in material out of it
    Vec6 toolVelocity = Vec6::Zero();
    CutFront cut;            // where the burr cuts
    static State at(const Pose& device) {
      State s;
      s.tool = s.lastDevice = isFinite(device) ? device : Pose{};
      s.cut.reset(device.position);
      return s;
    }
  };
  State s_;
};

}  // namespace

const NodeType& BarbicRenderer::type() {
  static const NodeType t = makeNodeType<BarbicRenderer>(
      "BarbicRenderer", "hapticsRenderer", "MillSim haptics",
      "Algorithm #3: tool distance field against the object's point shell, virtual coupling and a 6×6 "
      "quasi-static solve (Barbič & James 2008).");
  return t;
}

std::unique_ptr<HapticAlgorithm> BarbicRenderer::compile(const ToolGeometry& tool, HapticScene& scene) const {
  BarbicParams p;
  p.scale = pointShellScale.get();
  p.contactK = contactStiffness.get();
  p.feedResistance = feedResistance.get();
  p.maxStep = maxStep.get();
  p.coupling = Coupling{couplingStiffness.get(), couplingDamping.get(), angularCouplingStiffness.get(),
                        angularCouplingDamping.get()};
  p.sampled = sampledSdf.get();
  p.culling = culling.get();
  p.rigidContact = rigidContact.get();
  p.maxTested = std::size_t(maxTestedPoints.get());
  p.maxContacts = std::size_t(maxContacts.get());
  return std::make_unique<BarbicAlgorithm>(p, tool, double(sdfVoxelSize.get()), scene);
}

// A tool body on a virtual coupling: the stiffness is the coupling, the
// resolution the point shell's scale, and the tool body never enters material.
// Cost model (`millsim check`): a frame tests the shell points near the tool
// (with culling: at most a surface wrapped around the tool, its area over the
// shell spacing (pointShellScale x voxel)², capped by maxTestedPoints; without
// culling: every shell point) at kNsPerPoint each (distance lookup and the
// 6x6 assembly). Measured with `millsim bench rates --renderer BarbicRenderer
// --field culling --values false` on the tooth phantom (2-core AMD EPYC VM
// shared with a build, release): every one of the 5868 points of the scale-3
// shell in 118 us a frame, 20 ns per point. docs/algorithms.md, "Frame cost model".
FrameCostEstimate BarbicRenderer::estimateFrameCost(const FrameCostContext& context) const {
  constexpr double kNsPerPoint = 20.0;
  const int scale = pointShellScale.get();
  std::size_t points = 0;
  std::string how;
  if (!culling.get()) {
    points = context.shellPoints ? context.shellPoints(scale) : 0;
    how = std::to_string(points) + " points (the whole point shell at pointShellScale " + std::to_string(scale) +
          ", culling off)";
  } else {
    if (!(context.voxelSize > 0.0)) return {};
    const ToolGeometry& t = context.tool;
    const double area = 4.0 * std::numbers::pi * t.tipRadius * t.tipRadius +
                        2.0 * std::numbers::pi * t.shaftRadius * t.shaftLength;
    const double spacing = scale * context.voxelSize;
    points = std::min<std::size_t>(std::size_t(area / (spacing * spacing)), std::size_t(maxTestedPoints.get()));
    how = std::to_string(points) + " points (the tool's surface over (pointShellScale x voxel)², at most "
                                   "maxTestedPoints)";
  }
  return {double(points) * kNsPerPoint * 1e-9, how + " x " + formatNumber(kNsPerPoint) + " ns",
          culling.get() ? "raise pointShellScale or lower maxTestedPoints" : "set culling true or raise pointShellScale"};
}

RendererTraits BarbicRenderer::traits() const {
  RendererTraits t;
  t.stiffnessField = "couplingStiffness";
  t.resolutionSweeps = {{"pointShellScale", {"1", "2", "3"}}};
  t.reference = ReferenceKind::Coupling;
  t.constrainsTool = true;
  return t;
}

}  // namespace millsim
