#include "millsim/volume/IsoSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/task_arena.h>
#include <vtkCellArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkTypeInt32Array.h>
#include <vtkTypeInt64Array.h>

namespace millsim {

namespace {

using Grid = VoxelVolume::Grid;
using Leaf = Grid::TreeType::LeafNodeType;
using openvdb::Coord;

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int ceilDiv(int a, int b) { return -floorDiv(-a, b); }

// Chunks k with [k·s − pad, k·s + s + pad] overlapping [lo, hi] along one axis,
// clipped to the chunk grid: pad 0 is "reads a sample in [lo, hi]", pad 1 is
// "also reads it for a gradient".
void chunkRange(int lo, int hi, int s, int pad, int count, int& first, int& last) {
  first = std::max(ceilDiv(lo - s - pad, s), 0);
  last = std::min(floorDiv(hi + pad, s), count - 1);
}

// Copies the values of box [b0, b1] (inclusive) into out, x fastest, block by
// block: a leaf is read straight from its buffer, anything else is a tile or
// background and so constant over the block. Several times faster than one
// accessor lookup per voxel.
void gather(const Grid::ConstAccessor& acc, const Coord& b0, const Coord& b1, float* out) {
  const int nx = b1.x() - b0.x() + 1, ny = b1.y() - b0.y() + 1;
  constexpr int kMask = ~int(Leaf::DIM - 1);
  for (int oz = b0.z() & kMask; oz <= b1.z(); oz += Leaf::DIM)
    for (int oy = b0.y() & kMask; oy <= b1.y(); oy += Leaf::DIM)
      for (int ox = b0.x() & kMask; ox <= b1.x(); ox += Leaf::DIM) {
        const Coord o(ox, oy, oz);
        const int x0 = std::max(ox, b0.x()), x1 = std::min(ox + int(Leaf::DIM) - 1, b1.x());
        const int y0 = std::max(oy, b0.y()), y1 = std::min(oy + int(Leaf::DIM) - 1, b1.y());
        const int z0 = std::max(oz, b0.z()), z1 = std::min(oz + int(Leaf::DIM) - 1, b1.z());
        const Leaf* leaf = acc.probeConstLeaf(o);
        if (!leaf) {
          const float constant = acc.getValue(o);
          for (int z = z0; z <= z1; ++z)
            for (int y = y0; y <= y1; ++y) {
              float* dst = out + (std::size_t(z - b0.z()) * ny + (y - b0.y())) * nx - b0.x();
              std::fill(dst + x0, dst + x1 + 1, constant);
            }
          continue;
        }
        // A leaf stores z fastest: read it in that order (the leaf streams
        // from cache) and scatter into the small output block instead.
        const float* data = leaf->buffer().data();
        const std::size_t zStride = std::size_t(nx) * ny;
        for (int x = x0; x <= x1; ++x)
          for (int y = y0; y <= y1; ++y) {
            const float* src = data + Leaf::coordToOffset(Coord(x, y, 0));
            float* dst = out + (std::size_t(z0 - b0.z()) * ny + (y - b0.y())) * nx + (x - b0.x());
            for (int z = z0; z <= z1; ++z, dst += zStride) *dst = src[z & (Leaf::DIM - 1)];
          }
      }
}

// out = in[-1] + 2 in + in[+1] along `axis`, over the volume-index box
// [from, to]; `in` and `out` are laid out alike over a box starting at volume
// index `origin` with `stride`. A neighbour past the volume's face is the
// sample itself (clamped, as VTK's one-sided differences there).
void smooth121(const float* in, float* out, int axis, glm::ivec3 from, glm::ivec3 to, glm::ivec3 origin,
               const std::ptrdiff_t (&stride)[3], glm::ivec3 dims) {
  for (int z = from.z; z <= to.z; ++z)
    for (int y = from.y; y <= to.y; ++y) {
      const std::size_t r = std::size_t(z - origin.z) * std::size_t(stride[2]) +
                            std::size_t(y - origin.y) * std::size_t(stride[1]) + std::size_t(from.x - origin.x);
      if (axis == 0) {
        for (int x = from.x; x <= to.x; ++x) {
          const std::size_t i = r + std::size_t(x - from.x);
          const std::ptrdiff_t m = x > 0 ? -1 : 0, p = x < dims.x - 1 ? 1 : 0;
          out[i] = in[i + m] + 2.f * in[i] + in[i + p];
        }
      } else {
        const int v = axis == 1 ? y : z;
        const std::ptrdiff_t m = v > 0 ? -stride[axis] : 0, p = v < dims[axis] - 1 ? stride[axis] : 0;
        for (int x = 0; x <= to.x - from.x; ++x) {
          const std::size_t i = r + std::size_t(x);
          out[i] = in[i + m] + 2.f * in[i] + in[i + p];
        }
      }
    }
}

}  // namespace

// One VTK pipeline, reused for every chunk, so that a chunk pays only for its
// own samples and not for setting up a filter and its arrays.
struct IsoSurfaceMesher::Extractor {
  vtkNew<vtkImageData> image;
  vtkNew<vtkFloatArray> scalars;
  vtkNew<vtkFloatArray> gradients;
  vtkNew<vtkFlyingEdges3D> flyingEdges;
  std::vector<float> raw;     // the chunk's samples plus two more on each side
  std::vector<float> padded;  // ... smoothed 1-2-1 on every axis, one more on each side (for gradients)
  std::vector<float> passX, passXY;  // the smoothing's separable passes (raw's layout)
  struct Neighbours {
    std::ptrdiff_t minus, plus;  // offsets in `padded`
    float scale;
  };
  std::vector<Neighbours> stencil[3];
  // Sobel's gradient, separably: `padded` smoothed along y and along z, then
  // each axis's copy smoothed over its two other axes (same layout as padded).
  std::vector<float> alongY, alongZ, forX, forY, forZ;
  std::optional<Grid::ConstAccessor> accessor;
  // VTK's TBB backend runs its loops in the caller's arena. A chunk is far
  // too small to share between threads: waking TBB's workers for each of
  // flying edges' passes took a third of the time of an update. An arena of one thread
  // keeps every chunk on the calling thread, without touching VTK's global
  // SMP settings (which other threads may be using).
  tbb::task_arena serial{1};

