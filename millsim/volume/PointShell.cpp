#include "millsim/volume/PointShell.h"

#include "millsim/volume/FloorToInt.h"
#include "millsim/volume/VoxelVolume.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

namespace millsim {

namespace {

// The fine voxels updateRegion copied: [lo, lo + dim), z fastest, then y,
// then x, as OpenVDB lays out a leaf, so that the copy moves runs of z.
struct DenseFine {
  const float* data;
  glm::ivec3 lo, dim;
  std::size_t index(int i, int j, int k) const {
    return (std::size_t(i - lo.x) * std::size_t(dim.y) + std::size_t(j - lo.y)) * std::size_t(dim.z) + std::size_t(k - lo.z);
  }
  std::size_t strideX() const { return std::size_t(dim.y) * std::size_t(dim.z); }
  std::size_t strideY() const { return std::size_t(dim.z); }
  float operator()(int i, int j, int k) const { return data[index(i, j, k)]; }
  // The cell's corners from (x, y, z): c[a + 2b + 4c] is voxel (x + a, y + b, z + c).
  // One index and seven offsets, not eight indices (trilinear() was a
  // quarter of the shell update's instructions; 0.87 -> 0.66 G over #3's
  // §8.2 replay with this).
  void corners(int x, int y, int z, float c[8]) const {
    const float* p = data + index(x, y, z);
    const std::size_t sx = strideX(), sy = strideY();
    c[0] = p[0], c[1] = p[sx], c[2] = p[sy], c[3] = p[sx + sy];
    c[4] = p[1], c[5] = p[sx + 1], c[6] = p[sy + 1], c[7] = p[sx + sy + 1];
  }
};

// The densest fine voxel of each coarse voxel of the box [lo, lo + dim) (air
// outside the volume's coarseDims), written z fastest as DenseFine lays it
// out. S is the scale when known at compile time (0: `scale` at run time):
// the s³ reads then unroll, where the run-time loops were 38 % of a scale-3
// milling frame's instructions (bench/MillingBench.cpp, callgrind).
template <int S>
void densestOfEach(const DenseFine& fine, float* out, glm::ivec3 lo, glm::ivec3 dim, glm::ivec3 coarseDims, float air,
                   int scale = S) {
  const int s = S > 0 ? S : scale;
  const std::size_t sx = fine.strideX(), sy = fine.strideY();
  for (int I = lo.x; I < lo.x + dim.x; ++I)
    for (int J = lo.y; J < lo.y + dim.y; ++J)
      for (int K = lo.z; K < lo.z + dim.z; ++K) {
        float v = air;
        if (I >= 0 && J >= 0 && K >= 0 && I < coarseDims.x && J < coarseDims.y && K < coarseDims.z) {
          const float* block = fine.data + fine.index(I * s, J * s, K * s);
          for (int i = 0; i < s; ++i)
            for (int j = 0; j < s; ++j) {
              const float* run = block + std::size_t(i) * sx + std::size_t(j) * sy;
              for (int k = 0; k < s; ++k) v = std::max(v, run[k]);
            }
        }
        *out++ = v;
      }
}

// Dense copies of a region: F, the fine voxels it reads, and the coarse values
// of E (F itself at scale 1).
struct DenseRegion {
  DenseFine fine, coarse;
};

// Copies F into `fineOut` leaf by leaf (one tree lookup per 8³ block instead
// of one per voxel) and, at scale > 1, E's coarse values into `coarseOut`.
DenseRegion copyDense(const VoxelVolume& volume, int scale, glm::ivec3 coarseDims, glm::ivec3 eLo, glm::ivec3 eDim,
                      float* fineOut, float* coarseOut) {
  // F reaches one voxel further each way: the iso-surface search of a point
  // walks up to s voxels (per axis) from its block and reads one beyond (trilinear).
  const glm::ivec3 fLo = eLo * scale - 1, fDim = eDim * scale + 2;
  const auto& tree = volume.grid().tree();
  using Leaf = VoxelVolume::Grid::TreeType::LeafNodeType;
  const glm::ivec3 fHi = fLo + fDim - 1;
  const DenseFine fine{fineOut, fLo, fDim};
  for (int oz = fLo.z & ~7; oz <= fHi.z; oz += 8)
    for (int oy = fLo.y & ~7; oy <= fHi.y; oy += 8)
      for (int ox = fLo.x & ~7; ox <= fHi.x; ox += 8) {
        const openvdb::Coord origin(ox, oy, oz);
        const Leaf* leaf = tree.probeConstLeaf(origin);
        const glm::ivec3 lo = glm::max(glm::ivec3(ox, oy, oz), fLo), hi = glm::min(glm::ivec3(ox, oy, oz) + 7, fHi);
        if (!leaf) {  // a tile: one value for the whole block
          const float tile = tree.getValue(origin);
          for (int i = lo.x; i <= hi.x; ++i)
            for (int j = lo.y; j <= hi.y; ++j) {
              float* run = fineOut + fine.index(i, j, lo.z);
              std::fill(run, run + (hi.z - lo.z) + 1, tile);
            }
          continue;
        }
        // The leaf's values straight from its buffer, a run of z at a time
        // (the same order as the copy's): no per-voxel lookup, and no
        // strided read (across x that was a quarter of updateRegion's own
        // instructions).
        const float* data = leaf->buffer().data();
        for (int i = lo.x; i <= hi.x; ++i)
          for (int j = lo.y; j <= hi.y; ++j)
            std::copy_n(data + ((i & 7) << 6) + ((j & 7) << 3) + (lo.z & 7), hi.z - lo.z + 1, fineOut + fine.index(i, j, lo.z));
      }
  // Coarse values of E, exactly as PointShell::coarse() computes them (the
  // densest fine voxel). At scale 1 they are the fine voxels: F itself.
  if (scale == 1) return {fine, fine};
  if (scale == 2) densestOfEach<2>(fine, coarseOut, eLo, eDim, coarseDims, volume.airValue());
  else if (scale == 3) densestOfEach<3>(fine, coarseOut, eLo, eDim, coarseDims, volume.airValue());
  else densestOfEach<0>(fine, coarseOut, eLo, eDim, coarseDims, volume.airValue(), scale);
  return {fine, DenseFine{coarseOut, eLo, eDim}};
}

// The fine voxels read through the grid's accessor (a bucket built or rebuilt whole).
template <class Accessor> struct AccessorFine {
  const Accessor& acc;
  float operator()(int i, int j, int k) const { return acc.getValue(openvdb::Coord(i, j, k)); }
  void corners(int x, int y, int z, float c[8]) const {
    for (int n = 0; n < 8; ++n) c[n] = (*this)(x + (n & 1), y + ((n >> 1) & 1), z + (n >> 2));
  }
};

// Trilinear value of the fine field at p (fine index units; integers are voxel centres).
template <class Fine> double trilinear(const Fine& fine, const glm::dvec3& p) {
  const int x = floorToInt(p.x), y = floorToInt(p.y), z = floorToInt(p.z);
  const glm::dvec3 f = p - glm::dvec3(x, y, z);
  // At a voxel centre (where every point's walk starts at scale 1) the
  // weights below are all 0 and give exactly the voxel's value.
  if (f.x == 0.0 && f.y == 0.0 && f.z == 0.0) return fine(x, y, z);
  float c[8];
  fine.corners(x, y, z, c);
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double c00 = lerp(c[0], c[1], f.x);
  const double c10 = lerp(c[2], c[3], f.x);
  const double c01 = lerp(c[4], c[5], f.x);
  const double c11 = lerp(c[6], c[7], f.x);
  return lerp(lerp(c00, c10, f.y), lerp(c01, c11, f.y), f.z);
}

// The iso-crossing between a (value va > iso) and b (vb <= iso) on the
// trilinear field. One linear interpolation was the first choice, but the
// field is not linear along a diagonal: at a convex edge (a corner voxel
// whose face neighbours sit at the iso-value) it is quadratic, and the
// interpolated point lay 0.3 voxel inside the edge, which the trilinear
// iso-surface keeps sharp (issue 14). One regula-falsi step on the field
// itself: sample at the interpolated point and interpolate again in the half
// that holds the crossing. More steps changed the physical suite's figures by
// under 0.3 % and cost a milling frame 10 µs p50 each (the shell update).
// Exact on a flat face, where the field is linear along the normal.
template <class Fine>
glm::dvec3 refine(const Fine& fine, double iso, glm::dvec3 a, double va, glm::dvec3 b, double vb) {
  const glm::dvec3 m = a + (b - a) * ((va - iso) / (va - vb));
  const double vm = trilinear(fine, m);
  if (vm > iso) a = m, va = vm;
  else if (vm < iso) b = m, vb = vm;
  else return m;
  return a + (b - a) * ((va - iso) / (va - vb));
}

}  // namespace

// A coarse point starts at the centroid of its block's material, not at the
// block centre: at the centre it could outlive the material it stands for. A
// burr that had cut all but a corner voxel of a block rested on a point in the
// middle of its own cut, which no cut within its reach could remove, and
// milling stalled (the §8.2 procedure at pointShellScale 3).
template <class Fine>
glm::dvec3 PointShell::materialCentre(const Fine& fine, int I, int J, int K) const {
  const glm::dvec3 centre = glm::dvec3(I, J, K) * double(scale_) + 0.5 * (scale_ - 1);
  if (scale_ == 1) return centre;
  glm::dvec3 sum(0.0);
  int n = 0;
  for (int k = 0; k < scale_; ++k)
    for (int j = 0; j < scale_; ++j)
      for (int i = 0; i < scale_; ++i) {
        const int x = I * scale_ + i, y = J * scale_ + j, z = K * scale_ + k;
        if (fine(x, y, z) > iso_) sum += glm::dvec3(x, y, z), ++n;
      }
  return n > 0 ? sum / double(n) : centre;
}

PointShell::PointShell(const VoxelVolume& volume, float isoValue, int scale, std::size_t headroomPerPoint,
                       std::size_t minHeadroom)
    : volume_(&volume), iso_(isoValue) {
  scale_ = scale;
  if (scale < 1) throw VolumeError("point shell scale must be a positive integer, got " + std::to_string(scale));
  coarseDims_ = (volume.dims() + scale - 1) / scale;
  bucketDims_ = (coarseDims_ + kBucket - 1) / kBucket;
  superDims_ = (bucketDims_ + kSuper - 1) / kSuper;
  buckets_.resize(std::size_t(bucketDims_.x) * bucketDims_.y * bucketDims_.z);
  supers_.resize(std::size_t(superDims_.x) * superDims_.y * superDims_.z);
  for (int bz = 0; bz < bucketDims_.z; ++bz)
    for (int by = 0; by < bucketDims_.y; ++by)
      for (int bx = 0; bx < bucketDims_.x; ++bx) {
        const int s = ((bz / kSuper) * superDims_.y + by / kSuper) * superDims_.x + bx / kSuper;
        supers_[std::size_t(s)].buckets.push_back((bz * bucketDims_.y + by) * bucketDims_.x + bx);
      }

  // Only a bucket that holds material now can ever hold points (milling only
  // removes material): mark those.
  for (auto leaf = volume.grid().tree().cbeginLeaf(); leaf; ++leaf) {
    if (leaf->onVoxelCount() == 0) continue;
    const openvdb::Coord o = leaf->origin();
    // A fine leaf can reach into two coarse buckets per axis at most.
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const glm::ivec3 b = glm::ivec3(o.x() + dx * 7, o.y() + dy * 7, o.z() + dz * 7) / scale / kBucket;
          if (glm::any(glm::greaterThanEqual(b, bucketDims_))) continue;
          buckets_[std::size_t((b.z * bucketDims_.y + b.y) * bucketDims_.x + b.x)].material = true;
        }
  }
  for (auto& s : supers_) s.buckets.shrink_to_fit();
  // Scratch, written now so that it is resident before the haptic thread uses
  // it. A merged bucket can list two points per voxel before the cap. The
  // coarse copy of a region is at most 1/s³ of its fine copy.
  merged_.resize(2 * kMaxBucketPoints);
  mergedCells_.resize(2 * kMaxBucketPoints);
  scratchEdge_ = std::min(kScratchEdge, kTileEdge + 6 * scale + 2);
  const std::size_t scratchVoxels = std::size_t(scratchEdge_) * std::size_t(scratchEdge_) * std::size_t(scratchEdge_);
  fineScratch_.resize(scratchVoxels);
  coarseScratch_.resize(scratchVoxels / std::size_t(scale * scale * scale));
  std::size_t materialBuckets = 0;
  for (const Bucket& b : buckets_) materialBuckets += b.material;
  order_.resize(materialBuckets);
  // The points of every bucket on TBB's threads, each from a dense copy of its
  // region (voxel by voxel through an accessor, the three shells were 4.4 of
  // the 11 s of a 25 µm `check`), then laid out tight in bucket order: the
  // same array whatever the split.
  struct Built {
    std::vector<ShellPoint> points;
    std::vector<std::uint16_t> cells;
  };
  std::vector<Built> built(buckets_.size());
  const int eEdge = kBucket + 2, fEdge = eEdge * scale + 2;
  using Scratch = std::pair<std::vector<float>, std::vector<float>>;
  tbb::enumerable_thread_specific<Scratch> scratch([&] {
    return Scratch(std::size_t(fEdge) * fEdge * fEdge, scale == 1 ? 0 : std::size_t(eEdge) * eEdge * eEdge);
  });
  tbb::parallel_for(tbb::blocked_range<int>(0, int(buckets_.size())), [&](const tbb::blocked_range<int>& range) {
    Scratch& buffers = scratch.local();
    for (int b = range.begin(); b != range.end(); ++b) {
      if (!buckets_[std::size_t(b)].material) continue;  // never held material: no points, ever
      const glm::ivec3 cLo = glm::ivec3(b % bucketDims_.x, (b / bucketDims_.x) % bucketDims_.y,
                                        b / (bucketDims_.x * bucketDims_.y)) * kBucket;
      const glm::ivec3 cHi = glm::min(cLo + kBucket, coarseDims_) - 1;
      const DenseRegion dense =
          copyDense(volume, scale, coarseDims_, cLo - 1, cHi - cLo + 3, buffers.first.data(), buffers.second.data());
      Built& out = built[std::size_t(b)];
      scanDense(dense, cLo, cHi, [&](int I, int J, int K, const ShellPoint* p, int m) {
        for (int q = 0; q < m && out.points.size() < kMaxBucketPoints; ++q) {  // computeBucket's cap
          out.points.push_back(p[q]);
          out.cells.push_back(std::uint16_t(((K - cLo.z) * kBucket + (J - cLo.y)) * kBucket + (I - cLo.x)));
        }
      });
    }
  });
  // One array of exactly the points plus the headroom, written through
  // (nothing reserved unwritten), each bucket's points freed once copied.
  for (const Built& in : built) count_ += in.points.size();
  const std::size_t slots = count_ + std::max(count_ * headroomPerPoint, minHeadroom);
  points_.assign(slots, ShellPoint{}), cells_.assign(slots, 0);
  for (std::size_t b = 0; b < buckets_.size(); ++b) {
    Bucket& bucket = buckets_[b];
    Built& in = built[b];
    bucket.size = bucket.capacity = std::uint16_t(in.points.size());
    bucket.begin = std::uint32_t(tail_);
    for (const ShellPoint& p : in.points) bucket.box.add(p.position);
    std::copy(in.points.begin(), in.points.end(), points_.begin() + std::ptrdiff_t(tail_));
    std::copy(in.cells.begin(), in.cells.end(), cells_.begin() + std::ptrdiff_t(tail_));
    tail_ += in.points.size();
    in = Built{};
  }
  for (int s = 0; s < int(supers_.size()); ++s) refreshSuper(s);
}

