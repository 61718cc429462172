// IsoSurfaceMesher: area and normals on an analytic sphere, equality with a
// whole-volume vtkFlyingEdges3D run, incremental updates equal to a fresh
// build, and the empty cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <glm/geometric.hpp>
#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include "millsim/volume/IsoSurface.h"
#include "millsim/volume/ToothPhantom.h"

namespace millsim {
namespace {

constexpr float kAir = 0.f;
constexpr float kIso = 100.f;
constexpr double kPi = 3.14159265358979323846;

// A density that is kIso at signed distance 0 (voxels; negative inside) and
// changes by 100 per voxel, clamped to [air, 10·iso]: smooth like a CT edge.
float densityFromDistance(double d) { return float(std::clamp(kIso - 100.0 * d, double(kAir), 10.0 * kIso)); }

VoxelVolume makeVolume(glm::ivec3 dims, glm::dvec3 h, const std::function<double(glm::dvec3)>& distance) {
  std::vector<float> v(std::size_t(dims.x) * dims.y * dims.z);
  std::size_t n = 0;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) v[n++] = densityFromDistance(distance(glm::dvec3(i, j, k)));
  return VoxelVolume::fromDense(v.data(), dims, h, kAir);
}

// Two overlapping spheres, one of them cut open by the volume's +x face, with
// a box-shaped hole: curved, flat and sharp parts, and an open border.
const glm::ivec3 kCompoundDims{96, 80, 72};
const glm::dvec3 kCentreA{40.3, 38.2, 35.6}, kCentreB{78.7, 41.4, 30.1};
constexpr double kRadiusA = 22.0, kRadiusB = 20.0;
double compoundDistance(glm::dvec3 p) {
  const double a = glm::length(p - kCentreA) - kRadiusA, b = glm::length(p - kCentreB) - kRadiusB;
  const glm::dvec3 q = glm::abs(p - glm::dvec3(52.4, 30.3, 21.2)) - glm::dvec3(6.1, 9.3, 8.2);
  const double hole = glm::length(glm::max(q, 0.0)) + std::min(std::max({q.x, q.y, q.z}), 0.0);
  return std::max(std::min(a, b), -hole);
}
VoxelVolume makeCompound() { return makeVolume(kCompoundDims, glm::dvec3(0.1e-3), compoundDistance); }

struct Mesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
};

double area(const Mesh& m) {
  double a = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 p(m.positions[m.indices[t]]), q(m.positions[m.indices[t + 1]]), r(m.positions[m.indices[t + 2]]);
    a += 0.5 * glm::length(glm::cross(q - p, r - p));
  }
  return a;
}

// The reference: vtkFlyingEdges3D over the whole volume at once, with VTK's normals.
Mesh wholeVolumeFlyingEdges(const VoxelVolume& volume, float iso) {
  const glm::ivec3 d = volume.dims();
  vtkNew<vtkImageData> image;
  image->SetExtent(0, d.x - 1, 0, d.y - 1, 0, d.z - 1);
  image->SetSpacing(volume.voxelSize().x, volume.voxelSize().y, volume.voxelSize().z);
  const glm::dvec3 o = volume.indexToLocal(glm::dvec3(0));
  image->SetOrigin(o.x, o.y, o.z);
  vtkNew<vtkFloatArray> s;
  s->SetNumberOfTuples(vtkIdType(d.x) * d.y * d.z);
  vtkIdType n = 0;
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) s->SetValue(n++, volume.valueAt(i, j, k));
  image->GetPointData()->SetScalars(s);
  vtkNew<vtkFlyingEdges3D> fe;
  fe->SetInputData(image);
  fe->SetValue(0, iso);
  fe->ComputeNormalsOn();
  fe->Update();
  vtkPolyData* out = fe->GetOutput();
  Mesh m;
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i) {
    double p[3], nn[3];
    out->GetPoint(i, p);
    normals->GetTuple(i, nn);
    m.positions.emplace_back(p[0], p[1], p[2]);
    m.normals.emplace_back(nn[0], nn[1], nn[2]);
  }
  vtkNew<vtkIdList> ids;
  auto polys = out->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    EXPECT_EQ(ids->GetNumberOfIds(), 3);
    for (vtkIdType k = 0; k < 3; ++k) m.indices.push_back(std::uint32_t(ids->GetId(k)));
  }
  return m;
}