  Extractor(const VoxelVolume& volume, float isoValue) {
    image->SetSpacing(volume.voxelSize().x, volume.voxelSize().y, volume.voxelSize().z);
    // The image's extent is the chunk's voxel range (absolute indices), so VTK
    // maps voxel (i, j, k) to indexToLocal(i, j, k) and computes a border
    // vertex from the same absolute index in both chunks: bit-identical.
    const glm::dvec3 origin = volume.indexToLocal(glm::dvec3(0.0));
    image->SetOrigin(origin.x, origin.y, origin.z);
    scalars->SetName("density");
    gradients->SetName("gradient");
    gradients->SetNumberOfComponents(3);
    image->GetPointData()->SetScalars(scalars);
    image->GetPointData()->AddArray(gradients);
    flyingEdges->SetInputData(image);
    flyingEdges->SetValue(0, isoValue);
    flyingEdges->ComputeNormalsOff();  // see IsoSurface.h: they would be one-sided at chunk faces
    flyingEdges->ComputeGradientsOff();
    flyingEdges->ComputeScalarsOff();
    // Interpolates our own gradient array along each cut edge with the
    // vertex's own parameter, exactly as VTK's normals would be, but from
    // differences that reach into the neighbouring chunks.
    flyingEdges->InterpolateAttributesOn();
  }
};

IsoSurfaceMesher::IsoSurfaceMesher(const VoxelVolume& volume, float isoValue, int chunkSize)
    : volume_(&volume), isoValue_(isoValue), chunkSize_(chunkSize) {
  if (chunkSize < 1 || chunkSize > 256)
    throw std::invalid_argument("IsoSurfaceMesher: chunk size " + std::to_string(chunkSize) +
                                " is not between 1 and 256");
  const glm::ivec3 cells = volume.dims() - 1;
  for (int a = 0; a < 3; ++a) chunkGrid_[a] = (cells[a] + chunkSize - 1) / chunkSize;
  extractor_ = std::make_unique<Extractor>(volume, isoValue);
}

IsoSurfaceMesher::~IsoSurfaceMesher() = default;
IsoSurfaceMesher::IsoSurfaceMesher(IsoSurfaceMesher&&) noexcept = default;
IsoSurfaceMesher& IsoSurfaceMesher::operator=(IsoSurfaceMesher&&) noexcept = default;

const MeshChunk* IsoSurfaceMesher::chunk(const ChunkKey& key) const {
  const auto it = chunks_.find(key);
  return it == chunks_.end() ? nullptr : &it->second;
}

std::size_t IsoSurfaceMesher::triangleCount() const {
  std::size_t n = 0;
  for (const auto& [key, c] : chunks_) n += c.indices.size() / 3;
  return n;
}

double IsoSurfaceMesher::totalArea() const {
  double area = 0.0;
  for (const auto& [key, c] : chunks_)
    for (std::size_t t = 0; t + 2 < c.indices.size(); t += 3) {
      const glm::dvec3 a(c.positions[c.indices[t]]), b(c.positions[c.indices[t + 1]]),
          d(c.positions[c.indices[t + 2]]);
      area += 0.5 * glm::length(glm::cross(b - a, d - a));
    }
  return area;
}

void IsoSurfaceMesher::buildAll() {
  chunks_.clear();
  if (chunkGrid_.x <= 0 || chunkGrid_.y <= 0 || chunkGrid_.z <= 0) return;
  const int s = chunkSize_;
  // Only chunks whose samples touch a leaf or an active tile can hold a
  // surface: everything else is the background, a constant. Marking them
  // from the tree costs one visit per leaf instead of a look at every chunk.
  std::vector<char> candidate(std::size_t(chunkGrid_.x) * chunkGrid_.y * chunkGrid_.z, 0);
  auto mark = [&](const openvdb::CoordBBox& box) {
    int f[3], l[3];
    for (int a = 0; a < 3; ++a) chunkRange(box.min()[a], box.max()[a], s, 0, chunkGrid_[a], f[a], l[a]);
    for (int z = f[2]; z <= l[2]; ++z)
      for (int y = f[1]; y <= l[1]; ++y)
        for (int x = f[0]; x <= l[0]; ++x)
          candidate[(std::size_t(z) * chunkGrid_.y + y) * chunkGrid_.x + x] = 1;
  };
  const auto& tree = volume_->grid().tree();
  for (auto leaf = tree.cbeginLeaf(); leaf; ++leaf) mark(leaf->getNodeBoundingBox());
  auto tile = tree.cbeginValueOn();
  tile.setMaxDepth(tile.getLeafDepth() - 1);  // tiles only, not every active voxel
  for (; tile; ++tile) {
    openvdb::CoordBBox box;
    tile.getBoundingBox(box);
    mark(box);
  }

  extractor_->accessor.emplace(volume_->grid().getConstAccessor());
  for (int z = 0; z < chunkGrid_.z; ++z)
    for (int y = 0; y < chunkGrid_.y; ++y)
      for (int x = 0; x < chunkGrid_.x; ++x)
        if (candidate[(std::size_t(z) * chunkGrid_.y + y) * chunkGrid_.x + x]) extract({x, y, z}, nullptr);
  extractor_->accessor.reset();
}

std::vector<IsoSurfaceMesher::ChunkKey> IsoSurfaceMesher::update(const std::vector<BlockOrigin>& dirtyLeafOrigins) {
  // A changed voxel moves the cells on both sides of it and, through the
  // smoothed samples' central-difference gradient, the normals two samples
  // further: pad 2.
  std::map<ChunkKey, char, KeyLess> dirty;
  for (const BlockOrigin& o : dirtyLeafOrigins) {
    int f[3], l[3];
    for (int a = 0; a < 3; ++a) chunkRange(o[a], o[a] + int(Leaf::DIM) - 1, chunkSize_, 2, chunkGrid_[a], f[a], l[a]);
    for (int z = f[2]; z <= l[2]; ++z)
      for (int y = f[1]; y <= l[1]; ++y)
        for (int x = f[0]; x <= l[0]; ++x) dirty.emplace(ChunkKey(x, y, z), 0);
  }
  std::vector<ChunkKey> changed;
  extractor_->accessor.emplace(volume_->grid().getConstAccessor());
  for (const auto& [key, unused] : dirty) extract(key, &changed);
  extractor_->accessor.reset();
  return changed;
}

void IsoSurfaceMesher::extract(const ChunkKey& key, std::vector<ChunkKey>* changed) {
  Extractor& ex = *extractor_;
  const glm::ivec3 dims = volume_->dims();
  const glm::ivec3 lo = key * chunkSize_;
  const glm::ivec3 hi = glm::min(lo + chunkSize_, dims - 1);
  const glm::ivec3 p0 = glm::max(lo - 1, glm::ivec3(0)), p1 = glm::min(hi + 1, dims - 1);
  const glm::ivec3 q0 = glm::max(lo - 2, glm::ivec3(0)), q1 = glm::min(hi + 2, dims - 1);
  const glm::ivec3 n = hi - lo + 1, pn = p1 - p0 + 1, qn = q1 - q0 + 1;

  ex.raw.resize(std::size_t(qn.x) * qn.y * qn.z);
  gather(*ex.accessor, Coord(q0.x, q0.y, q0.z), Coord(q1.x, q1.y, q1.z), ex.raw.data());
  const std::ptrdiff_t rawStride[3] = {1, qn.x, std::ptrdiff_t(qn.x) * qn.y};
  const std::ptrdiff_t stride[3] = {1, pn.x, std::ptrdiff_t(pn.x) * pn.y};
  // The raw sample at the chunk's voxel (lo.x, y, z).
  auto row = [&](int y, int z) {
    return ex.raw.data() + (z - q0.z) * rawStride[2] + (y - q0.y) * rawStride[1] + (lo.x - q0.x);
  };

  // The chunk's own samples for VTK, and whether any cell is cut at all
  // (flying edges calls a sample >= iso "above"): chunks of nothing but
  // material (or, in update(), nothing but air) stop here.
  ex.scalars->SetNumberOfTuples(vtkIdType(n.x) * n.y * n.z);
  float* dst = ex.scalars->GetPointer(0);
  const float iso = isoValue_;
  int below = 0, above = 0;  // counts, not flags, so that the loop vectorises
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y, dst += n.x) {
      const float* src = row(y, z);
      for (int i = 0; i < n.x; ++i) {
        dst[i] = src[i];
        below += src[i] < iso;
        above += src[i] >= iso;
      }
    }
  const bool cut = below > 0 && above > 0;
  if (!cut) {
    if (chunks_.erase(key) && changed) changed->push_back(key);
    return;
  }