// Density of the coarse voxel (I, J, K): the densest of the s³ fine voxels it
// covers. The maximum, not the mean, so that material thinner than s voxels
// (a 1-voxel plate averages to a third of its density at s = 3 and vanishes)
// still yields shell points: a coarse shell may sit up to (s − 1)/2 voxels
// proud of the surface, but it never lets the tool through material.
template <class Accessor>
float PointShell::coarse(const Accessor& acc, int I, int J, int K) const {
  if (scale_ == 1) return acc.getValue(openvdb::Coord(I, J, K));
  if (I < 0 || J < 0 || K < 0 || I >= coarseDims_.x || J >= coarseDims_.y || K >= coarseDims_.z)
    return volume_->airValue();
  float densest = volume_->airValue();
  for (int k = 0; k < scale_; ++k)
    for (int j = 0; j < scale_; ++j)
      for (int i = 0; i < scale_; ++i)
        densest = std::max(densest, acc.getValue(openvdb::Coord(I * scale_ + i, J * scale_ + j, K * scale_ + k)));
  return densest;
}

template <class Accessor>
std::size_t PointShell::computeBucket(const Accessor& acc, int b) {
  const Bucket& bucket = buckets_[std::size_t(b)];
  std::size_t n = 0;
  if (bucket.material) {  // else it never held material: no points, ever
    const int bx = b % bucketDims_.x, by = (b / bucketDims_.x) % bucketDims_.y,
              bz = b / (bucketDims_.x * bucketDims_.y);
    const glm::ivec3 lo = glm::ivec3(bx, by, bz) * kBucket;
    const glm::ivec3 hi = glm::min(lo + kBucket, coarseDims_);
    for (int K = lo.z; K < hi.z; ++K)
      for (int J = lo.y; J < hi.y; ++J)
        for (int I = lo.x; I < hi.x; ++I) {
          const float v = coarse(acc, I, J, K);
          if (v <= iso_) continue;
          const float nb[6] = {coarse(acc, I - 1, J, K), coarse(acc, I + 1, J, K), coarse(acc, I, J - 1, K),
                               coarse(acc, I, J + 1, K), coarse(acc, I, J, K - 1), coarse(acc, I, J, K + 1)};
          ShellPoint p[2];
          const int m = makePoints(AccessorFine<Accessor>{acc}, v, nb, I, J, K, p);
          for (int q = 0; q < m && n < kMaxBucketPoints; ++q) {
            merged_[n] = p[q];
            mergedCells_[n++] = std::uint16_t(((K - lo.z) * kBucket + (J - lo.y)) * kBucket + (I - lo.x));
          }
        }
  }
  return n;
}

