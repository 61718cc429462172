#include "millsim/renderers/WholeToolField.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

namespace millsim {

double WholeToolField::shaftDepth(const glm::dvec3& p) const {
  return hasPlane_ ? depth_ + glm::dot(into_, p - at_) : -std::numeric_limits<double>::infinity();
}

double WholeToolField::burrDepth(const glm::dvec3& p) const {
  const double v = burr_.value(p);
  const double slope = glm::length(burr_.gradient(p));  // cached with the value: one evaluation
  if (slope > 0.0 && std::isfinite(slope)) return v / slope;
  return v > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

double WholeToolField::value(const glm::dvec3& p) const {
  return shaftAnswers(p) ? shaftDepth(p) : burr_.value(p);
}

glm::dvec3 WholeToolField::gradient(const glm::dvec3& p) const {
  return shaftAnswers(p) ? into_ : burr_.gradient(p);
}

glm::dvec3 WholeToolField::contactNormal(const glm::dvec3& p) const {
  return shaftAnswers(p) ? -into_ : burr_.contactNormal(p);
}

glm::dvec3 WholeToolField::projectToSurface(glm::dvec3 p, double maxStep) const {
  if (!hasPlane_) return ProxyField::projectToSurface(p, maxStep);
  const glm::dvec3 ns = -into_;
  for (int k = 0; k < 6; ++k) {
    const double ds = shaftDepth(p), db = burrDepth(p);
    const glm::dvec3 g = burr_.gradient(p);
    const double slope = glm::length(g);
    glm::dvec3 step(0.0);
    if (!(slope > 0.0) || !std::isfinite(db)) {
      if (!(db > 0.0)) step = ds * ns;  // the burr far from material: the plane alone
      else break;                        // the burr past its ramp: no way out known (the caller refuses such slides)
    } else {
      const glm::dvec3 nb = -g / slope;  // the burr's outward normal
      if (ds <= 0.0 && db <= 0.0) {
        step = ds > db ? ds * ns : db * nb;  // both out: onto the nearer
      } else {
        // Out of the deeper alone if that leaves the other out; else out of both.
        const double gb = glm::dot(nb, ns);
        const glm::dvec3 burrOut = std::max(db, 0.0) * nb, shaftOut = std::max(ds, 0.0) * ns;
        const bool burrAlone = db > 0.0 && ds - glm::dot(ns, burrOut) <= 0.0;
        const bool shaftAlone = ds > 0.0 && db - glm::dot(nb, shaftOut) <= 0.0;
        const double det = 1.0 - gb * gb;
        if (burrAlone && (!shaftAlone || db <= ds)) step = burrOut;
        else if (shaftAlone) step = shaftOut;
        else if (det > 1e-9) step = ((db - gb * ds) / det) * nb + ((ds - gb * db) / det) * ns;
        else step = std::max(db, ds) * nb;  // parallel: one push clears both
      }
    }
    const double len = glm::length(step);
    if (!(len >= 1e-3 * maxStep)) {  // on the surface to 0.2 µm at 0.1 mm voxels (or NaN: stop)
      if (std::isfinite(len)) p += step;
      break;
    }
    p += len > maxStep ? step * (maxStep / len) : step;
  }
  return p;
}

}  // namespace millsim
