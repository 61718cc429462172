#pragma once
// VolumeSampler: the one fast path for reading densities. Trilinear density
// and gradient at any index-space point through a cached OpenVDB accessor; one
// sampler per thread (accessors are not shared). Outside the volume the value
// is air, however far (or NaN) the point.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "millsim/haptics/BurrHead.h"
#include "millsim/volume/FloorToInt.h"
#include "millsim/volume/StampRule.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

class VolumeSampler {
public:
  explicit VolumeSampler(const VoxelVolume& volume)
      : acc_(volume.grid().getConstAccessor()), tree_(&volume.grid().tree()), air_(volume.airValue()) {}

  // The window: a dense copy of the voxels around where the caller works
  // (focus()), edge³ voxels, z fastest as in a leaf. A cell inside it is read
  // with one index and fixed strides, whichever leaves it straddles: half of
  // the burr's cells straddle leaves, and their corners were a fifth of #1's
  // frames. Off (no cost) until enabled; enabling allocates, so do it on the
  // scene thread. Whoever changes the voxels afterwards tells the sampler
  // (refresh()), as VoxelScene::mill does: the copy does not follow by itself.
  void enableWindow(int edge) {
    windowEdge_ = std::max(edge, 0);
    windowCells_ = unsigned(std::max(windowEdge_ - 1, 0));
    window_.assign(std::size_t(windowEdge_) * std::size_t(windowEdge_) * std::size_t(windowEdge_), air_);
    windowLo_ = glm::ivec3(CachedLeaf::kNone / 2);  // holds nothing yet
  }
  // Makes the window hold every cell within `reach` voxels of an index-space
  // point, recentring it there (a copy from the grid) only when it does not
  // already. A reach the window cannot hold, or a point far outside, leaves it.
  void focus(const glm::dvec3& centre, double reach) {
    if (windowEdge_ < 2 || !(reach >= 0.0) || 2.0 * reach + 2.0 > double(windowEdge_ - 1)) return;
    const double x = inRange(centre.x), y = inRange(centre.y), z = inRange(centre.z);
    const glm::ivec3 lo(floorToInt(x - reach), floorToInt(y - reach), floorToInt(z - reach));
    const glm::ivec3 hi(floorToInt(x + reach) + 1, floorToInt(y + reach) + 1, floorToInt(z + reach) + 1);
    if (glm::all(glm::greaterThanEqual(lo, windowLo_)) && glm::all(glm::lessThan(hi, windowLo_ + windowEdge_))) return;
    const glm::ivec3 mid(floorToInt(x), floorToInt(y), floorToInt(z));
    if (glm::any(glm::greaterThan(glm::abs(mid), glm::ivec3(1 << 29)))) return;
    windowLo_ = mid - windowEdge_ / 2;
    copyToWindow(windowLo_, windowLo_ + windowEdge_ - 1);
  }
  // Copies voxels [lo, hi] (inclusive) into the window again where it holds
  // them: after the caller changed them.
  void refresh(const glm::ivec3& lo, const glm::ivec3& hi) {
    if (windowEdge_ < 2) return;
    copyToWindow(glm::max(lo, windowLo_), glm::min(hi, windowLo_ + windowEdge_ - 1));
  }

