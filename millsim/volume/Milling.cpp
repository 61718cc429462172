#include "millsim/volume/Milling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "millsim/volume/FloorToInt.h"

namespace millsim {

Miller::Miller(VoxelVolume& volume, float isoValue, const TissueMap* tissues)
    : volume_(volume),
      acc_(volume.grid().getAccessor()),
      tissues_(tissues),
      labels_(tissues ? std::make_unique<TissueMap::LabelGrid::ConstAccessor>(tissues->labels().getConstAccessor())
                      : nullptr),
      iso_(isoValue) {}

StampResult Miller::stamp(const glm::dvec3& centreLocal, double radius, DirtyBlocks& dirty) {
  if (!(radius > 0.0) || !std::isfinite(centreLocal.x + centreLocal.y + centreLocal.z)) return {};
  const glm::dvec3 h = volume_.voxelSize();
  const double ramp = (h.x + h.y + h.z) / 3.0;
  const bool sameBurr = lastRound_.valid && lastRound_.radius == radius;
  const StampResult result = stampWith(
      centreLocal, radius,
      [radius, ramp](const glm::dvec3& d) { return std::clamp(0.5 + (radius - std::sqrt(glm::dot(d, d))) / ramp, 0.0, 1.0); },
      dirty, sameBurr ? &lastRound_.centre : nullptr);
  lastRound_ = {true, volume_.localToIndex(centreLocal), radius};
  return result;
}

StampResult Miller::stamp(const glm::dvec3& centreLocal, const glm::dvec3& axisLocal, const BurrHead& head,
                          DirtyBlocks& dirty) {
  if (head.shape == BurrShape::Round) return stamp(centreLocal, head.radius, dirty);
  if (!(head.radius > 0.0 && head.length > 0.0 && head.endRadius >= 0.0) ||
      !std::isfinite(centreLocal.x + centreLocal.y + centreLocal.z) ||
      !std::isfinite(axisLocal.x + axisLocal.y + axisLocal.z))
    return {};
  const double axisLength = glm::length(axisLocal);
  if (!(axisLength > 0.0)) return {};
  const glm::dvec3 axis = axisLocal / axisLength;
  const glm::dvec3 h = volume_.voxelSize();
  const double ramp = (h.x + h.y + h.z) / 3.0;
  return stampWith(
      centreLocal, head.boundingRadius(),
      [&head, axis, ramp](const glm::dvec3& d) {
        const double y = glm::dot(d, axis);
        const double rho = std::sqrt(std::max(0.0, glm::dot(d, d) - y * y));
        return std::clamp(0.5 - headProfileDistance(head, rho, y) / ramp, 0.0, 1.0);
      },
      dirty);
}

template <class Coverage>
StampResult Miller::stampWith(const glm::dvec3& centreLocal, double radius, Coverage coverageAt, DirtyBlocks& dirty,
                              const glm::dvec3* settled) {
  StampResult result;
  const glm::dvec3 h = volume_.voxelSize();
  const double ramp = (h.x + h.y + h.z) / 3.0;
  const float air = volume_.airValue();
  const double phiScale = 1.0 / (2.0 * (double(iso_) - air));
  const double voxelVolume = h.x * h.y * h.z;
  auto phi = [&](double v) { return std::clamp((v - air) * phiScale, 0.0, 1.0); };

  // Voxels whose centres can be touched: within radius + half a ramp.
  const glm::dvec3 c = volume_.localToIndex(centreLocal);
  const glm::dvec3 reach = (radius + 0.5 * ramp) / h;
  const glm::ivec3 dims = volume_.dims();
  const glm::ivec3 lo = glm::max(glm::ivec3(glm::floor(c - reach)), glm::ivec3(0));
  const glm::ivec3 hi = glm::min(glm::ivec3(glm::ceil(c + reach)), dims - 1);
  // The reach padded by a thousandth of a voxel, far above the rounding of
  // the distances: rows and runs are chosen generously, so they never drop a
  // voxel the per-voxel test would keep (a whole voxel of padding visited
  // half as many voxels again).
  const double padded = radius + 0.5 * ramp + 1e-3 * std::max({h.x, h.y, h.z});
  const double reach2 = padded * padded;
  // Each leaf the box spans is looked up once, on first use, not once a row
  // (through the accessors those lookups were a third of a stamp's
  // instructions in the §8.2 replay). Numbered stamps: no clearing.
  if (glm::any(glm::greaterThan(lo, hi))) return result;  // the reach misses the volume
  using Leaf = VoxelVolume::Grid::TreeType::LeafNodeType;
  const glm::ivec3 leafLo = lo >> 3, leaves = (hi >> 3) - leafLo + 1;
  const bool tabled = leaves.x <= kStampLeaves && leaves.y <= kStampLeaves && leaves.z <= kStampLeaves;
  if (++stampNumber_ == 0) {  // wrapped: forget every entry
    for (StampLeaf& e : stampLeaves_) e.stamp = 0;
    stampNumber_ = 1;
  }
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
  // The settled stamp's core: the voxels it covered wholly (coverage 1) it
  // left at air, or uncut as hardness 0, and this stamp leaves them so too,
  // so only the crescent the burr swept since and the ramp of its surface
  // are visited (at 25 µm voxels the core was most of what a stamp read).
  // The core radius is cut by the same thousandth of a voxel as the reach
  // is padded, so rounding never puts a voxel in it that is not.
  const double core = radius - 0.5 * ramp - 1e-3 * std::max({h.x, h.y, h.z});
  const double core2 = settled && core > 0.0 ? core * core : -1.0;
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
        // The density that leaves the voxel a (1 − coverage) material fraction:
        // on the sphere's surface (coverage ½) that is exactly the iso-value.
        now = static_cast<float>(air + 2.0 * (double(iso_) - air) * (1.0 - coverage));
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
  for (int k = lo.z; k <= hi.z; ++k)
    for (int j = lo.y; j <= hi.y; ++j) {
      // Only the run of the row the (padded) reach crosses: a stamp visits
      // about half the voxels of its box, and the test below still decides.
      const double dy = (j - c.y) * h.y, dz = (k - c.z) * h.z;
      const double chord2 = reach2 - dy * dy - dz * dz;
      if (chord2 < 0.0) continue;
      const double half = std::sqrt(chord2) / h.x;
      // floorToInt, not std::floor and std::ceil (library calls on the x86-64
      // baseline); c.x is within a reach of [lo.x, hi.x], which is not empty.
      int rowLo = std::max(lo.x, floorToInt(c.x - half)), rowHi = std::min(hi.x, -floorToInt(-(c.x + half)));
      if (settled) {
        // Leave out the voxels nearer the settled centre o than this one
        // (Milling.h, lastRound_): there |d|² − |d_o|² = A·i + B (m²) exceeds
        // a millionth of a voxel², far above the rounding of either, so this
        // stamp's coverage is at most o's and it would change nothing.
        const glm::dvec3& o = *settled;
        const glm::dvec3 h2 = h * h, w = h2 * (o - c);
        const double A = 2.0 * w.x;
        const double B = -w.x * (c.x + o.x) + w.y * (2.0 * j - c.y - o.y) + w.z * (2.0 * k - c.z - o.z);
        const double margin = 1e-6 * std::max({h2.x, h2.y, h2.z});
        if (A == 0.0) {
          if (B > margin) continue;
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
            continue;
          }
        }
      }
      cutRun(rowLo, rowHi, j, k);
    }
  totalRemoved_.add(result.removedVolume);
  return result;
}

}  // namespace millsim
