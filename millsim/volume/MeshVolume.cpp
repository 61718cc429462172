// MeshVolume (MeshVolume.h): closed mesh parts into density and label voxels.
#include "millsim/volume/MeshVolume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>

#include "millsim/volume/ReaderLimits.h"
#include "millsim/volume/VolumeError.h"
#include "millsim/volume/VoxelSizeRange.h"

namespace millsim {

namespace {

std::string inMillimetres(const glm::dvec3& p) {
  return "(" + fmt(p.x * 1e3) + ", " + fmt(p.y * 1e3) + ", " + fmt(p.z * 1e3) + ") mm";
}

}  // namespace

MeshVolume voxeliseMesh(const SurfaceMesh& mesh, const std::string& name, const MeshVoxelOptions& o) {
  const double h = o.voxelSize, unit = o.unit;
  if (!(h >= kMinVoxelSize && h <= kMaxVoxelSize))
    throw VolumeError(name + ": a mesh is voxelised at the VolumeObject's voxelSize, which is " + fmt(h) +
                      " m; expected " + fmt(kMinVoxelSize) + " to " + fmt(kMaxVoxelSize) + " m");
  if (!(unit > 0.0) || !std::isfinite(unit)) throw VolumeError(name + ": mesh unit " + fmt(unit) + " m is not a positive length");
  if (!(o.isoValue > o.airValue)) throw VolumeError(name + ": isoValue must lie above airValue to voxelise a mesh");

  // Closed parts only: a hole wider than half a voxel would let the outside in.
  for (const MeshPart& part : mesh.parts) {
    const OpenEdges open = openEdges(part);
    if (open.count > 0 && open.widestGap * unit > 0.5 * h)
      throw VolumeError(name + ": part '" + part.name + "' is not closed: " + std::to_string(open.count) +
                        " open edges (edges of one triangle only), the first from " + inMillimetres(glm::dvec3(open.from) * unit) +
                        " to " + inMillimetres(glm::dvec3(open.to) * unit) + ", the widest hole " + fmt(open.widestGap * unit * 1e3) +
                        " mm across; close it in a mesh tool (MeshLab: Filters > Remeshing > Close Holes) or export it as a solid");
  }

  MeshVolume out{VoxelVolume(VoxelVolume::Grid::create(o.airValue), glm::ivec3(1), glm::dvec3(h), o.airValue),
                 VoxelVolume(VoxelVolume::Grid::create(0.f), glm::ivec3(1), glm::dvec3(h), 0.f), {}, {}, {}, {}, {}, mesh.format};
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const MeshPart& part : mesh.parts) {
    out.parts.push_back(part.name);
    out.enclosed.push_back(enclosedVolume(part) * unit * unit * unit);
    out.triangles.push_back(part.triangles.size());
    for (const glm::vec3& v : part.vertices) lo = glm::min(lo, glm::dvec3(v) * unit), hi = glm::max(hi, glm::dvec3(v) * unit);
  }
  out.size = hi - lo;
  // Voxel centres on the lattice of multiples of h in the mesh's own
  // coordinates, not on its bounding box: how a shape is sampled does not
  // then depend on where its box ends, and meshes in one frame (a trainee's
  // preparation and the ideal one) voxelise onto the same lattice. Three
  // voxels of air round the mesh: the distance band and the coverage ramp fit inside the box.
  constexpr int kPad = 3;
  const glm::dvec3 first = glm::floor(lo / h) - double(kPad), span = glm::ceil(hi / h) + double(kPad) - first + 1.0;
  // Refused before anything is meshed; a tooth read in the wrong unit is the usual cause.
  if (span.x * span.y * span.z > double(kMaxVoxels)) {
    const bool large = std::max({out.size.x, out.size.y, out.size.z}) > 0.2;
    throw VolumeError(name + ": the mesh is " + fmt(out.size.x * 1e3) + " × " + fmt(out.size.y * 1e3) + " × " +
                      fmt(out.size.z * 1e3) + " mm at " + fmt(unit) + " m per unit; at " + fmt(h * 1e3) + " mm voxels that is " +
                      fmt(span.x * span.y * span.z) + " voxels, more than " + std::to_string(kMaxVoxels) +
                      (large ? " (is the file in millimetres? meshUnit='0.001')" : " (a larger voxelSize needs fewer)"));
  }
  const glm::ivec3 dims(span);
  checkVolumeShape(name, dims, glm::dvec3(h));  // refuses too many voxels before anything is meshed
  const glm::dvec3 half = 0.5 * (glm::dvec3(dims) - 1.0), centre = (first + half) * h;
  out.centre = centre;

