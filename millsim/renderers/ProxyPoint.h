#pragma once
// The 3-DOF probe–proxy ("god-object") algorithm on the scene's implicit
// surface, used by Algorithm #1 for the burr centre and for the shaft's
// intersection point. The paper takes it from its ref. [1], which it does not
// give; MillSim uses the implicit-surface proxy of Salisbury & Tarr (1997):
//
//  - free: the proxy is the probe, as long as the segment from the proxy to
//    the probe stays outside material;
//  - contact: the proxy stops where that segment enters the surface (marched
//    at half a voxel, then refined by bisection), even when the probe has
//    come out on the far side of a thin wall, so it cannot tunnel;
//  - in contact: the proxy slides in the tangent plane towards the probe's
//    projection and is projected back onto s = 0 by Newton steps along the
//    gradient, a bounded distance per iteration.
// The force the caller derives is k·(proxy − probe).
#include <glm/vec3.hpp>

namespace millsim {

class HapticScene;

class ProxyPoint {
public:
  struct Params {
    int slideIterations = 6;  // tangent-plane steps per update
    double maxSlideVoxels = 2.0;  // longest slide per iteration, in voxels
  };
  ProxyPoint() = default;
  explicit ProxyPoint(Params p) : params_(p) {}

  void reset(const glm::dvec3& at) {
    proxy_ = at;
    inContact_ = false;
  }
  // Puts the proxy on the surface at a known contact point (Algorithm #1's
  // first shaft intersection).
  void placeInContact(const glm::dvec3& onSurface) {
    proxy_ = onSurface;
    inContact_ = true;
  }
  // Moves the proxy for a new probe position; returns the new proxy.
  const glm::dvec3& update(const HapticScene& scene, const glm::dvec3& probe);
  // Where `other` is and whether it touches, keeping this one's parameters (a live retune).
  void takeStateFrom(const ProxyPoint& other) {
    proxy_ = other.proxy_;
    inContact_ = other.inContact_;
  }
  const glm::dvec3& position() const { return proxy_; }
  bool inContact() const { return inContact_; }

private:
  // Where the segment from → to first enters material (half-voxel steps,
  // bisection, then eq. 1's fraction); false if it stays outside.
  bool findEntry(const HapticScene& scene, const glm::dvec3& from, const glm::dvec3& to, glm::dvec3& entry) const;
  glm::dvec3 projectToSurface(const HapticScene& scene, glm::dvec3 p, double maxStep) const;

  Params params_;
  glm::dvec3 proxy_{0.0};
  bool inContact_ = false;
};

}  // namespace millsim