void PointShell::store(int b, std::size_t n, bool tight) {
  Bucket& bucket = buckets_[std::size_t(b)];
  count_ -= bucket.size;
  n = std::min(n, kMaxBucketPoints);
  if (n > bucket.capacity) {
    // Outgrown: a new range at the free end, with slack for more milling.
    std::size_t want = tight ? n : std::min(kMaxBucketPoints, n + n / 4 + 16);
    if (points_.size() - tail_ < want) {
      bucket.size = 0;  // being replaced: compaction need not keep its points
      compact();
      const std::size_t room = points_.size() - tail_;
      if (room < want) want = std::min(n, room);
      if (want < n) droppedPoints_ += n - want, n = want;  // the cap
    }
    bucket.begin = std::uint32_t(tail_);
    bucket.capacity = std::uint16_t(want);
    tail_ += want;
    ++relocations_;
  }
  std::copy(merged_.begin(), merged_.begin() + std::ptrdiff_t(n), points_.begin() + bucket.begin);
  std::copy(mergedCells_.begin(), mergedCells_.begin() + std::ptrdiff_t(n), cells_.begin() + bucket.begin);
  bucket.size = std::uint16_t(n);
  count_ += n;
  bucket.box = Aabb{};
  for (std::size_t i = 0; i < n; ++i) bucket.box.add(merged_[i].position);
}

