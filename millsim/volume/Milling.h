#pragma once
// Material removal by the burr, inside the haptic frame.
//
// The paper takes its removal model from its ref. [1], which is not given, so
// MillSim uses this rule (docs/algorithms.md, "Milling"): a stamp of a burr of
// radius r at centre c covers each voxel by coverage = clamp(0.5 + (r − |x − c|)/h,
// 0, 1), h the mean voxel size, and lowers its density to what leaves a
// material fraction of (1 − coverage):
//     v ← min(v, air + 2·(iso − air)·(1 − coverage)).
// With φ(v) = clamp((v − air) / (2·(iso − air)), 0, 1) the material fraction
// (φ = ½ on the iso-surface), the new iso-surface lies on the sphere, voxels
// fully inside become air, a stamp never adds material, and stamping the same
// place again changes nothing (so holding the burr still does not widen the
// hole). Removed volume is Σ (φ(old) − φ(new)) × voxel volume.
//
// Other burr heads (millsim/haptics/BurrHead.h) stamp the same way with the
// head's exact signed distance d(x): coverage = clamp(0.5 − d(x)/h, 0, 1)
// (for the sphere d = |x − c| − r, the rule above).
//
// Hardness (docs/algorithms.md, "Tissue hardness") sets how fast a renderer
// advances the burr; the stamp itself only leaves tissue of hardness 0 alone.
//
// Paced milling (docs/algorithms.md, "Milling at fine voxels"): a stamp's
// work grows as (r/h)² — every voxel of its surface's ramp — so at micro-CT
// voxels one stamp outlasts a 1 kHz frame. queue() then work(budget) walks a
// stamp row by row, at most `budget` densities read a call, and carries the
// rest over; a stamp queued while one is being walked replaces the one
// waiting (the newest burr position wins). Densities only fall and each
// voxel ends at the minimum over the stamps, so walking a stamp over several
// calls leaves the same grid, bit for bit, as stamping it at once.
#include <glm/vec3.hpp>

#include <atomic>
#include <memory>

#include "millsim/haptics/BurrHead.h"
#include "millsim/volume/DirtyBlocks.h"
#include "millsim/volume/TissueMap.h"
#include "millsim/volume/VoxelVolume.h"

namespace millsim {

struct StampResult {
  double removedVolume = 0.0;  // m³
  int voxelsChanged = 0;
  long voxelsRead = 0;  // the walk's work: densities read, and one a row started
};

// The writer's side of milling. Holds its own accessor: use one Miller per
// writing thread, and no other thread may read the grid while it writes (see
// VolumeReplica for how graphics gets the changes). Nothing else may raise a
// density while a Miller is in use (lastRound_).
class Miller {
public:
  // `tissues` (optional, outliving the Miller) gives each voxel's hardness;
  // without it every voxel has hardness 1.
  Miller(VoxelVolume& volume, float isoValue, const TissueMap* tissues = nullptr);

  // Stamps a burr sphere given in the volume's local frame (metres): walks
  // what was begun, then this stamp (a queued one it replaces), to the end.
  // Marks every changed block in `dirty`. Does not allocate.
  StampResult stamp(const glm::dvec3& centreLocal, double radius, DirtyBlocks& dirty);
  // Stamps a burr head (dimensions in the volume's local metres) centred at
  // `centreLocal` whose shaft axis (the tool's local +Y) is the unit vector
  // `axisLocal`. A round head is exactly the sphere stamp above (bit for bit).
  // Does not allocate.
  StampResult stamp(const glm::dvec3& centreLocal, const glm::dvec3& axisLocal, const BurrHead& head,
                    DirtyBlocks& dirty);

  // Paced milling: queues a stamp (arguments as stamp()'s), replacing any
  // queued one that has not begun; an invalid one is ignored.
  void queue(const glm::dvec3& centreLocal, double radius);
  void queue(const glm::dvec3& centreLocal, const glm::dvec3& axisLocal, const BurrHead& head);
  // Walks the stamp begun and then the queued one, until `budget` densities
  // were read (a row is never split: it may read one row more) or nothing is
  // left; budget 0: until nothing is left. Does not allocate.
  StampResult work(long budget, DirtyBlocks& dirty);
  // Whether a stamp is being walked or waits.
  bool busy() const { return walk_.active || queued_.valid; }
  // A stamp as queued: a round burr of `radius`, or a head along `axis`.
  struct Stamp {
    bool valid = false;
    bool round = true;
    glm::dvec3 centreLocal{0.0};
    double radius = 0.0;  // the sphere's, or the head's bounding radius
    glm::dvec3 axis{0.0, 1.0, 0.0};
    BurrHead head{};
  };
  // The stamp being walked and the one waiting; null when there is none.
  const Stamp* walking() const { return walk_.active ? &walk_.stamp : nullptr; }
  const Stamp* waiting() const { return queued_.valid ? &queued_ : nullptr; }