  // The samples the gradient is taken of: the raw ones smoothed 1-2-1 along
  // each axis (neighbours clamped at the volume's faces), over the padded box.
  // The phantom's surface is a one-voxel density ramp; a Sobel gradient of it
  // still leans with the sub-voxel phase where the surface crosses the
  // samples, and shaded one ring per voxel on the crown's gentle slopes
  // (docs/images/screens). The smoothing widens the ramp the gradient sees to
  // about three voxels; the mesh itself is the raw samples' iso-surface.
  {
    const std::size_t all = ex.raw.size();
    ex.passX.resize(all), ex.passXY.resize(all);
    auto rawAt = [&](int x, int y, int z) {
      return std::size_t(z - q0.z) * std::size_t(rawStride[2]) + std::size_t(y - q0.y) * std::size_t(rawStride[1]) +
             std::size_t(x - q0.x);
    };
    smooth121(ex.raw.data(), ex.passX.data(), 0, {p0.x, q0.y, q0.z}, {p1.x, q1.y, q1.z}, q0, rawStride, dims);
    smooth121(ex.passX.data(), ex.passXY.data(), 1, {p0.x, p0.y, q0.z}, {p1.x, p1.y, q1.z}, q0, rawStride, dims);
    smooth121(ex.passXY.data(), ex.passX.data(), 2, p0, p1, q0, rawStride, dims);  // passX is free again: the result
    ex.padded.resize(std::size_t(pn.x) * pn.y * pn.z);
    float* smoothed = ex.padded.data();
    for (int z = p0.z; z <= p1.z; ++z)
      for (int y = p0.y; y <= p1.y; ++y) {
        const float* src = ex.passX.data() + rawAt(p0.x, y, z);
        for (int x = 0; x < pn.x; ++x) *smoothed++ = src[x] * (1.f / 64.f);
      }
  }