  // A stamp the grid does not hold yet (Milling.h, paced milling): while it
  // is set, each corner a density reads is the lower of the grid's value and
  // what the stamp will leave there, so a renderer feels the cut where the
  // burr is, not where the walk has got to. Up to two: the stamp being walked
  // and the one waiting. Only for a volume with no tissue of hardness 0
  // (the stamp leaves those voxels; the sampler does not know them).
  struct PendingCut {
    bool round = true;
    glm::dvec3 centre{0.0};  // index space
    double radius = 0.0;     // m: the sphere's, or the head's bounding radius
    glm::dvec3 axis{0.0, 1.0, 0.0};
    BurrHead head{};
  };
  static constexpr int kMaxPendingCuts = 2;
  // `iso` is the volume's; voxel size and ramp as the Miller's.
  void setPendingCuts(const PendingCut* cuts, int n, float iso, const glm::dvec3& voxelSize) {
    pendingCount_ = std::clamp(n, 0, kMaxPendingCuts);
    iso_ = iso, h_ = voxelSize, ramp_ = (voxelSize.x + voxelSize.y + voxelSize.z) / 3.0;
    for (int c = 0; c < pendingCount_; ++c) {
      PendingReach& r = reach_[c];
      pending_[c] = cuts[c];
      const double radius = cuts[c].radius;
      // A cell whose centre is farther than the reach, half a ramp and half
      // its diagonal has no corner the stamp touches.
      const double cell = radius + 0.5 * ramp_ + 0.5 * glm::length(voxelSize) + 1e-3 * ramp_;
      r.cell2 = cell * cell;
      // A round stamp's coverage is exactly 0 beyond r + ramp/2 and exactly 1
      // within r − ramp/2; a relative margin of 10⁻⁹ keeps rounding on the
      // safe side, so only the ramp between needs the square root.
      const double outer = radius + 0.5 * ramp_, inner = radius - 0.5 * ramp_;
      r.outer2 = outer * outer * (1.0 + 1e-9);
      r.inner2 = inner > 0.0 ? inner * inner * (1.0 - 1e-9) : -1.0;
    }
  }
  void clearPendingCuts() { pendingCount_ = 0; }

  // Trilinear density at an index-space point (voxel centres at integers).
  float density(const glm::dvec3& p) const {
    if (pendingCount_ > 0) return densityWithPendingCuts(p);
    const double x = inRange(p.x), y = inRange(p.y), z = inRange(p.z);
    const int i = floorToInt(x), j = floorToInt(y), k = floorToInt(z);
    float c[8];
    cellCorners(i, j, k, c);
    return interpolate(c, x - i, y - j, z - k);
  }

  // Density gradient (per voxel, index units) by central differences of the
  // trilinear field one voxel apart: smooth across cell faces, unlike the
  // derivative of a single trilinear cell.
  glm::dvec3 gradient(const glm::dvec3& p) const {
    return {0.5 * (density(p + glm::dvec3(1, 0, 0)) - density(p - glm::dvec3(1, 0, 0))),
            0.5 * (density(p + glm::dvec3(0, 1, 0)) - density(p - glm::dvec3(0, 1, 0))),
            0.5 * (density(p + glm::dvec3(0, 0, 1)) - density(p - glm::dvec3(0, 0, 1)))};
  }

  float voxel(int i, int j, int k) const { return acc_.getValue(openvdb::Coord(i, j, k)); }

private:
  // density() with the pending cuts read over the grid (out of line: the
  // common path keeps its registers).
  // The densities at cell (i, j, k)'s eight corners, x fastest in bit 0, y
  // in bit 1, z in bit 2: from the window, a kept leaf, or the blocks.
  [[gnu::always_inline]] void cellCorners(int i, int j, int k, float* c) const {
    // Unsigned: one compare a side, and no signed overflow far from the window.
    const unsigned wi = unsigned(i) - unsigned(windowLo_.x), wj = unsigned(j) - unsigned(windowLo_.y),
                   wk = unsigned(k) - unsigned(windowLo_.z);
    if (wi < windowCells_ && wj < windowCells_ && wk < windowCells_) {
      const std::size_t sy = std::size_t(windowEdge_), sx = sy * sy;
      const float* d = window_.data() + wi * sx + wj * sy + wk;
      c[0] = d[0], c[1] = d[sx], c[2] = d[sy], c[3] = d[sx + sy];
      c[4] = d[1], c[5] = d[sx + 1], c[6] = d[sy + 1], c[7] = d[sx + sy + 1];
      return;
    }
    // When the cell lies inside one 8³ leaf (343 of its 512 cells) whose
    // buffer is kept: eight reads from it (offset = x·64 + y·8 + z) instead of
    // eight accessor lookups, 1.3x faster near a surface (bench/
    // VolumeBench.cpp, BM_SampleNearSurface against ...EightLookups).
    const CachedLeaf& e = cache_[slot(i >> 3, j >> 3, k >> 3)];
    if ((i & 7) != 7 && (j & 7) != 7 && (k & 7) != 7 && e.data && e.i == i >> 3 && e.j == j >> 3 && e.k == k >> 3) {
      const int o = ((i & 7) << 6) + ((j & 7) << 3) + (k & 7);
      const float* d = e.data;
      c[0] = d[o], c[1] = d[o + 64], c[2] = d[o + 8], c[3] = d[o + 72];
      c[4] = d[o + 1], c[5] = d[o + 65], c[6] = d[o + 9], c[7] = d[o + 73];
    } else {
      corners(i, j, k, c);
    }
  }

