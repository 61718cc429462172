#include "millsim/renderers/ProxyPoint.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "millsim/haptics/HapticScene.h"
#include "millsim/math/Pose.h"

namespace millsim {

const glm::dvec3& ProxyPoint::update(const HapticScene& scene, const glm::dvec3& probe) {
  if (!isFinite(probe)) return proxy_;
  const double h = scene.voxelSize();
  glm::dvec3 entry;
  if (!inContact_) {
    if (scene.field(proxy_) > 0.0) {
      // The probe was never seen outside (a run that starts inside material):
      // there is no surface to hold it to, so follow it without force rather
      // than throw the hand out of the material.
      proxy_ = probe;
      return proxy_;
    }
    // Free motion, unless the way from the proxy to the probe enters material
    // (even if the probe has already come out on the far side of a thin wall).
    if (!findEntry(scene, proxy_, probe, entry)) {
      proxy_ = probe;
      return proxy_;
    }
    proxy_ = entry;
    inContact_ = true;
  } else if (scene.field(probe) <= 0.0 && !findEntry(scene, proxy_, probe, entry)) {
    // The probe is back outside and nothing lies between: released.
    proxy_ = probe;
    inContact_ = false;
    return proxy_;
  }
  for (int it = 0; it < params_.slideIterations; ++it) {
    const glm::dvec3 n = scene.outwardNormal(proxy_);
    if (n == glm::dvec3(0.0)) break;  // no gradient (homogeneous material): stay put
    const glm::dvec3 delta = probe - proxy_;
    // Remove the component that would push the proxy into the material.
    glm::dvec3 move = delta - std::min(glm::dot(delta, n), 0.0) * n;
    const double len = glm::length(move);
    if (len < 1e-3 * h) break;
    const double maxStep = params_.maxSlideVoxels * h;
    if (len > maxStep) move *= maxStep / len;
    const glm::dvec3 next = projectToSurface(scene, proxy_ + move, maxStep);
    if (!isFinite(next)) break;
    proxy_ = next;
  }
  // Milling may have removed the material under the proxy: follow the
  // receding surface towards the probe.
  if (scene.field(proxy_) < 0.0) {
    const glm::dvec3 next = projectToSurface(scene, proxy_, params_.maxSlideVoxels * h);
    if (isFinite(next) && glm::dot(next - proxy_, probe - proxy_) > 0.0) proxy_ = next;
  }
  return proxy_;
}

bool ProxyPoint::findEntry(const HapticScene& scene, const glm::dvec3& from, const glm::dvec3& to,
                           glm::dvec3& entry) const {
  const double h = scene.voxelSize();
  const double dist = glm::length(to - from);
  // Half-voxel steps (bounded in number, for absurd jumps).
  const int steps = std::clamp(int(std::ceil(dist / (0.5 * h))), 1, 4096);
  // The start is on or outside the surface; it is never itself the entry.
  glm::dvec3 prev = from;
  double sPrev = std::min(scene.field(from), 0.0);
  for (int i = 1; i <= steps; ++i) {
    const glm::dvec3 p = from + (to - from) * (double(i) / steps);
    const double s = scene.field(p);
    if (s > 0.0) {
      // Refine between the last outside and first inside sample.
      glm::dvec3 a = prev, b = p;
      double sa = sPrev, sb = s;
      for (int k = 0; k < 12; ++k) {
        const glm::dvec3 m = 0.5 * (a + b);
        const double sm = scene.field(m);
        if (sm > 0.0) b = m, sb = sm;
        else a = m, sa = sm;
      }
      // The paper's density fraction (eq. 1) between the two bracketing points.
      const double f = sb - sa > 0.0 ? std::clamp(-sa / (sb - sa), 0.0, 1.0) : 0.0;
      entry = a + (b - a) * f;
      return true;
    }
    prev = p;
    sPrev = s;
  }
  return false;
}

glm::dvec3 ProxyPoint::projectToSurface(const HapticScene& scene, glm::dvec3 p, double maxStep) const {
  for (int k = 0; k < 4; ++k) {
    const double s = scene.field(p);
    const glm::dvec3 g = scene.gradient(p);
    const double gg = glm::dot(g, g);
    if (!(gg > 0.0) || !std::isfinite(gg)) break;
    glm::dvec3 step = -(s / gg) * g;
    const double len = glm::length(step);
    if (len > maxStep) step *= maxStep / len;
    p += step;
    if (len < 1e-4 * maxStep) break;
  }
  return p;
}

}  // namespace millsim