void PointShell::compact() {
  std::size_t m = 0;
  for (int b = 0; b < int(buckets_.size()); ++b)
    if (buckets_[std::size_t(b)].material) order_[m++] = b;
  // Array order (ranges never overlap), so each bucket only ever slides down.
  std::sort(order_.begin(), order_.begin() + std::ptrdiff_t(m), [&](int a, int b) {
    const std::uint32_t x = buckets_[std::size_t(a)].begin, y = buckets_[std::size_t(b)].begin;
    return x < y || (x == y && a < b);
  });
  std::size_t cursor = 0;
  for (std::size_t i = 0; i < m; ++i) {
    Bucket& bucket = buckets_[std::size_t(order_[i])];
    if (bucket.size != 0 && bucket.begin != cursor) {
      std::copy(points_.begin() + bucket.begin, points_.begin() + bucket.begin + bucket.size, points_.begin() + std::ptrdiff_t(cursor));
      std::copy(cells_.begin() + bucket.begin, cells_.begin() + bucket.begin + bucket.size, cells_.begin() + std::ptrdiff_t(cursor));
    }
    bucket.begin = std::uint32_t(cursor);
    bucket.capacity = bucket.size;
    cursor += bucket.size;
  }
  tail_ = cursor;
  ++compactions_;
}