  [[gnu::noinline]] float densityWithPendingCuts(const glm::dvec3& p) const {
    const double x = inRange(p.x), y = inRange(p.y), z = inRange(p.z);
    const int i = floorToInt(x), j = floorToInt(y), k = floorToInt(z);
    float c[8];
    cellCorners(i, j, k, c);
    for (int n = 0; n < pendingCount_; ++n) {
      const PendingCut& cut = pending_[n];
      const PendingReach& r = reach_[n];
      const glm::dvec3 mid = (glm::dvec3(i, j, k) + 0.5 - cut.centre) * h_;
      if (glm::dot(mid, mid) > r.cell2) continue;
      for (int corner = 0; corner < 8; ++corner) {
        if (c[corner] <= air_) continue;  // air: the stamp leaves it
        // c[] order: x fastest in bit 0, y in bit 1, z in bit 2.
        const glm::dvec3 d = (glm::dvec3(i + (corner & 1), j + ((corner >> 1) & 1), k + (corner >> 2)) - cut.centre) * h_;
        double coverage;
        if (cut.round) {
          const double d2 = glm::dot(d, d);
          if (d2 > r.outer2) continue;
          coverage = d2 < r.inner2 ? 1.0 : stamp::roundCoverage(std::sqrt(d2), cut.radius, ramp_);
        } else {
          coverage = stamp::headCoverage(d, cut.axis, cut.head, ramp_);
        }
        if (coverage <= 0.0) continue;
        // The Miller's own rule, so the value is the one the walk will write.
        const float now = stamp::densityLeft(air_, iso_, coverage);
        if (now < c[corner]) c[corner] = now;
      }
    }
    return interpolate(c, x - i, y - j, z - k);
  }

  static float interpolate(const float c[8], double tx, double ty, double tz) {
    const double x00 = c[0] + (c[1] - c[0]) * tx, x10 = c[2] + (c[3] - c[2]) * tx;
    const double x01 = c[4] + (c[5] - c[4]) * tx, x11 = c[6] + (c[7] - c[6]) * tx;
    const double y0 = x00 + (x10 - x00) * ty, y1 = x01 + (x11 - x01) * ty;
    return static_cast<float>(y0 + (y1 - y0) * tz);
  }

  // Copies voxels [lo, hi] (inclusive, within the window) from the grid, a
  // leaf at a time: runs of z from its buffer, or its tile's value.
  [[gnu::noinline]] void copyToWindow(const glm::ivec3& lo, const glm::ivec3& hi) {
    if (glm::any(glm::greaterThan(lo, hi))) return;
    const auto& tree = *tree_;
    const std::size_t sy = std::size_t(windowEdge_), sx = sy * sy;
    for (int ox = lo.x & ~7; ox <= hi.x; ox += 8)
      for (int oy = lo.y & ~7; oy <= hi.y; oy += 8)
        for (int oz = lo.z & ~7; oz <= hi.z; oz += 8) {
          const openvdb::Coord origin(ox, oy, oz);
          const glm::ivec3 a = glm::max(glm::ivec3(ox, oy, oz), lo), b = glm::min(glm::ivec3(ox, oy, oz) + 7, hi);
          const auto* leaf = tree.probeConstLeaf(origin);
          const float* data = leaf ? leaf->buffer().data() : nullptr;
          const float tile = leaf ? 0.f : tree.getValue(origin);
          for (int i = a.x; i <= b.x; ++i)
            for (int j = a.y; j <= b.y; ++j) {
              float* run = window_.data() + std::size_t(i - windowLo_.x) * sx + std::size_t(j - windowLo_.y) * sy +
                           std::size_t(a.z - windowLo_.z);
              if (data) std::copy_n(data + ((i & 7) << 6) + ((j & 7) << 3) + (a.z & 7), b.z - a.z + 1, run);
              else std::fill_n(run, b.z - a.z + 1, tile);
            }
        }
  }