// All chunks as one mesh (vertices not merged).
Mesh merged(const IsoSurfaceMesher& mesher) {
  Mesh m;
  for (const auto& [key, c] : mesher.chunks()) {
    const auto base = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), c.positions.begin(), c.positions.end());
    m.normals.insert(m.normals.end(), c.normals.begin(), c.normals.end());
    for (auto i : c.indices) m.indices.push_back(base + i);
  }
  return m;
}

// Exact bit pattern of a position: vertices are "the same" only if bit-identical.
struct PosKey {
  std::uint32_t x, y, z;
  bool operator<(const PosKey& o) const { return std::tie(x, y, z) < std::tie(o.x, o.y, o.z); }
};
PosKey key(const glm::vec3& p) {
  PosKey k;
  std::memcpy(&k.x, &p.x, 4);
  std::memcpy(&k.y, &p.y, 4);
  std::memcpy(&k.z, &p.z, 4);
  return k;
}

// Edges used by exactly one triangle after merging bit-identical vertices:
// cracks between chunks would show up here.
std::size_t borderEdges(const Mesh& m) {
  std::map<PosKey, std::uint32_t> ids;
  std::vector<std::uint32_t> weld(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    weld[i] = ids.emplace(key(m.positions[i]), std::uint32_t(ids.size())).first->second;
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
  for (std::size_t t = 0; t < m.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      std::uint32_t a = weld[m.indices[t + e]], b = weld[m.indices[t + (e + 1) % 3]];
      if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return std::size_t(std::count_if(uses.begin(), uses.end(), [](const auto& u) { return u.second == 1; }));
}

// Triangles not wound counter-clockwise seen from the side their vertex
// normals point to. Only possible where the surface has a crease, whose
// vertex normals average both sides.
std::size_t clockwiseFromOutside(const Mesh& m) {
  std::size_t wrong = 0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 &a = m.positions[m.indices[t]], &b = m.positions[m.indices[t + 1]], &c = m.positions[m.indices[t + 2]];
    const glm::vec3 n = m.normals[m.indices[t]] + m.normals[m.indices[t + 1]] + m.normals[m.indices[t + 2]];
    if (glm::dot(glm::cross(b - a, c - a), n) < 0) ++wrong;
  }
  return wrong;
}

TEST(IsoSurfaceMesher, SphereAreaAndOutwardNormals) {
  const double h = 0.1e-3, R = 20.0;
  const glm::dvec3 c(31.3, 32.1, 30.7);
  const VoxelVolume volume = makeVolume({64, 64, 64}, glm::dvec3(h), [&](glm::dvec3 p) { return glm::length(p - c) - R; });
  IsoSurfaceMesher mesher(volume, kIso);
  mesher.buildAll();
  const double expected = 4 * kPi * R * R * h * h;
  EXPECT_NEAR(mesher.totalArea(), expected, 0.01 * expected);

  const Mesh m = merged(mesher);
  const glm::dvec3 centre = volume.indexToLocal(c);
  double dotSum = 0, worst = 1;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const double d = glm::dot(glm::dvec3(m.normals[i]), glm::normalize(glm::dvec3(m.positions[i]) - centre));
    dotSum += d;
    worst = std::min(worst, d);
  }
  EXPECT_GT(dotSum / double(m.positions.size()), 0.9);
  EXPECT_GT(worst, 0.9);  // central differences are this good everywhere on a sphere of 20 voxels
  EXPECT_EQ(clockwiseFromOutside(m), 0u);
  EXPECT_EQ(borderEdges(m), 0u) << "the sphere must be closed across chunk borders";
  EXPECT_GT(mesher.chunkCount(), 8u);
}