  // Gradient per voxel (density per voxel): central differences, one-sided
  // at the volume's faces exactly as VTK does there. Per axis, the offsets
  // of the two neighbours used and the factor 1/(their distance).
  for (int a = 0; a < 3; ++a) {
    auto& st = ex.stencil[a];
    st.resize(std::size_t(n[a]));
    for (int i = 0; i < n[a]; ++i) {
      const int v = lo[a] + i, vm = std::max(v - 1, 0), vp = std::min(v + 1, dims[a] - 1);
      st[std::size_t(i)] = {(vm - v) * stride[a], (vp - v) * stride[a], vp > vm ? 1.f / float(vp - vm) : 0.f};
    }
  }
  // Sobel's gradient: each axis's central difference, averaged 1-2-1 over
  // the two other axes. The central difference alone, over the phantom's
  // one-voxel density ramp, leans towards the grid's axes by where the
  // surface crosses the voxel, and shades terraces on smooth slopes. The
  // neighbours are the central difference's (clamped at the volume's faces):
  // one sample beyond the smoothed samples' own, so two in all. Computed separably —
  // smoothed copies of the padded samples, then differences — at about a
  // third of the reads of the 3 × 9 taps.
  const std::size_t box = ex.padded.size();
  for (auto* b : {&ex.alongY, &ex.alongZ, &ex.forX, &ex.forY, &ex.forZ}) b->resize(box);
  const float* samples = ex.padded.data();
  auto at = [&](int x, int y, int z) {
    return std::size_t(z - p0.z) * std::size_t(stride[2]) + std::size_t(y - p0.y) * std::size_t(stride[1]) + std::size_t(x - p0.x);
  };
  auto smooth = [&](const float* in, float* out, int axis, glm::ivec3 from, glm::ivec3 to) {
    smooth121(in, out, axis, from, to, p0, stride, dims);
  };
  auto span = [&](int axis0, int axis1) {  // chunk range on the two axes, padded range on the third
    glm::ivec3 from = p0, to = p1;
    from[axis0] = lo[axis0], to[axis0] = hi[axis0];
    from[axis1] = lo[axis1], to[axis1] = hi[axis1];
    return std::pair{from, to};
  };
  auto only = [&](int axis) {  // chunk range on one axis, padded on the others
    glm::ivec3 from = p0, to = p1;
    from[axis] = lo[axis], to[axis] = hi[axis];
    return std::pair{from, to};
  };
  {
    const auto [fy, ty] = only(1);
    smooth(samples, ex.alongY.data(), 1, fy, ty);
    const auto [fz, tz] = only(2);
    smooth(samples, ex.alongZ.data(), 2, fz, tz);
    const auto [fx1, tx1] = span(1, 2);
    smooth(ex.alongY.data(), ex.forX.data(), 2, fx1, tx1);  // x padded: differenced along x next
    const auto [fy1, ty1] = span(0, 2);
    smooth(ex.alongZ.data(), ex.forY.data(), 0, fy1, ty1);
    const auto [fz1, tz1] = span(0, 1);
    smooth(ex.alongY.data(), ex.forZ.data(), 0, fz1, tz1);
  }
  ex.gradients->SetNumberOfTuples(vtkIdType(n.x) * n.y * n.z);
  float* g = ex.gradients->GetPointer(0);
  const auto *sx = ex.stencil[0].data(), *sy = ex.stencil[1].data(), *sz = ex.stencil[2].data();
  const float *gx = ex.forX.data(), *gy = ex.forY.data(), *gz = ex.forZ.data();
  for (int k = 0; k < n.z; ++k)
    for (int j = 0; j < n.y; ++j) {
      const std::size_t r = at(lo.x, lo.y + j, lo.z + k);
      for (int i = 0; i < n.x; ++i, g += 3) {
        const std::size_t p = r + std::size_t(i);
        g[0] = (gx[p + sx[i].plus] - gx[p + sx[i].minus]) * sx[i].scale * (1.f / 16.f);
        g[1] = (gy[p + sy[j].plus] - gy[p + sy[j].minus]) * sy[j].scale * (1.f / 16.f);
        g[2] = (gz[p + sz[k].plus] - gz[p + sz[k].minus]) * sz[k].scale * (1.f / 16.f);
      }
    }