// Voxel centres lie up to a voxel inside the surface they stand for; left
// there, every contact began that deep (Algorithm #3 felt the surface half a
// voxel late on average, 1.2 voxels at s = 3: force errors of 30-50 % in the
// accuracy suite). One-voxel steps along the normal, then linear
// interpolation between the last two samples, as marching cubes places its
// vertices.
template <class Fine>
glm::dvec3 PointShell::ontoSurface(const Fine& fine, glm::dvec3 at, const glm::dvec3& outward, double startValue) const {
  const glm::dvec3 vs = volume_->voxelSize();
  const glm::dvec3 step = outward * std::min({vs.x, vs.y, vs.z}) / vs;  // one (smallest) voxel, in index units
  double v0 = std::isnan(startValue) ? trilinear(fine, at) : startValue;
  if (!(v0 > iso_)) return at;  // a sliver whose centroid samples outside: leave it
  // Up to s voxels along each axis (a box, not a ball: a corner voxel's point
  // walks a diagonal, √2–√3 voxels to a convex edge; s voxels along the
  // normal stopped it short and rounded every edge by 0.4 voxel, so a burr
  // on an edge at h = 0.1 mm felt it 0.04 mm late; issue 14). The box is
  // what the shell update's stencil covers (one coarse voxel around).
  const glm::dvec3 lo = at - double(scale_), hi = at + double(scale_);
  const double perStep = std::max({std::abs(step.x), std::abs(step.y), std::abs(step.z)});
  double travelled = 0.0;  // the largest per-axis distance from the start so far
  for (int i = 0; travelled < double(scale_) && i < 2 * scale_ + 2; ++i) {  // at most ⌈s·√3⌉ steps, and a rounding
    const double frac = std::min(1.0, (double(scale_) - travelled) / perStep);
    const glm::dvec3 next = frac == 1.0 ? at + step : glm::clamp(at + step * frac, lo, hi);
    const double v1 = trilinear(fine, next);
    if (v1 <= iso_) return refine(fine, iso_, at, v0, next, v1);
    at = next, v0 = v1, travelled += perStep * frac;
  }
  return at;  // still inside s voxels out: as far as the block's stencil allows
}