  // A coordinate the cast to int and the corner above it can take: a point
  // farther out (or NaN) reads the air 2^30 voxels away, not an undefined
  // cast (UBSan: "outside the range of representable values") or a NaN
  // weight. Two compare-and-selects a coordinate.
  static double inRange(double x) {
    constexpr double kFar = 1 << 30;
    return x > -kFar ? (x < kFar ? x : kFar) : -kFar;
  }

  // The buffers of the leaves read last, one slot per leaf position modulo
  // 4 on each axis, so that any 4×4×4 leaves (a burr and its shaft's foot
  // span up to 3 per axis) never evict each other. The accessor caches one
  // leaf: the burr's samples hopping between the leaves around it missed it,
  // walked down from its cached internal node, and LeafBuffer::data() is an
  // out-of-line call. Milling turns a dense tile into a leaf but never removes
  // a leaf, and writes values in place, so a kept buffer stays the leaf's.
  // Callgrind over the §8.2 replay, the frames' instructions: #2 -8.7 % (an
  // 8-slot hashed table: -7.9 %; #1 with it -7.7 %), #3 unchanged; logs
  // byte-identical.
  //
  // Where there is no leaf and the tile is air, that is kept too: milling
  // never writes air (Miller skips it, and a replica only receives what
  // milling wrote), so an air tile stays one; samples in the air above the
  // tooth probed the tree for every corner. A material tile (a pruned CT's
  // interior) may become a leaf, and is read through the accessor each time.
  // With the straddling cells' corners written out (corners() below), a
  // sample in #1's frames of the §8.2 replay went from 425 instructions to
  // about 230: callgrind over the frames, #1 15.72 → 11.43 G instructions
  // (−27 %), #2 15.02 → 11.28 G (−25 %); logs byte-identical.
  static constexpr int kLeafCache = 64;
  struct CachedLeaf {
    static constexpr int kNone = std::numeric_limits<int>::min();  // no voxel's leaf: i >> 3 > kNone
    int i = kNone, j = kNone, k = kNone;  // leaf origin / 8
    const float* data = nullptr;          // the leaf's values, or null: an air tile of value `value`
    float value = 0.f;
  };
  static int slot(int li, int lj, int lk) { return (li & 3) | (lj & 3) << 2 | (lk & 3) << 4; }
  // The leaf or air tile holding leaf (li, lj, lk) (voxel / 8); null for a
  // material tile. The hit is inline; the miss, a walk down the tree, is not.
  const CachedLeaf* block(int li, int lj, int lk) const {
    const CachedLeaf& e = cache_[slot(li, lj, lk)];
    if (e.i == li && e.j == lj && e.k == lk) return &e;
    return fill(li, lj, lk);
  }
  [[gnu::noinline]] const CachedLeaf* fill(int li, int lj, int lk) const {
    CachedLeaf& e = cache_[slot(li, lj, lk)];
    const openvdb::Coord origin(li * 8, lj * 8, lk * 8);
    if (const auto* leaf = acc_.probeConstLeaf(origin)) {
      e = {li, lj, lk, leaf->buffer().data(), 0.f};
      return &e;
    }
    const float tile = acc_.getValue(origin);
    if (!(tile <= air_)) return nullptr;
    e = {li, lj, lk, nullptr, tile};
    return &e;
  }
  [[gnu::noinline]] float materialTile(int i, int j, int k) const { return acc_.getValue(openvdb::Coord(i, j, k)); }