  // m³ removed so far. The scene thread of `millsim run` reads it while the
  // haptic thread mills (VolumeObject.removedVolume, live): a relaxed atomic
  // with one writer, so the read is race-free and the stamp never waits.
  double totalRemoved() const { return totalRemoved_.load(std::memory_order_relaxed); }

private:
  // The stamp being walked: its voxel box in index space and the next row.
  struct Walk {
    bool active = false;
    Stamp stamp;
    glm::dvec3 c{0.0};         // centre (index space)
    glm::ivec3 lo{0}, hi{-1};  // the voxels within reach (+ half a ramp)
    double reach2 = 0.0;       // the padded reach, squared (m²)
    bool settled = false;      // leave out what the last round stamp settled (lastRound_)
    glm::dvec3 settledCentre{0.0};
    double core2 = -1.0;  // the settled stamp's core radius, squared (m²)
    bool tabled = false;  // the stamp's leaves fit stampLeaves_
    glm::ivec3 leafLo{0};
    int j = 0, k = 0;  // the next row
  };
  // Starts walking `s` (lastRound_ moves on to it when it is round).
  void begin(const Stamp& s);
  // Walks the current stamp's rows with this coverage(d) of a voxel's offset
  // d from the centre (m), until `left` is spent or the stamp is done.
  template <class Coverage>
  void walkRows(Coverage coverage, long& left, DirtyBlocks& dirty, StampResult& result);
  VoxelVolume& volume_;
  VoxelVolume::Grid::Accessor acc_;
  const TissueMap* tissues_;
  std::unique_ptr<TissueMap::LabelGrid::ConstAccessor> labels_;  // only with tissues
  float iso_;
  Stamp queued_;
  Walk walk_;
  // The leaves a stamp's box spans, looked up once a stamp (walkRows): up to
  // 12 per axis (a reach of 40 voxels: a 2 mm burr at 25 µm voxels; the table
  // is about 70 KB); a larger stamp looks up per row, as the lesson's burr at
  // 25 µm did when the table was 5 leaves an axis.
  static constexpr int kStampLeaves = 12;
  struct StampLeaf {
    unsigned stamp = 0;  // valid in the stamp with this number
    VoxelVolume::Grid::TreeType::LeafNodeType* leaf = nullptr;
    bool air = false;  // no leaf: an air tile, nothing to remove
    const TissueMap::LabelGrid::TreeType::LeafNodeType* labelLeaf = nullptr;
    int tileLabel = 0;
  };
  StampLeaf stampLeaves_[kStampLeaves * kStampLeaves * kStampLeaves];
  unsigned stampNumber_ = 0;
  // The last round stamp begun: its centre (index space) and radius. Stamps
  // are walked in order, so it is done when the next one begins. Densities only
  // fall, and this Miller is the volume's one writer, so every voxel it
  // covered is still at most what it left there. A round stamp of the same
  // radius covers a voxel nearer that centre than its own no more, and would
  // change nothing there: it skips them, about half its sphere when the burr
  // creeps (the §8.2 procedure's milling), and the last stamp's core, which
  // it left air, with the same result bit for bit.
  struct LastRound {
    bool valid = false;
    glm::dvec3 centre{0.0};
    double radius = 0.0;
  } lastRound_;
  // Copyable (a Miller is moved into its VoxelScene) though atomic.
  struct Total {
    std::atomic<double> value{0.0};
    Total() = default;
    Total(const Total& o) : value(o.load(std::memory_order_relaxed)) {}
    Total& operator=(const Total& o) {
      value.store(o.load(std::memory_order_relaxed), std::memory_order_relaxed);
      return *this;
    }
    double load(std::memory_order order) const { return value.load(order); }
    void add(double d) { value.store(value.load(std::memory_order_relaxed) + d, std::memory_order_relaxed); }
  } totalRemoved_;
};

}  // namespace millsim