  ex.image->SetExtent(lo.x, hi.x, lo.y, hi.y, lo.z, hi.z);
  ex.scalars->Modified();
  ex.gradients->Modified();
  ex.image->Modified();
  ex.serial.execute([&] { ex.flyingEdges->Update(); });
  vtkPolyData* out = ex.flyingEdges->GetOutput();
  vtkPoints* points = out->GetPoints();
  vtkCellArray* polys = out->GetPolys();
  const vtkIdType nPoints = points ? points->GetNumberOfPoints() : 0;
  const vtkIdType nTris = polys ? polys->GetNumberOfCells() : 0;
  if (nPoints == 0 || nTris == 0) {
    if (chunks_.erase(key) && changed) changed->push_back(key);
    return;
  }

  MeshChunk& mesh = chunks_[key];
  mesh.version = nextVersion_++;
  mesh.positions.resize(std::size_t(nPoints));
  mesh.normals.resize(std::size_t(nPoints));
  auto* grad = vtkFloatArray::SafeDownCast(out->GetPointData()->GetArray("gradient"));
  if (!grad) throw std::logic_error("IsoSurfaceMesher: flying edges did not interpolate the gradient");
  const glm::vec3 invVoxel(1.0 / volume_->voxelSize());
  bool degenerate = false;
  auto* xyz = vtkFloatArray::SafeDownCast(points->GetData());  // flying edges makes float points
  for (vtkIdType i = 0; i < nPoints; ++i) {
    if (xyz) {
      const float* p = xyz->GetPointer(3 * i);
      mesh.positions[std::size_t(i)] = glm::vec3(p[0], p[1], p[2]);
    } else {
      double p[3];
      points->GetPoint(i, p);
      mesh.positions[std::size_t(i)] = glm::vec3(float(p[0]), float(p[1]), float(p[2]));
    }
    const float* gi = grad->GetPointer(3 * i);
    // Density rises into the object, so the outward normal is −∇density (in
    // metres: divide by the voxel size, which matters for anisotropic voxels).
    const glm::vec3 outward = -glm::vec3(gi[0], gi[1], gi[2]) * invVoxel;
    const float len = glm::length(outward);
    degenerate |= !(len > 0.f);
    mesh.normals[std::size_t(i)] = len > 0.f ? outward / len : glm::vec3(0.f);
  }

