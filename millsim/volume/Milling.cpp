#include "millsim/volume/Milling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "millsim/volume/FloorToInt.h"
#include "millsim/volume/StampRule.h"

namespace millsim {

Miller::Miller(VoxelVolume& volume, float isoValue, const TissueMap* tissues)
    : volume_(volume),
      acc_(volume.grid().getAccessor()),
      tissues_(tissues),
      labels_(tissues ? std::make_unique<TissueMap::LabelGrid::ConstAccessor>(tissues->labels().getConstAccessor())
                      : nullptr),
      iso_(isoValue) {}

StampResult Miller::stamp(const glm::dvec3& centreLocal, double radius, DirtyBlocks& dirty) {
  queue(centreLocal, radius);
  return work(0, dirty);
}

StampResult Miller::stamp(const glm::dvec3& centreLocal, const glm::dvec3& axisLocal, const BurrHead& head,
                          DirtyBlocks& dirty) {
  queue(centreLocal, axisLocal, head);
  return work(0, dirty);
}

void Miller::queue(const glm::dvec3& centreLocal, double radius) {
  if (!(radius > 0.0) || !std::isfinite(centreLocal.x + centreLocal.y + centreLocal.z)) return;
  queued_ = Stamp{};
  queued_.valid = true, queued_.centreLocal = centreLocal, queued_.radius = radius;
}

void Miller::queue(const glm::dvec3& centreLocal, const glm::dvec3& axisLocal, const BurrHead& head) {
  if (head.shape == BurrShape::Round) return queue(centreLocal, head.radius);
  if (!(head.radius > 0.0 && head.length > 0.0 && head.endRadius >= 0.0) ||
      !std::isfinite(centreLocal.x + centreLocal.y + centreLocal.z) ||
      !std::isfinite(axisLocal.x + axisLocal.y + axisLocal.z))
    return;
  const double axisLength = glm::length(axisLocal);
  if (!(axisLength > 0.0)) return;
  queued_ = Stamp{};
  queued_.valid = true, queued_.round = false, queued_.centreLocal = centreLocal;
  queued_.radius = head.boundingRadius(), queued_.axis = axisLocal / axisLength, queued_.head = head;
}

StampResult Miller::work(long budget, DirtyBlocks& dirty) {
  StampResult result;
  long left = budget > 0 ? budget : std::numeric_limits<long>::max();
  const glm::dvec3 h = volume_.voxelSize();
  const double ramp = (h.x + h.y + h.z) / 3.0;
  while (left > 0) {
    if (!walk_.active) {
      if (!queued_.valid) break;
      begin(queued_);
      queued_.valid = false;
      continue;
    }
    const Stamp& s = walk_.stamp;
    if (s.round) {
      const double radius = s.radius;
      walkRows([radius, ramp](const glm::dvec3& d) { return stamp::roundCoverage(std::sqrt(glm::dot(d, d)), radius, ramp); },
               left, dirty, result);
    } else {
      const BurrHead& head = s.head;
      const glm::dvec3 axis = s.axis;
      walkRows([&head, axis, ramp](const glm::dvec3& d) { return stamp::headCoverage(d, axis, head, ramp); }, left,
               dirty, result);
    }
  }
  totalRemoved_.add(result.removedVolume);
  return result;
}

void Miller::begin(const Stamp& s) {
  Walk& w = walk_;
  w = Walk{};
  w.stamp = s;
  const glm::dvec3 h = volume_.voxelSize();
  const double ramp = (h.x + h.y + h.z) / 3.0;
  // Voxels whose centres can be touched: within radius + half a ramp.
  w.c = volume_.localToIndex(s.centreLocal);
  const glm::dvec3 reach = (s.radius + 0.5 * ramp) / h;
  const glm::ivec3 dims = volume_.dims();
  w.lo = glm::max(glm::ivec3(glm::floor(w.c - reach)), glm::ivec3(0));
  w.hi = glm::min(glm::ivec3(glm::ceil(w.c + reach)), dims - 1);
  // The reach padded by a thousandth of a voxel, far above the rounding of
  // the distances: rows and runs are chosen generously, so they never drop a
  // voxel the per-voxel test would keep (a whole voxel of padding visited
  // half as many voxels again).
  const double padded = s.radius + 0.5 * ramp + 1e-3 * std::max({h.x, h.y, h.z});
  w.reach2 = padded * padded;
  // The settled stamp's core: the voxels it covered wholly (coverage 1) it
  // left at air, or uncut as hardness 0, and this stamp leaves them so too,
  // so only the crescent the burr swept since and the ramp of its surface
  // are visited (at 25 µm voxels the core was most of what a stamp read).
  // The core radius is cut by the same thousandth of a voxel as the reach
  // is padded, so rounding never puts a voxel in it that is not.
  if (s.round) {
    w.settled = lastRound_.valid && lastRound_.radius == s.radius;
    w.settledCentre = lastRound_.centre;
    const double core = s.radius - 0.5 * ramp - 1e-3 * std::max({h.x, h.y, h.z});
    w.core2 = w.settled && core > 0.0 ? core * core : -1.0;
    lastRound_ = {true, w.c, s.radius};
  }
  if (glm::any(glm::greaterThan(w.lo, w.hi))) return;  // the reach misses the volume
  // Each leaf the box spans is looked up once a stamp, on first use, not
  // once a row (through the accessors those lookups were a third of a
  // stamp's instructions in the §8.2 replay). Numbered stamps: no clearing.
  // A leaf looked up stays valid while the stamp is walked over several
  // calls: this Miller is the grid's one writer, and what it adds (a leaf
  // made of a dense tile) is looked up again, not kept.
  w.leafLo = w.lo >> 3;
  const glm::ivec3 leaves = (w.hi >> 3) - w.leafLo + 1;
  w.tabled = leaves.x <= kStampLeaves && leaves.y <= kStampLeaves && leaves.z <= kStampLeaves;
  if (++stampNumber_ == 0) {  // wrapped: forget every entry
    for (StampLeaf& e : stampLeaves_) e.stamp = 0;
    stampNumber_ = 1;
  }
  w.j = w.lo.y, w.k = w.lo.z;
  w.active = true;
}

template <class Coverage>
void Miller::walkRows(Coverage coverageAt, long& left, DirtyBlocks& dirty, StampResult& result) {
  Walk& w = walk_;
  const glm::dvec3 h = volume_.voxelSize();
  const float air = volume_.airValue();
  const double phiScale = 1.0 / (2.0 * (double(iso_) - air));
  const double voxelVolume = h.x * h.y * h.z;
  auto phi = [&](double v) { return std::clamp((v - air) * phiScale, 0.0, 1.0); };
  const glm::dvec3 c = w.c;
  const glm::ivec3 lo = w.lo, hi = w.hi, leafLo = w.leafLo;
  const bool tabled = w.tabled;
  const double reach2 = w.reach2, core2 = w.core2;
  const glm::dvec3* settled = w.settled ? &w.settledCentre : nullptr;
  using Leaf = VoxelVolume::Grid::TreeType::LeafNodeType;
  auto leafAt = [&](int i, int j, int k) {
    StampLeaf local;
    StampLeaf& e = tabled ? stampLeaves_[((((k >> 3) - leafLo.z) * kStampLeaves) + ((j >> 3) - leafLo.y)) * kStampLeaves +
                                         ((i >> 3) - leafLo.x)]
                          : local;
    if (tabled && e.stamp == stampNumber_) return e;
    const openvdb::Coord at(i, j, k);
    e.stamp = stampNumber_;
    e.leaf = acc_.probeLeaf(at);
    // No leaf: a tile. Air (the usual case) has nothing to remove; a dense
    // tile goes through the accessor, which makes a leaf of it (so it is
    // looked up again, not kept).
    e.air = !e.leaf && acc_.getValue(at) <= air;
    if (!e.leaf && !e.air) e.stamp = 0;
    // The labels share the densities' leaf layout; a pruned (uniform) leaf is a tile.
    e.labelLeaf = tissues_ ? labels_->probeConstLeaf(at) : nullptr;
    e.tileLabel = tissues_ && !e.labelLeaf ? labels_->getValue(at) : 0;
    return e;
  };
  // Leaf by leaf along voxels [runLo, runHi] of row (j, k), in the same voxel
  // order as one by one (so the removed volume sums identically): a leaf's
  // buffer is read and written directly, which is what setValueOnly does,
  // without a lookup per voxel (through the accessors those were half the
  // stamp's time).
  auto cutRun = [&](int runLo, int runHi, int j, int k) {
    for (int seg = runLo; seg <= runHi; seg = (seg & ~7) + 8) {
      const int segHi = std::min(runHi, (seg & ~7) + 7);
      const StampLeaf block = leafAt(seg, j, k);
      if (block.air) continue;
      result.voxelsRead += segHi - seg + 1;
      Leaf* leaf = block.leaf;
      float* data = leaf ? leaf->buffer().data() : nullptr;
      const int rowOffset = ((j & 7) << 3) + (k & 7);
      const TissueMap::LabelGrid::TreeType::LeafNodeType* labelLeaf = block.labelLeaf;
      const int tileLabel = block.tileLabel;
      // The segment's changed voxels, marked dirty together after it.
      int changedLo = std::numeric_limits<int>::max(), changedHi = std::numeric_limits<int>::min();
      // Cuts voxel i of the row (density `old`, not air): true with the new
      // density in `now` if the burr lowers it and its tissue may be cut.
      auto cut = [&](int i, float old, float& now) {
        const glm::dvec3 d = (glm::dvec3(i, j, k) - c) * h;
        const double coverage = coverageAt(d);
        if (coverage <= 0.0) return false;
        now = stamp::densityLeft(air, iso_, coverage);
        if (now >= old) return false;
        // A tissue of hardness 0 (an implant, a guard a lesson sets) is never cut.
        if (tissues_ &&
            !(tissues_->hardness()[std::size_t(labelLeaf ? labelLeaf->getValue(((i & 7) << 6) + rowOffset) : tileLabel)] > 0.f))
          return false;
        result.removedVolume += (phi(old) - phi(now)) * voxelVolume;
        ++result.voxelsChanged;
        changedLo = std::min(changedLo, i), changedHi = i;
        return true;
      };
      // Air first: a read is cheaper than the distance. In a leaf the run is
      // scanned by a load and a compare a voxel (4 % of #3's frames went to
      // the air test when it chose between the leaf and the accessor at
      // every voxel).
      if (data) {
        for (int i = seg; i <= segHi; ++i) {
          float& value = data[((i & 7) << 6) + rowOffset];
          float now;
          if (!(value <= air) && cut(i, value, now)) value = now;
        }
      } else {
        for (int i = seg; i <= segHi; ++i) {
          const openvdb::Coord xyz(i, j, k);
          const float old = acc_.getValue(xyz);
          float now;
          if (!(old <= air) && cut(i, old, now)) acc_.setValueOnly(xyz, now);
        }
      }
      if (changedLo <= changedHi) dirty.markRun(changedLo, changedHi, j, k);
    }
  };
  // One row (j, k): the voxels within reach that a settled stamp leaves to this one.
  auto row = [&](int j, int k) {
      // Only the run of the row the (padded) reach crosses: a stamp visits
      // about half the voxels of its box, and the test below still decides.
      const double dy = (j - c.y) * h.y, dz = (k - c.z) * h.z;
      const double chord2 = reach2 - dy * dy - dz * dz;
      if (chord2 < 0.0) return;
      const double halfChord = std::sqrt(chord2) / h.x;
      // floorToInt, not std::floor and std::ceil (library calls on the x86-64
      // baseline); c.x is within a reach of [lo.x, hi.x], which is not empty.
      int rowLo = std::max(lo.x, floorToInt(c.x - halfChord)), rowHi = std::min(hi.x, -floorToInt(-(c.x + halfChord)));
      if (settled) {
        // Leave out the voxels nearer the settled centre o than this one
        // (Milling.h, lastRound_): there |d|² − |d_o|² = A·i + B (m²) exceeds
        // a millionth of a voxel², far above the rounding of either, so this
        // stamp's coverage is at most o's and it would change nothing.
        const glm::dvec3& o = *settled;
        const glm::dvec3 h2 = h * h, wo = h2 * (o - c);
        const double A = 2.0 * wo.x;
        const double B = -wo.x * (c.x + o.x) + wo.y * (2.0 * j - c.y - o.y) + wo.z * (2.0 * k - c.z - o.z);
        const double margin = 1e-6 * std::max({h2.x, h2.y, h2.z});
        if (A == 0.0) {
          if (B > margin) return;
        } else {
          // The last kept i, or the first, clamped before the conversion.
          const double edge = std::clamp((margin - B) / A, double(lo.x) - 1.0, double(hi.x) + 1.0);
          if (A > 0.0) rowHi = std::min(rowHi, floorToInt(edge));
          else rowLo = std::max(rowLo, -floorToInt(-edge));
        }
        // And the voxels inside o's core: those strictly within the row's chord of it.
        const double oy = (j - o.y) * h.y, oz = (k - o.z) * h.z;
        const double coreChord2 = core2 - oy * oy - oz * oz;
        if (coreChord2 > 0.0) {
          const double coreHalf = std::sqrt(coreChord2) / h.x;
          const double a = std::clamp(o.x - coreHalf, double(lo.x) - 2.0, double(hi.x) + 2.0);
          const double b = std::clamp(o.x + coreHalf, double(lo.x) - 2.0, double(hi.x) + 2.0);
          const int coreLo = floorToInt(a) + 1, coreHi = -floorToInt(-b) - 1;  // strictly inside (a, b)
          if (coreLo <= coreHi) {
            if (rowLo < coreLo) cutRun(rowLo, std::min(rowHi, coreLo - 1), j, k);
            if (rowHi > coreHi) cutRun(std::max(rowLo, coreHi + 1), rowHi, j, k);
            return;
          }
        }
      }
      cutRun(rowLo, rowHi, j, k);
  };
  // Row by row from where the last call stopped; a row costs one and the
  // densities it reads.
  while (w.k <= hi.z) {
    const int j = w.j, k = w.k;
    if (++w.j > hi.y) w.j = lo.y, ++w.k;
    const long before = result.voxelsRead;
    row(j, k);
    ++result.voxelsRead;
    left -= result.voxelsRead - before;
    if (left <= 0) break;
  }
  if (w.k > hi.z) w.active = false;
}

}  // namespace millsim