  // Every other cell (out of line, so that the common one above keeps its
  // registers): a leaf not kept yet, an air tile, or a cell straddling two to
  // eight leaves (a third of all cells, half of the burr's in the §8.2
  // replay), read through the kept blocks rather than one accessor lookup per
  // corner (the accessor caches one leaf, so corners alternating between two
  // leaves missed it every time).
  [[gnu::noinline]] void corners(int i, int j, int k, float* c) const {
    const int li0 = i >> 3, li1 = (i + 1) >> 3, lj0 = j >> 3, lj1 = (j + 1) >> 3, lk0 = k >> 3, lk1 = (k + 1) >> 3;
    // The eight corners' blocks; corners in one leaf share its lookup. (A
    // loop over the corners with the blocks in arrays cost 480 instructions
    // a cell; written out, 186 over the §8.2 replay.)
    const bool si = li1 != li0, sj = lj1 != lj0, sk = lk1 != lk0;
    const CachedLeaf* b000 = block(li0, lj0, lk0);
    const CachedLeaf* b100 = si ? block(li1, lj0, lk0) : b000;
    const CachedLeaf* b010 = sj ? block(li0, lj1, lk0) : b000;
    const CachedLeaf* b110 = !sj ? b100 : !si ? b010 : block(li1, lj1, lk0);
    const CachedLeaf* b001 = sk ? block(li0, lj0, lk1) : b000;
    const CachedLeaf* b101 = !sk ? b100 : !si ? b001 : block(li1, lj0, lk1);
    const CachedLeaf* b011 = !sk ? b010 : !sj ? b001 : block(li0, lj1, lk1);
    const CachedLeaf* b111 = !sk ? b110 : !sj ? b101 : !si ? b011 : block(li1, lj1, lk1);
    const int oi0 = (i & 7) << 6, oi1 = ((i + 1) & 7) << 6, oj0 = (j & 7) << 3, oj1 = ((j + 1) & 7) << 3;
    const int ok0 = k & 7, ok1 = (k + 1) & 7;
    c[0] = read(b000, oi0 + oj0 + ok0, i, j, k);
    c[1] = read(b100, oi1 + oj0 + ok0, i + 1, j, k);
    c[2] = read(b010, oi0 + oj1 + ok0, i, j + 1, k);
    c[3] = read(b110, oi1 + oj1 + ok0, i + 1, j + 1, k);
    c[4] = read(b001, oi0 + oj0 + ok1, i, j, k + 1);
    c[5] = read(b101, oi1 + oj0 + ok1, i + 1, j, k + 1);
    c[6] = read(b011, oi0 + oj1 + ok1, i, j + 1, k + 1);
    c[7] = read(b111, oi1 + oj1 + ok1, i + 1, j + 1, k + 1);
  }
  // Voxel (i, j, k) at `offset` in its block: a kept leaf's value, an air
  // tile's, or a material tile's through the accessor.
  float read(const CachedLeaf* b, int offset, int i, int j, int k) const {
    if (b && b->data) return b->data[offset];
    return b ? b->value : materialTile(i, j, k);
  }

  mutable VoxelVolume::Grid::ConstAccessor acc_;
  const VoxelVolume::Grid::TreeType* tree_;
  float air_;
  mutable CachedLeaf cache_[kLeafCache];
  int windowEdge_ = 0;                   // 0: no window
  unsigned windowCells_ = 0;             // cells a side whose corners all lie in the window: edge − 1
  glm::ivec3 windowLo_{CachedLeaf::kNone / 2};  // the window's first voxel (far away: holds nothing)
  std::vector<float> window_;             // edge³, z fastest
  int pendingCount_ = 0;                  // setPendingCuts
  PendingCut pending_[kMaxPendingCuts];
  struct PendingReach {
    double cell2 = 0.0, outer2 = 0.0, inner2 = -1.0;  // m², setPendingCuts
  } reach_[kMaxPendingCuts];
  float iso_ = 0.f;
  glm::dvec3 h_{1.0};
  double ramp_ = 1.0;
};

}  // namespace millsim