template <class Fine>
int PointShell::makePoints(const Fine& fine, float v, const float n[6], int I, int J, int K, ShellPoint out[2]) const {
  if (v <= iso_) return 0;
  bool surface = false;
  for (int i = 0; i < 6; ++i) surface |= n[i] <= iso_;
  if (!surface) return 0;
  const glm::dvec3 centre = materialCentre(fine, I, J, K);
  auto place = [&](const glm::dvec3& normal) {
    // At scale 1 the walk starts at the voxel's centre, where the field is
    // the voxel's own value (one trilinear sample less a point: 3 % of #3's
    // milling frames).
    const double start = scale_ == 1 ? double(v) : std::numeric_limits<double>::quiet_NaN();
    return ShellPoint{glm::vec3(volume_->indexToLocal(ontoSurface(fine, centre, normal, start))), glm::vec3(normal)};
  };
  // A sheet one voxel thin across an axis has a surface on each side, and one
  // point can face only one way. Its normal would come from which outside
  // neighbour is less empty: on a one-voxel plate at scale 2 that was the far
  // side, so the tool met nothing until it reached the far face and was then
  // pushed the wrong way (found by the accuracy suite). Two points, one per face.
  for (int a = 0; a < 3; ++a)
    if (n[2 * a] <= iso_ && n[2 * a + 1] <= iso_) {
      glm::dvec3 e(0.0);
      e[a] = 1.0;
      out[0] = place(-e), out[1] = place(e);
      return 2;
    }
  // Outward normal: down the density gradient (central differences; the
  // voxel size makes it a gradient in metres for anisotropic volumes). Not a
  // sheet, so along each axis with an outside neighbour the other is inside
  // and the gradient cannot vanish.
  const glm::dvec3 h = volume_->voxelSize() * double(scale_);
  const glm::dvec3 g((n[1] - n[0]) / h.x, (n[3] - n[2]) / h.y, (n[5] - n[4]) / h.z);
  out[0] = place(-g / glm::length(g));
  return 1;
}

void PointShell::rebuildAll(const VoxelVolume& volume) {
  auto acc = volume.grid().getConstAccessor();
  // A fresh tight layout from the start of the array (each bucket is
  // recomputed before it is written, so overwriting old ranges loses nothing).
  for (Bucket& b : buckets_) b.begin = 0, b.size = 0, b.capacity = 0;
  count_ = 0, tail_ = 0;
  for (int b = 0; b < int(buckets_.size()); ++b) store(b, computeBucket(acc, b), true);
  for (int s = 0; s < int(supers_.size()); ++s) refreshSuper(s);
}

int PointShell::update(const VoxelVolume& volume, const DirtyBlocks& dirty) {
  if (dirty.empty()) return 0;
  int rebuilt = 0;
  if (updateRegion(volume, dirty.voxelLo(), dirty.voxelHi(), rebuilt)) return rebuilt;
  // The changes of many stamps (a shell that was not looked at for a while)
  // outgrow the scratch space: cover their box with cubes whose fine region
  // fits (edge + 6s + 2 fine voxels with the stencils' margins) and update
  // the cubes that hold a marked block. The volume is already in its final
  // state, so cube by cube gives what one pass over the box would.
  const int edge = (scratchEdge_ - 6 * scale_ - 2) / 8 * 8;
  if (edge >= 8) {
    const glm::ivec3 lo = dirty.voxelLo(), hi = dirty.voxelHi();
    bool fits = true;
    for (int z = lo.z & ~7; z <= hi.z && fits; z += edge)
      for (int y = lo.y & ~7; y <= hi.y && fits; y += edge)
        for (int x = lo.x & ~7; x <= hi.x && fits; x += edge) {
          bool marked = false;
          for (int k = z; k < z + edge && !marked; k += 8)
            for (int j = y; j < y + edge && !marked; j += 8)
              for (int i = x; i < x + edge && !marked; i += 8) marked = dirty.markedVoxel(i, j, k);
          if (!marked) continue;
          const glm::ivec3 t(x, y, z);
          fits = updateRegion(volume, glm::max(t, lo), glm::min(t + edge - 1, hi), rebuilt);
        }
    if (fits) return rebuilt;
  }
  return rebuilt + update(volume, dirty.origins());
}