TEST(IsoSurfaceMesher, AnisotropicVoxelsGiveMetricNormals) {
  const glm::dvec3 h(0.1e-3, 0.15e-3, 0.2e-3);
  const double radius = 2.5e-3;  // metres
  const glm::ivec3 dims(64, 48, 36);
  const glm::dvec3 c = (glm::dvec3(dims) - 1.0) * 0.5 + glm::dvec3(0.31, -0.17, 0.23);
  const VoxelVolume volume = makeVolume(dims, h, [&](glm::dvec3 p) { return (glm::length((p - c) * h) - radius) / h.x; });
  IsoSurfaceMesher mesher(volume, kIso);
  mesher.buildAll();
  EXPECT_NEAR(mesher.totalArea(), 4 * kPi * radius * radius, 0.01 * 4 * kPi * radius * radius);
  const Mesh m = merged(mesher);
  const glm::dvec3 centre = volume.indexToLocal(c);
  double dotSum = 0;
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    dotSum += glm::dot(glm::dvec3(m.normals[i]), glm::normalize(glm::dvec3(m.positions[i]) - centre));
  EXPECT_GT(dotSum / double(m.positions.size()), 0.99);
}

class IsoSurfaceChunkSize : public ::testing::TestWithParam<int> {};

TEST_P(IsoSurfaceChunkSize, ChunkedEqualsWholeVolumeFlyingEdges) {
  const VoxelVolume volume = makeCompound();
  IsoSurfaceMesher mesher(volume, kIso, GetParam());
  mesher.buildAll();
  const Mesh whole = wholeVolumeFlyingEdges(volume, kIso);
  const Mesh chunked = merged(mesher);
  ASSERT_GT(whole.indices.size(), 1000u);
  // Same cells, same case table, same edge interpolation: the same triangles.
  EXPECT_EQ(mesher.triangleCount(), whole.indices.size() / 3);
  EXPECT_NEAR(mesher.totalArea(), area(whole), 1e-4 * area(whole));
  EXPECT_NEAR(mesher.totalArea(), area(chunked), 1e-9 * area(whole));
  // The open rim where sphere B leaves the volume is the only border, in both.
  const std::size_t rim = borderEdges(whole);
  EXPECT_GT(rim, 0u);
  EXPECT_EQ(borderEdges(chunked), rim);
  // The box hole's sharp edges leave a few triangles whose vertex normals
  // disagree with their face, as VTK's own whole-volume mesh does.
  EXPECT_LT(clockwiseFromOutside(chunked), whole.indices.size() / 3 / 1000);

  // Every vertex is one of the whole-volume vertices, bit for bit. Its
  // normal is the one a single chunk over the whole volume gives (no seams
  // at chunk faces), and near VTK's central-difference normal (ours are
  // smoothed across the two other axes, Sobel's operator).
  std::map<PosKey, glm::vec3> vtkNormal;
  for (std::size_t i = 0; i < whole.positions.size(); ++i) vtkNormal.emplace(key(whole.positions[i]), whole.normals[i]);
  IsoSurfaceMesher single(volume, kIso, 256);
  single.buildAll();
  ASSERT_EQ(single.chunks().size(), 1u);
  const Mesh one = merged(single);
  EXPECT_EQ(clockwiseFromOutside(chunked), clockwiseFromOutside(one));
  std::map<PosKey, glm::vec3> seamless;
  for (std::size_t i = 0; i < one.positions.size(); ++i) seamless.emplace(key(one.positions[i]), one.normals[i]);
  std::size_t missing = 0, leaning = 0;
  double worst = 1;
  for (std::size_t i = 0; i < chunked.positions.size(); ++i) {
    const auto it = vtkNormal.find(key(chunked.positions[i]));
    const auto same = seamless.find(key(chunked.positions[i]));
    if (it == vtkNormal.end() || same == seamless.end()) {
      ++missing;
      continue;
    }
    worst = std::min(worst, double(glm::dot(same->second, chunked.normals[i])));
    leaning += glm::dot(it->second, chunked.normals[i]) < 0.95f;  // 18°
  }
  EXPECT_EQ(missing, 0u);
  EXPECT_GT(worst, 0.99999);
  EXPECT_LT(leaning, chunked.positions.size() / 50) << "at most 2 % of normals more than 18° from VTK's (the box's edges)";
}

