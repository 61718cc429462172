#pragma once
// Independent geometry for the scene tests: where the iso-surface of a volume
// is along a ray (marched through the voxels with trilinear sampling, not
// through the renderer's mesh), and the camera distance a depth-buffer value
// stands for. Header-only.
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "millsim/graphics/SceneView.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VolumeSampler.h"

namespace millsim::test {

// Distance along the view axis (m) of a depth-buffer value.
inline double viewDistance(const Camera& c, double depth) {
  const double zNdc = 2.0 * depth - 1.0;
  return c.projection[3][2] / (zNdc + c.projection[2][2]);
}
inline double viewDistanceOf(const Camera& c, const glm::dvec3& world) { return -(c.view * glm::dvec4(world, 1.0)).z; }

// World ray through a pixel centre (x from the left, y from the top).
inline std::pair<glm::dvec3, glm::dvec3> pixelRay(const Camera& c, int x, int y) {
  const glm::dmat4 inv = glm::inverse(c.projection * c.view);
  const double nx = (x + 0.5) / c.width * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / c.height * 2.0;
  glm::dvec4 a = inv * glm::dvec4(nx, ny, -1.0, 1.0), b = inv * glm::dvec4(nx, ny, 1.0, 1.0);
  const glm::dvec3 from = glm::dvec3(a) / a.w, to = glm::dvec3(b) / b.w;
  return {from, glm::normalize(to - from)};
}

// First point along the ray where it crosses the iso-surface, to within 1 µm,
// as the renderer draws it: only where the volume's clip planes keep it, and
// on a cut where it enters material there (the drawer caps the cut with its
// section: what the iso-surface encloses, and a soft tissue below it, here
// where the nearest voxel's tissue is soft and over half its density is left).
inline std::optional<glm::dvec3> firstSurface(const DrawVolume& v, const glm::dvec3& from, const glm::dvec3& dir,
                                              double maxDistance) {
  const VolumeSampler sampler(*v.voxels);
  const glm::dmat4 worldToLocal = glm::inverse(v.localToWorld);
  auto kept = [&](double t) {
    for (const glm::dvec4& p : v.clipPlanes)
      if (glm::dot(p, glm::dvec4(from + t * dir, 1.0)) < 0.0) return false;
    return true;
  };
  auto inside = [&](double t) {
    const glm::dvec3 local(worldToLocal * glm::dvec4(from + t * dir, 1.0));
    return sampler.density(v.voxels->localToIndex(local)) >= v.iso;
  };
  auto onCap = [&](double t) {
    if (inside(t)) return true;
    if (!v.tissues) return false;
    const glm::dvec3 local(worldToLocal * glm::dvec4(from + t * dir, 1.0));
    const glm::dvec3 index = v.voxels->localToIndex(local);
    const glm::ivec3 c(glm::round(index));
    const int label = v.tissues->labelAt(c.x, c.y, c.z);
    if (label <= 0 || !v.tissues->soft(label)) return false;
    const double air = v.voxels->airValue(), original = v.tissues->entries()[std::size_t(label)].densityBelowSurface;
    return sampler.density(index) > 0.5 * (air + original);
  };
  const double step = 0.2 * v.voxels->voxelSize().x;
  bool started = false, was = false, cutBefore = false;
  for (double t = 0.0; t < maxDistance; t += step) {
    if (!kept(t)) {
      started = false;
      cutBefore = true;
      continue;
    }
    if (!started && cutBefore && onCap(t)) {  // entering the kept side through the cap
      double lo = t - step, hi = t;
      while (hi - lo > 1e-6) (kept(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
      return from + hi * dir;
    }
    const bool now = inside(t);
    if (started && now != was) {
      double lo = t - step, hi = t;
      while (hi - lo > 1e-6) (inside(0.5 * (lo + hi)) == was ? lo : hi) = 0.5 * (lo + hi);
      return from + hi * dir;
    }
    started = true;
    was = now;
  }
  return std::nullopt;
}

}  // namespace millsim::test