// Every coarse voxel of [rLo, rHi] that has shell points, in scan order (K,
// J, I, as a bucket lists them), from a dense copy of its region.
template <class Dense, class Emit>
void PointShell::scanDense(const Dense& dense, glm::ivec3 rLo, glm::ivec3 rHi, Emit&& emit) const {
  const std::ptrdiff_t sx = std::ptrdiff_t(dense.coarse.strideX()), sy = std::ptrdiff_t(dense.coarse.strideY());
  for (int K = rLo.z; K <= rHi.z; ++K)
    for (int J = rLo.y; J <= rHi.y; ++J) {
      // A row at a time, the neighbours at fixed strides: most of the
      // box is air or deep material, and a 3-D index for each of the
      // seven reads was most of the loop's cost.
      const float* row = dense.coarse.data + dense.coarse.index(rLo.x, J, K);
      for (int I = rLo.x; I <= rHi.x; ++I) {
        const float* c = row + (I - rLo.x) * sx;
        const float v = *c;
        if (v <= iso_) continue;
        const float n[6] = {c[-sx], c[sx], c[-sy], c[sy], c[-1], c[1]};
        ShellPoint p[2];
        const int m = makePoints(dense.fine, v, n, I, J, K, p);
        if (m != 0) emit(I, J, K, p, m);
      }
    }
}

bool PointShell::updateRegion(const VoxelVolume& volume, glm::ivec3 vlo, glm::ivec3 vhi, int& rebuilt) {
  if (glm::any(glm::greaterThan(vlo, vhi))) return true;  // nothing marked
  // C: coarse voxels whose value, surface status or normal can have changed
  // (the changed coarse voxels and their six-neighbours); E: C plus the
  // neighbours their test reads; F: the fine voxels E reads.
  const glm::ivec3 cLo = glm::max(vlo / scale_ - 1, glm::ivec3(0));
  const glm::ivec3 cHi = glm::min(vhi / scale_ + 1, coarseDims_ - 1);
  if (glm::any(glm::greaterThan(cLo, cHi))) return true;
  const glm::ivec3 eLo = cLo - 1, eDim = cHi - cLo + 3;
  const glm::ivec3 fDim = eDim * scale_ + 2;  // as copyDense reads F
  const std::size_t fineCount = std::size_t(fDim.x) * fDim.y * fDim.z;
  if (fineCount > fineScratch_.size() || std::size_t(eDim.x) * eDim.y * eDim.z > coarseScratch_.size()) return false;
  const DenseRegion dense = copyDense(volume, scale_, coarseDims_, eLo, eDim, fineScratch_.data(), coarseScratch_.data());

  // Each bucket overlapping C: keep its points outside C, recompute those in C,
  // merged in scan order (K, J, I) as a full rebuild would list them.
  const glm::ivec3 bLo = cLo / kBucket, bHi = cHi / kBucket;
  for (int bz = bLo.z; bz <= bHi.z; ++bz)
    for (int by = bLo.y; by <= bHi.y; ++by)
      for (int bx = bLo.x; bx <= bHi.x; ++bx) {
        const int b = (bz * bucketDims_.y + by) * bucketDims_.x + bx;
        Bucket& bucket = buckets_[std::size_t(b)];
        if (!bucket.material) continue;  // never held material
        const glm::ivec3 rLo = glm::max(glm::ivec3(bx, by, bz) * kBucket, cLo);
        const glm::ivec3 rHi = glm::min(glm::ivec3(bx, by, bz) * kBucket + kBucket - 1, cHi);
        const glm::ivec3 bo = glm::ivec3(bx, by, bz) * kBucket;
        auto cellOf = [&](int I, int J, int K) {
          return std::uint16_t(((K - bo.z) * kBucket + (J - bo.y)) * kBucket + (I - bo.x));
        };
        std::size_t merged = 0;  // points in merged_ so far
        std::size_t old = 0;
        const std::size_t nOld = bucket.size;
        const ShellPoint* oldPoints = points_.data() + bucket.begin;
        const std::uint16_t* oldCells = cells_.data() + bucket.begin;
        auto flushOldBefore = [&](int cell) {
          for (; old < nOld; ++old) {
            const int c = oldCells[old];
            if (c >= cell) break;
            const glm::ivec3 at = bo + glm::ivec3(c % kBucket, (c / kBucket) % kBucket, c / (kBucket * kBucket));
            if (glm::all(glm::greaterThanEqual(at, rLo)) && glm::all(glm::lessThanEqual(at, rHi))) continue;  // recomputed
            merged_[merged] = oldPoints[old];
            mergedCells_[merged++] = std::uint16_t(c);
          }
        };
        scanDense(dense, rLo, rHi, [&](int I, int J, int K, const ShellPoint* p, int m) {
          flushOldBefore(cellOf(I, J, K));
          for (int q = 0; q < m; ++q) {
            merged_[merged] = p[q];
            mergedCells_[merged++] = cellOf(I, J, K);
          }
        });
        flushOldBefore(std::numeric_limits<int>::max());
        // The same cap as a rebuild (the tail of a bucket with more points than
        // voxels, which real data does not reach, is dropped by both).
        store(b, merged, false);
        ++rebuilt;
      }
  // Each super-bucket over the buckets above once, not once per bucket (the
  // box spans about 11 buckets a frame at scale 1, mostly of one super-bucket).
  const glm::ivec3 sLo = bLo / kSuper, sHi = bHi / kSuper;
  for (int z = sLo.z; z <= sHi.z; ++z)
    for (int y = sLo.y; y <= sHi.y; ++y)
      for (int x = sLo.x; x <= sHi.x; ++x) refreshSuper((z * superDims_.y + y) * superDims_.x + x);
  return true;
}