INSTANTIATE_TEST_SUITE_P(IsoSurface, IsoSurfaceChunkSize, ::testing::Values(8, 16, 32));

// Sets every voxel within `radius` of `centre` (index space) to air through
// a grid accessor, as milling does, and returns the leaf origins it touched.
std::vector<BlockOrigin> carve(VoxelVolume& volume, glm::dvec3 centre, double radius) {
  auto acc = volume.grid().getAccessor();
  std::set<openvdb::Coord> leaves;
  const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(centre - radius)), 0);
  const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(centre + radius)), volume.dims() - 1);
  for (int k = lo.z; k <= hi.z; ++k)
    for (int j = lo.y; j <= hi.y; ++j)
      for (int i = lo.x; i <= hi.x; ++i)
        if (glm::length(glm::dvec3(i, j, k) - centre) <= radius) {
          acc.setValueOff(openvdb::Coord(i, j, k), volume.airValue());
          leaves.insert(openvdb::Coord(i & ~7, j & ~7, k & ~7));
        }
  std::vector<BlockOrigin> origins;
  for (const openvdb::Coord& c : leaves) origins.emplace_back(c.x(), c.y(), c.z());
  return origins;
}

// A point on sphere A's surface above or below (x, y).
glm::dvec3 onSphereA(double x, double y, double side) {
  const double dx = x - kCentreA.x, dy = y - kCentreA.y;
  return {x, y, kCentreA.z + side * std::sqrt(kRadiusA * kRadiusA - dx * dx - dy * dy)};
}

void expectSameMesh(const IsoSurfaceMesher& updated, const IsoSurfaceMesher& fresh) {
  EXPECT_EQ(updated.triangleCount(), fresh.triangleCount());
  EXPECT_NEAR(updated.totalArea(), fresh.totalArea(), 1e-6 * fresh.totalArea());
  ASSERT_EQ(updated.chunkCount(), fresh.chunkCount());
  for (const auto& [k, c] : fresh.chunks()) {
    const MeshChunk* u = updated.chunk(k);
    ASSERT_NE(u, nullptr) << "chunk " << k.x << "," << k.y << "," << k.z;
    EXPECT_TRUE(u->positions == c.positions) << "chunk " << k.x << "," << k.y << "," << k.z;
    EXPECT_TRUE(u->normals == c.normals) << "chunk " << k.x << "," << k.y << "," << k.z;
    EXPECT_TRUE(u->indices == c.indices) << "chunk " << k.x << "," << k.y << "," << k.z;
  }
}

TEST_P(IsoSurfaceChunkSize, IncrementalUpdateEqualsFullBuild) {
  const int s = GetParam();
  VoxelVolume volume = makeCompound();
  IsoSurfaceMesher mesher(volume, kIso, s);
  mesher.buildAll();
  const std::size_t totalChunks = std::size_t(mesher.chunkGrid().x) * mesher.chunkGrid().y * mesher.chunkGrid().z;

  // First stamp straddles the x = 32 and y = 32 chunk borders (for every
  // chunk size tried); the second sits on x = 48, y = 40, on the other side.
  const glm::dvec3 stamps[] = {onSphereA(32, 32, +1), onSphereA(48, 40, -1)};
  const double radii[] = {5.0, 6.5};
  for (int n = 0; n < 2; ++n) {
    std::map<IsoSurfaceMesher::ChunkKey, std::uint64_t, IsoSurfaceMesher::KeyLess> before;
    for (const auto& [k, c] : mesher.chunks()) before[k] = c.version;
    const double areaBefore = mesher.totalArea();

    const auto dirty = carve(volume, stamps[n], radii[n]);
    const auto changed = mesher.update(dirty);

    IsoSurfaceMesher fresh(volume, kIso, s);
    fresh.buildAll();
    expectSameMesh(mesher, fresh);
    EXPECT_NE(mesher.totalArea(), areaBefore);

    // Only a handful of chunks were re-extracted, and exactly those changed version.
    EXPECT_GE(changed.size(), 2u);
    EXPECT_LE(changed.size(), 64u);
    EXPECT_LT(changed.size(), totalChunks / 4);
    const std::set<IsoSurfaceMesher::ChunkKey, IsoSurfaceMesher::KeyLess> changedSet(changed.begin(), changed.end());
    for (const auto& [k, c] : mesher.chunks()) {
      const auto old = before.find(k);
      if (changedSet.count(k)) {
        if (old != before.end()) {
          EXPECT_GT(c.version, old->second);
        }
      } else {
        ASSERT_NE(old, before.end());
        EXPECT_EQ(c.version, old->second);
      }
    }
  }
}