  // VTK's triangles are wound clockwise seen from the side the gradient
  // points to, i.e. counter-clockwise seen from outside: keep the order.
  mesh.indices.resize(std::size_t(nTris) * 3);
  auto copyIndices = [&](auto* connectivity) {
    if (connectivity->GetNumberOfValues() != 3 * nTris)
      throw std::logic_error("IsoSurfaceMesher: flying edges produced a cell that is not a triangle");
    const auto* c = connectivity->GetPointer(0);
    for (std::size_t k = 0; k < mesh.indices.size(); ++k) mesh.indices[k] = std::uint32_t(c[k]);
  };
  if (polys->IsStorage64Bit())
    copyIndices(polys->GetConnectivityArray64());
  else
    copyIndices(polys->GetConnectivityArray32());

  // A vertex at a flat spot of the field (zero gradient) takes the mean of
  // its triangles' normals, so graphics never gets a zero normal.
  if (degenerate) {
    std::vector<glm::vec3> faceSum(mesh.positions.size(), glm::vec3(0.f));
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
      const glm::vec3 &a = mesh.positions[mesh.indices[t]], &b = mesh.positions[mesh.indices[t + 1]],
                      &c = mesh.positions[mesh.indices[t + 2]];
      const glm::vec3 face = glm::cross(b - a, c - a);
      for (int v = 0; v < 3; ++v) faceSum[mesh.indices[t + v]] += face;
    }
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
      if (mesh.normals[i] == glm::vec3(0.f) && glm::length(faceSum[i]) > 0.f)
        mesh.normals[i] = glm::normalize(faceSum[i]);
  }
  if (changed) changed->push_back(key);
}

}  // namespace millsim