void PointShell::refreshSuper(int s) {
  Super& sup = supers_[std::size_t(s)];
  sup.box = Aabb{};
  sup.count = 0;
  for (int b : sup.buckets) {
    sup.box.add(buckets_[std::size_t(b)].box);
    sup.count += buckets_[std::size_t(b)].size;
  }
}

int PointShell::update(const VoxelVolume& volume, const std::vector<BlockOrigin>& dirty) {
  if (dirty.empty()) return 0;
  auto acc = volume.grid().getConstAccessor();
  // A changed voxel changes its coarse voxel and, through the neighbour test and
  // the normals, coarse voxels one step away: widen each block by one coarse voxel.
  int rebuilt = 0;
  // Small fixed-size marks avoid rebuilding a bucket twice without allocating.
  constexpr int kMaxMarked = 256;
  int marked[kMaxMarked];
  int nMarked = 0;
  auto rebuildOnce = [&](int b) {
    for (int i = 0; i < nMarked; ++i)
      if (marked[i] == b) return;
    if (nMarked < kMaxMarked) marked[nMarked++] = b;
    store(b, computeBucket(acc, b), false);
    ++rebuilt;
  };
  for (const BlockOrigin& o : dirty) {
    const glm::ivec3 cLo = glm::max(o / scale_ - 1, glm::ivec3(0));
    const glm::ivec3 cHi = glm::min((o + 7) / scale_ + 1, coarseDims_ - 1);
    const glm::ivec3 bLo = cLo / kBucket, bHi = cHi / kBucket;
    for (int bz = bLo.z; bz <= bHi.z; ++bz)
      for (int by = bLo.y; by <= bHi.y; ++by)
        for (int bx = bLo.x; bx <= bHi.x; ++bx) rebuildOnce((bz * bucketDims_.y + by) * bucketDims_.x + bx);
  }
  // Refresh the super-buckets of everything rebuilt.
  for (int i = 0; i < nMarked; ++i) {
    const int b = marked[i];
    const int bx = b % bucketDims_.x, by = (b / bucketDims_.x) % bucketDims_.y, bz = b / (bucketDims_.x * bucketDims_.y);
    refreshSuper(((bz / kSuper) * superDims_.y + by / kSuper) * superDims_.x + bx / kSuper);
  }
  if (nMarked == kMaxMarked)  // more than we could track: refresh all super-buckets
    for (int s = 0; s < int(supers_.size()); ++s) refreshSuper(s);
  return rebuilt;
}

std::vector<ShellPoint> PointShell::points() const {
  std::vector<ShellPoint> out;
  out.reserve(count_);
  forEach([&](const ShellPoint& p) { out.push_back(p); });
  return out;
}

std::size_t PointShell::memoryBytes() const {
  std::size_t bytes = sizeof(PointShell) + buckets_.capacity() * sizeof(Bucket) + supers_.capacity() * sizeof(Super);
  for (const auto& s : supers_) bytes += s.buckets.capacity() * sizeof(int);
  bytes += points_.capacity() * sizeof(ShellPoint) + cells_.capacity() * sizeof(std::uint16_t) +
           order_.capacity() * sizeof(int);
  bytes += (fineScratch_.capacity() + coarseScratch_.capacity()) * sizeof(float) + merged_.capacity() * sizeof(ShellPoint) +
           mergedCells_.capacity() * sizeof(std::uint16_t);
  return bytes;
}

}  // namespace millsim
