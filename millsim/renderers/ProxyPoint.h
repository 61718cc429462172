#pragma once
// The 3-DOF probe–proxy ("god-object") algorithm on an implicit field, used by
// Algorithm #1 for the burr centre and for the shaft's intersection point. The
// paper takes it from its ref. [1], which it does not give; MillSim uses the
// implicit-surface proxy of Salisbury & Tarr (1997):
//
//  - free: the proxy is the probe, as long as the segment from the proxy to
//    the probe stays outside material;
//  - contact: the proxy stops where that segment enters the surface (marched
//    at half a voxel, then refined by bisection), even when the probe has
//    come out on the far side of a thin wall, so it cannot tunnel;
//  - in contact: the proxy slides in the tangent plane towards the probe's
//    projection and is projected back onto the zero set by Newton steps along
//    the gradient, a bounded distance per iteration.
// The force the caller derives is k·(proxy − probe).
//
// The field is either the scene's s(p) (a point: the shaft's intersection
// point, and the paper's burr-centre vertex) or BurrField, s dilated by the
// burr sphere (the burr's centre held so that its *surface* stays out of
// material: docs/algorithms.md, Algorithm #1).
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

namespace millsim {

class HapticScene;

// A field the proxy is kept out of: value > 0 inside, gradient = d value / dp.
class ProxyField {
public:
  virtual ~ProxyField() = default;
  virtual double value(const glm::dvec3& p) const = 0;
  virtual glm::dvec3 gradient(const glm::dvec3& p) const = 0;
  virtual double voxelSize() const = 0;  // the natural search step
  // Unit outward normal (−gradient, normalised), zero where it is undefined.
  glm::dvec3 outwardNormal(const glm::dvec3& p) const;
  // The normal a proxy in contact slides against, which sets the direction
  // of its force: the outward normal unless the field knows a better one.
  virtual glm::dvec3 contactNormal(const glm::dvec3& p) const { return outwardNormal(p); }
  // p moved onto the field's zero set, at most maxStep a step: Newton steps
  // along the gradient (a field of several parts may know a better way).
  virtual glm::dvec3 projectToSurface(glm::dvec3 p, double maxStep) const;
  // Whether a proxy held straight above `probe` may rest on a saddle (a ridge
  // along which sliding either way brings it nearer): false unless the field
  // knows (BurrField: only where the burr centre itself is in material).
  virtual bool maySaddle(const glm::dvec3& /*probe*/) const { return false; }
};

// The scene's implicit surface s(p) itself.
class SceneField final : public ProxyField {
public:
  explicit SceneField(const HapticScene& scene) : scene_(scene) {}
  double value(const glm::dvec3& p) const override;
  glm::dvec3 gradient(const glm::dvec3& p) const override;
  double voxelSize() const override;

private:
  const HapticScene& scene_;
};

// The burr sphere's dilation of the scene: g(c) = max over |u| = 1 of
// s(c + r·u), > 0 exactly when the burr centred at c has part of its surface in
// material. Evaluated at 26 fixed directions (cube faces, edges, corners) plus
// the last maximiser, then refined by two parabola fits over the sphere's
// tangent angles. Its gradient is ∇s at the maximiser (the envelope theorem),
// parallel to the maximiser's direction u there. About 40 field samples per
// evaluation; the last one is cached, so value() then gradient() at one point
// costs one evaluation. No allocation after the first bind().
//
// Between the 26 directions (27.5° apart at most) the sphere sags 0.11 r
// below its samples, and s is informative only within about a voxel of the
// surface: at 25 µm voxels a 0.6 mm burr hid 2.7 voxels of material there,
// and a burr meeting a rim between two directions went in unfelt and caught
// on it (the physical suite's hole: 93 % force error at 25 µm, 38 % at
// 0.1 mm). So where the voxels are fine for the burr, an evaluation that
// sees no surface among the 26 while material is near (the first touch)
// also samples a Fibonacci set of directions dense enough that the sphere
// sags at most kHiddenVoxels between them (bind() sizes it; none at the
// paper's 0.1 mm for burrs up to 0.66 mm).
//
// The maximiser is a poor contact normal: where the burr just touches, s
// falls off its peak by only a few hundredths of a voxel within 5°, about as
// much as the trilinear samples of a curved surface are off, so the argmax of
// the voxelised field lands 4° (RMS; up to 10°) off a ball's normal.
// contactNormal() fits a paraboloid to s over two rings 0.2 and 0.4 rad
// around the maximiser (17 samples, twice) and takes its peak where that is a
// clear one: 1.3° RMS on a ball against the maximiser's 4.9° (docs/
// algorithms.md, Algorithm #1). Elsewhere — the burr's own pit, a crease, and
// often a bowl, whose sampled peak looks flatter than it is — it fades back
// to the maximiser.
class BurrField final : public ProxyField {
public:
  // How far (voxels) the sphere may sag between two directions of the search.
  static constexpr double kHiddenVoxels = 0.75;

  explicit BurrField(double radius) : radius_(radius) {}
  // The scene of this frame (the field reads it until the next call). Forgets
  // the cached evaluation: milling may have changed the scene since. Sizes the
  // fine directions for the scene's voxels (allocates only when they change).
  void bind(const HapticScene& scene);
  // Directions of the first-touch search beyond the 26 (0 where they suffice).
  std::size_t fineDirections() const { return fine_.size(); }
  double value(const glm::dvec3& c) const override { return evaluate(c), value_; }
  glm::dvec3 gradient(const glm::dvec3& c) const override { return evaluate(c), gradient_; }
  // −(the fitted peak's direction) at c; the last one is cached as well.
  glm::dvec3 contactNormal(const glm::dvec3& c) const override;
  double voxelSize() const override;
  // The dilated surface curves no tighter than the burr's radius, so a proxy
  // r out of the material rests on a saddle only if the probe (the burr
  // centre) is more than r below it: in material itself.
  bool maySaddle(const glm::dvec3& probe) const override;
  // The unit direction from the centre to the burr's deepest point at the last
  // evaluation (where it touches, in contact).
  const glm::dvec3& deepestDirection() const { return direction_; }
  double radius() const { return radius_; }

private:
  void evaluate(const glm::dvec3& c) const;

