#include "measure/AnalyticScene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "millsim/volume/MeshVolume.h"

namespace millsim::measure {

Shape halfSpace(glm::dvec3 lo, glm::dvec3 hi) {
  return {"half-space", [](const glm::dvec3& p) { return p.y; }, lo, hi};
}

Shape ball(double R) {
  const double m = 0.5e-3;
  return {"sphere", [R](const glm::dvec3& p) { return glm::length(p) - R; }, glm::dvec3(-R - m), glm::dvec3(R + m)};
}

Shape cavity(double R) {
  const double m = 2e-3;
  return {"cavity", [R](const glm::dvec3& p) { return R - glm::length(p); }, glm::dvec3(-R - m), glm::dvec3(R + m)};
}

Shape edge(glm::dvec3 lo, glm::dvec3 hi) {
  return {"edge",
          [](const glm::dvec3& p) {
            // Exact distance to the quarter-space x < 0, y < 0.
            if (p.x <= 0.0 && p.y <= 0.0) return std::max(p.x, p.y);
            return std::hypot(std::max(p.x, 0.0), std::max(p.y, 0.0));
          },
          lo, hi};
}

Shape plate(double thickness, glm::dvec3 lo, glm::dvec3 hi) {
  return {"plate", [t = thickness](const glm::dvec3& p) { return std::abs(p.y) - 0.5 * t; }, lo, hi};
}

std::unique_ptr<AnalyticScene> voxelise(const Shape& shape, double h) {
  if (!(h > 0.0)) throw std::invalid_argument("voxelise: the voxel size must be positive");
  auto out = std::make_unique<AnalyticScene>();
  out->shape = shape;
  out->h = h;
  // Lattice-aligned box: voxel i sits at world lo + i·h with lo a multiple of h.
  const glm::dvec3 lo = glm::floor(shape.lo / h) * h, hi = glm::ceil(shape.hi / h) * h;
  const glm::ivec3 n = glm::ivec3(glm::round((hi - lo) / h)) + 1;
  std::vector<float> v(std::size_t(n.x) * n.y * n.z);
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::dvec3 p = lo + glm::dvec3(i, j, k) * h;
        v[(std::size_t(k) * n.y + j) * n.x + i] = float(1000.0 * std::clamp(0.5 - shape.distance(p) / h, 0.0, 1.0));
      }
  out->volume = std::make_unique<VoxelVolume>(VoxelVolume::fromDense(v.data(), n, glm::dvec3(h), 0.f));
  // Voxel i is at local (i − (n−1)/2)·h: translate the centre to the box centre.
  out->localToWorld = glm::translate(glm::dmat4(1.0), lo + glm::dvec3(n - 1) * (0.5 * h));
  out->scene = std::make_unique<VoxelScene>();
  out->scene->addVolume(*out->volume, out->localToWorld, kIso);
  return out;
}

std::unique_ptr<AnalyticScene> voxeliseMesh(const Shape& shape, const SurfaceMesh& mesh, double h) {
  MeshVoxelOptions o;
  o.voxelSize = h;
  o.isoValue = kIso;  // air 0, material 2 · kIso = 1000: the analytic scenes' densities
  o.airValue = 0.f;
  MeshVolume voxels = voxeliseMesh(mesh, "the " + shape.name + " mesh", o);
  auto out = std::make_unique<AnalyticScene>();
  out->shape = shape;
  out->h = h;
  out->volume = std::make_unique<VoxelVolume>(std::move(voxels.density));
  // Voxel centres on h·ℤ³ of the mesh's coordinates, as voxelise() puts them.
  out->localToWorld = glm::translate(glm::dmat4(1.0), voxels.centre);
  out->scene = std::make_unique<VoxelScene>();
  out->scene->addVolume(*out->volume, out->localToWorld, kIso);
  return out;
}

}  // namespace millsim::measure