  // Largest part first: each next one (inside it, in a nested tooth) is layered over it.
  std::vector<std::size_t> order(mesh.parts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return out.enclosed[a] > out.enclosed[b]; });

  openvdb::initialize();
  const openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
  std::vector<openvdb::FloatGrid::Ptr> distance(mesh.parts.size());
  openvdb::BoolGrid::Ptr material = openvdb::BoolGrid::create(false);
  for (std::size_t p = 0; p < mesh.parts.size(); ++p) {
    const MeshPart& part = mesh.parts[p];
    std::vector<openvdb::Vec3s> points(part.vertices.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::dvec3 index = (glm::dvec3(part.vertices[i]) * unit - centre) / h + half;
      points[i] = openvdb::Vec3s(float(index.x), float(index.y), float(index.z));
    }
    std::vector<openvdb::Vec3I> triangles(part.triangles.size());
    for (std::size_t i = 0; i < triangles.size(); ++i)
      triangles[i] = openvdb::Vec3I(part.triangles[i].x, part.triangles[i].y, part.triangles[i].z);
    const openvdb::tools::QuadAndTriangleDataAdapter<openvdb::Vec3s, openvdb::Vec3I> adapter(points, triangles);
    distance[p] = openvdb::tools::meshToVolume<openvdb::FloatGrid>(adapter, *xform, 2.f, 2.f);
    // Where the part covers any of a voxel: closer than half a voxel outside its surface.
    material->topologyUnion(*openvdb::tools::sdfInteriorMask(*distance[p], float(0.5 * h)));
  }

  // Hard material is wholly material (Milling's fraction 1); a soft part's,
  // as the phantom's pulp, 0.3 — below the isoValue.
  const float air = o.airValue, hard = 2.f * o.isoValue - air, soft = air + 0.6f * (o.isoValue - air);
  std::vector<openvdb::FloatGrid::ConstAccessor> at;
  for (const auto& d : distance) at.push_back(d->getConstAccessor());
  std::vector<double> covered(mesh.parts.size(), 0.0);
  openvdb::FloatGrid::Ptr density = openvdb::FloatGrid::create(air), labels = openvdb::FloatGrid::create(0.f);
  auto dAcc = density->getAccessor();
  auto lAcc = labels->getAccessor();
  auto voxel = [&](const openvdb::Coord& c) {
    if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= dims.x || c.y() >= dims.y || c.z() >= dims.z) return;
    float v = air;
    int innermost = -1, widest = -1;
    double widestCover = 0.0;
    for (std::size_t p : order) {
      const double cover = std::clamp(0.5 - double(at[p].getValue(c)) / h, 0.0, 1.0);
      if (cover <= 0.0) continue;
      covered[p] += cover;
      const bool isSoft = o.softParts.count(mesh.parts[p].name) != 0 || o.softLabels.count(int(p) + 1) != 0;
      v += float(cover) * ((isSoft ? soft : hard) - v);
      if (cover >= 0.5) innermost = int(p);
      if (cover > widestCover) widestCover = cover, widest = int(p);
    }
    if (!(v > air)) return;
    dAcc.setValue(c, v);
    lAcc.setValue(c, float((innermost >= 0 ? innermost : widest) + 1));
  };
  for (auto it = material->cbeginValueOn(); it; ++it) {
    if (it.isVoxelValue()) {
      voxel(it.getCoord());
      continue;
    }
    openvdb::CoordBBox box;
    it.getBoundingBox(box);
    for (auto c = box.begin(); c; ++c) voxel(*c);
  }

  // A part that holds far less than its surface encloses leaked: its
  // outside reached its inside through a hole the edge count let pass.
  const double voxelVolume = h * h * h;
  for (std::size_t p = 0; p < mesh.parts.size(); ++p)
    if (out.enclosed[p] > 64.0 * voxelVolume && covered[p] * voxelVolume < 0.8 * out.enclosed[p])
      throw VolumeError(name + ": part '" + mesh.parts[p].name + "' voxelises to " + fmt(covered[p] * voxelVolume * 1e9) +
                        " mm³ but its surface encloses " + fmt(out.enclosed[p] * 1e9) +
                        " mm³: it is not closed, or its faces cross each other; repair it in a mesh tool");
  out.density = VoxelVolume(density, dims, glm::dvec3(h), air);
  out.labels = VoxelVolume(labels, dims, glm::dvec3(h), 0.f);
  return out;
}

MeshVolume loadMeshVolume(const std::filesystem::path& file, const MeshVoxelOptions& options) {
  return voxeliseMesh(readSurfaceMesh(file), file.string(), options);
}

}  // namespace millsim