  double radius_;
  const HapticScene* scene_ = nullptr;
  std::vector<glm::dvec3> fine_;  // the first-touch search's directions (bind)
  double fineVoxel_ = 0.0;        // the voxel size fine_ was made for
  // s's rise over one voxel along the last contact's normal: a sample within
  // that of the surface is in contact's reach and needs no fine search.
  mutable double risePerVoxel_ = 0.0;
  // Where the last fine search found no surface, and in which scene (null: none).
  mutable const HapticScene* clearScene_ = nullptr;
  mutable glm::dvec3 clearAt_{0.0};
  mutable bool cached_ = false;
  mutable glm::dvec3 at_{0.0};
  mutable double value_ = -1.0;
  mutable glm::dvec3 gradient_{0.0};
  mutable glm::dvec3 direction_{0.0, -1.0, 0.0};  // the last maximiser (the next evaluation's first guess)
  mutable bool normalCached_ = false;  // contactNormal() at at_
  mutable glm::dvec3 normal_{0.0};
};

class ProxyPoint {
public:
  struct Params {
    int slideIterations = 6;  // tangent-plane steps per update
    double maxSlideVoxels = 2.0;  // longest slide per iteration, in voxels
    // When milling has moved the surface away from a proxy in contact: true
    // moves it straight towards the probe until it touches again (the burr's
    // proxy); false projects it along the gradient (the shaft's point).
    bool recedeTowardsProbe = false;
    // Refuse (halve, up to four times) a slide that ends past the field's
    // one-voxel ramp, where it has no gradient to project back along: in a
    // concave crease a slide along one face runs into the other (the burr's
    // proxy; its field is a maximum over the sphere, whose creases are sharp).
    bool refuseSinkingSlides = false;
    // Slide along the line where two faces meet when a slide runs from one
    // into the other (two-plane god object), instead of bouncing between them.
    bool slideAlongCreases = false;
    // Take a slide only if it brings the proxy nearer the probe (halved up
    // to twice, else stay): a god object minimises that distance, and where
    // the free space is a needle — the burr in the hole it drilled, pushed
    // against a wall — slides projected onto alternate walls otherwise hopped
    // 0.1–0.2 mm a frame with the probe still (the burr's proxy).
    bool descentOnly = false;
    // How far (voxels) the proxy may slide in one update beyond how far the
    // probe moved since the last: a proxy held by refused slides while the
    // probe drifts (the burr in its own pit, leaning) otherwise slipped the
    // whole way at once, up to 0.2 mm (0.2 N) in a frame.
    double maxSlipVoxels = std::numeric_limits<double>::infinity();
    // Leave a saddle: where the probe is straight below the proxy and the
    // field says it may be one (maySaddle), try half a voxel to each side
    // along the two tangents and slide on from the one nearest the probe, if
    // nearer. A burr pressed past a convex edge straight down its bisector
    // otherwise stays on the bisector (nothing tips it off), where a rigid
    // burr slides onto a face (the physical suite's edge: 22° off).
    bool leaveSaddles = false;
  };
  // What moves frame to frame: a plain struct, so that a renderer taking
  // over (a cross-fade) copies it and a reset is a fresh one.
  struct State {
    glm::dvec3 proxy{0.0};
    glm::dvec3 lastProbe{0.0};  // the probe of the last update (for maxSlipVoxels)
    bool inContact = false;
    static State at(const glm::dvec3& p) { return State{p, p, false}; }
  };
  ProxyPoint() = default;
  explicit ProxyPoint(Params p) : params_(p) {}

  void reset(const glm::dvec3& at) { s_ = State::at(at); }
  // Puts the proxy on the surface at a known contact point (Algorithm #1's
  // first shaft intersection).
  void placeInContact(const glm::dvec3& onSurface) {
    s_.proxy = onSurface;
    s_.inContact = true;
  }
  // Moves the proxy for a new probe position; returns the new proxy.
  const glm::dvec3& update(const ProxyField& field, const glm::dvec3& probe);
  // The same on the scene's surface s(p).
  const glm::dvec3& update(const HapticScene& scene, const glm::dvec3& probe);
  // Where `other` is and whether it touches, keeping this one's parameters (a live retune).
  const State& state() const { return s_; }
  void setState(const State& s) { s_ = s; }
  const glm::dvec3& position() const { return s_.proxy; }
  bool inContact() const { return s_.inContact; }

private:
  // Where the segment from → to first enters material (half-voxel steps,
  // bisection, then eq. 1's fraction); false if it stays outside.
  bool findEntry(const ProxyField& field, const glm::dvec3& from, const glm::dvec3& to, glm::dvec3& entry) const;
  // A saddle's way off (ProxyPoint::Params::leaveSaddles): the surface point
  // half a voxel to one side nearest the probe, if nearer than the proxy.
  bool saddleExit(const ProxyField& field, const glm::dvec3& probe, const glm::dvec3& n, glm::dvec3& exit) const;

  Params params_;
  State s_;
};

}  // namespace millsim