TEST(IsoSurfaceMesher, UpdateRemovesAChunkThatLostItsSurface) {
  // A small blob inside chunk (1, 1, 1) of 16³ cells.
  const glm::dvec3 c(24.2, 23.6, 24.4);
  VoxelVolume volume = makeVolume({64, 64, 64}, glm::dvec3(0.1e-3), [&](glm::dvec3 p) { return glm::length(p - c) - 3.0; });
  IsoSurfaceMesher mesher(volume, kIso);
  mesher.buildAll();
  ASSERT_EQ(mesher.chunkCount(), 1u);
  ASSERT_NE(mesher.chunk({1, 1, 1}), nullptr);
  const auto changed = mesher.update(carve(volume, c, 6.0));
  EXPECT_EQ(changed, std::vector<IsoSurfaceMesher::ChunkKey>{glm::ivec3(1, 1, 1)});
  EXPECT_EQ(mesher.chunk({1, 1, 1}), nullptr);
  EXPECT_EQ(mesher.chunkCount(), 0u);
  EXPECT_EQ(mesher.triangleCount(), 0u);
}

TEST(IsoSurfaceMesher, NoSurfaceWithoutASignChange) {
  const glm::ivec3 dims(40, 36, 30);
  std::vector<float> values(std::size_t(dims.x) * dims.y * dims.z, kAir);
  const VoxelVolume air = VoxelVolume::fromDense(values.data(), dims, glm::dvec3(0.1e-3), kAir);
  IsoSurfaceMesher airMesher(air, kIso);
  airMesher.buildAll();
  EXPECT_EQ(airMesher.triangleCount(), 0u);
  EXPECT_EQ(airMesher.chunkCount(), 0u);

  // Material everywhere: no surface, not even at the volume's faces (open border).
  std::fill(values.begin(), values.end(), 5 * kIso);
  const VoxelVolume solid = VoxelVolume::fromDense(values.data(), dims, glm::dvec3(0.1e-3), kAir);
  IsoSurfaceMesher solidMesher(solid, kIso);
  solidMesher.buildAll();
  EXPECT_EQ(solidMesher.triangleCount(), 0u);
  EXPECT_EQ(solidMesher.totalArea(), 0.0);
}

TEST(IsoSurfaceMesher, RejectsBadChunkSizes) {
  const glm::ivec3 dims(8, 8, 8);
  std::vector<float> values(512, kAir);
  const VoxelVolume air = VoxelVolume::fromDense(values.data(), dims, glm::dvec3(0.1e-3), kAir);
  EXPECT_THROW(IsoSurfaceMesher(air, kIso, 0), std::invalid_argument);
  EXPECT_THROW(IsoSurfaceMesher(air, kIso, 257), std::invalid_argument);
}

TEST(IsoSurfaceMesher, ToothPhantomMatchesWholeVolumeFlyingEdges) {
  const VoxelVolume tooth = makeToothPhantom(ToothPhantomOptions{{128, 128, 88}, 0.2e-3, false});
  const float iso = 700.f;  // VolumeObject's default isoValue
  IsoSurfaceMesher mesher(tooth, iso);
  mesher.buildAll();
  const Mesh whole = wholeVolumeFlyingEdges(tooth, iso);
  ASSERT_GT(whole.indices.size(), 1000u);
  EXPECT_NEAR(mesher.totalArea(), area(whole), 0.01 * area(whole));
  EXPECT_EQ(mesher.triangleCount(), whole.indices.size() / 3);
}

}  // namespace
}  // namespace millsim
