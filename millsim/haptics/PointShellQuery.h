#pragma once
// PointShellQuery: what a renderer reads of a point shell (Algorithm #3's
// "MPO", built and kept current with milling by millsim/volume/PointShell):
// points with outward normals in a volume's local frame, bucketed by 8³
// coarse voxels and the buckets grouped by 4³ into super-buckets, each with
// a tight bounding box, and box-culled visits of them (the paper's octree).
// The renderer contract owns this type so that a renderer sees points and
// boxes, never the volume room. The queries are templates, inlined into the
// renderer's loops: no virtual call per bucket or point.
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

namespace millsim {

struct ShellPoint {
  glm::vec3 position;  // volume-local frame, metres
  glm::vec3 normal;    // unit, pointing out of the material
};

struct Aabb {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
  bool empty() const { return lo.x > hi.x; }
  void add(const glm::vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  void add(const Aabb& b) {
    if (!b.empty()) lo = glm::min(lo, b.lo), hi = glm::max(hi, b.hi);
  }
  bool overlaps(const Aabb& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y && lo.z <= b.hi.z && b.lo.z <= hi.z;
  }
};

class PointShellQuery {
public:
  static constexpr int kBucket = 8;  // coarse voxels per bucket edge
  static constexpr int kSuper = 4;   // buckets per super-bucket edge

  // The reduced resolution s (the shell of the volume reduced over s³ blocks).
  int scale() const { return scale_; }
  std::size_t size() const { return count_; }

  // The buckets `overlaps` accepts, as forEachCandidate would visit them
  // (indices into `out`, cleared first), and their points' count: one
  // traversal for a budget check and the visit after it. Does not allocate
  // once `out` holds bucketCount().
  template <class Overlaps> std::size_t collectCandidates(Overlaps&& overlaps, std::vector<int>& out) const {
    out.clear();
    std::size_t n = 0;
    for (const Super& s : supers_) {
      if (s.count == 0 || !overlaps(s.box)) continue;
      for (int b : s.buckets) {
        const Bucket& bucket = buckets_[std::size_t(b)];
        if (bucket.size != 0 && overlaps(bucket.box)) n += bucket.size, out.push_back(b);
      }
    }
    return n;
  }
  // Visits the points of the buckets collectCandidates listed.
  template <class Visit> void forEachIn(const std::vector<int>& listed, Visit&& visit) const {
    for (int b : listed) {
      const Bucket& bucket = buckets_[std::size_t(b)];
      for (const ShellPoint *p = first(bucket), *end = p + bucket.size; p != end; ++p) visit(*p);
    }
  }
  std::size_t bucketCount() const { return buckets_.size(); }
  // Whether any candidate point satisfies `pred` (stops at the first).
  template <class Overlaps, class Pred> bool anyCandidate(Overlaps&& overlaps, Pred&& pred) const {
    for (const Super& s : supers_) {
      if (s.count == 0 || !overlaps(s.box)) continue;
      for (int b : s.buckets) {
        const Bucket& bucket = buckets_[std::size_t(b)];
        if (bucket.size == 0 || !overlaps(bucket.box)) continue;
        for (const ShellPoint *p = first(bucket), *end = p + bucket.size; p != end; ++p)
          if (pred(*p)) return true;
      }
    }
    return false;
  }

  // Visits the points of every bucket whose bounding box `overlaps(Aabb)` accepts:
  // the test is applied first to super-buckets, then to buckets.
  template <class Overlaps, class Visit> void forEachCandidate(Overlaps&& overlaps, Visit&& visit) const {
    for (const Super& s : supers_) {
      if (s.count == 0 || !overlaps(s.box)) continue;
      for (int b : s.buckets) {
        const Bucket& bucket = buckets_[std::size_t(b)];
        if (bucket.size == 0 || !overlaps(bucket.box)) continue;
        for (const ShellPoint *p = first(bucket), *end = p + bucket.size; p != end; ++p) visit(*p);
      }
    }
  }
  // Every point, bucket by bucket (the brute-force path, for comparison).
  template <class Visit> void forEach(Visit&& visit) const {
    for (const Bucket& b : buckets_)
      for (const ShellPoint *p = first(b), *end = p + b.size; p != end; ++p) visit(*p);
  }
protected:
  PointShellQuery() = default;
  ~PointShellQuery() = default;
  PointShellQuery(const PointShellQuery&) = default;
  PointShellQuery& operator=(const PointShellQuery&) = default;

  // Points [begin, begin + size) of points_ (cells_ holds each one's coarse
  // voxel within the bucket, (k·8 + j)·8 + i); the range is `capacity` long.
  struct Bucket {
    Aabb box;
    std::uint32_t begin = 0;
    std::uint16_t size = 0, capacity = 0;
    bool material = false;  // held material at build: only such a bucket can ever hold points
  };
  const ShellPoint* first(const Bucket& b) const { return points_.data() + b.begin; }
  struct Super {
    std::vector<int> buckets;
    Aabb box;
    std::size_t count = 0;
  };

  int scale_ = 1;
  std::vector<Bucket> buckets_;
  std::vector<Super> supers_;
  std::size_t count_ = 0;
  std::vector<ShellPoint> points_;  // every bucket's range, then free slots (PointShell's headroom)
};

}  // namespace millsim
