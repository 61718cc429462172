#pragma once
// RegionAccounting: what the burr removed inside each MillingTarget and
// ForbiddenRegion of a scene, counted on the scene thread from the milled
// blocks the haptic loop publishes (as it does for graphics), so the haptic
// thread pays nothing for assessment. A block's contribution to a region is
// Σ over its voxels inside the region of (φ_start − φ_now) × voxel volume,
// φ the material fraction of docs/algorithms.md "Milling"; a block seen again
// replaces its earlier contribution, so totals never drift.
//
// The same blocks give what was removed outside every target and per tissue
// (RemovalSummary), and the time every target was done.
//
// A soft tissue (TissueMap::soft: the pulp, below the isoValue) has nothing
// to remove: a ForbiddenRegion naming one is entered when the burr's head
// reaches one of its voxels below the surface (burrAt, for every frame's
// drawn burr), and is violated from that frame.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "millsim/haptics/BurrHead.h"
#include "millsim/math/Pose.h"
#include "millsim/volume/BlockChannel.h"

namespace millsim {

class Scene;
class AssessmentRegion;

struct RegionResult {
  std::string name;
  bool forbidden = false;
  double removed = 0.0;           // m³
  double initial = 0.0;           // m³ of material inside at the start
  double initialForbidden = 0.0;  // targets: m³ of that material also inside a forbidden region
  double firstViolation = -1.0;   // s; forbidden regions only; -1: never
  // Forbidden regions' soft tissues: when the burr's head first reached one of
  // their voxels (s, -1: never), how far past their surface it reached (m, to
  // a voxel) and the volume of their voxels it swept (m³).
  double firstEntry = -1.0;
  double depth = 0.0;
  double swept = 0.0;
  // And the thinnest wall left over them: the least distance from a voxel
  // the burr cut through to their surface (m, to a voxel); 0 once entered;
  // -1 while nothing was cut within kWallReach of them.
  double thinnestWall = -1.0;
  double fraction() const { return initial > 0.0 ? removed / initial : 0.0; }
};

// What the burr removed beyond each region's own count: outside every
// MillingTarget (the over-preparation a teacher marks down) and per tissue;
// and when every target was done.
struct RemovalSummary {
  bool hasTargets = false;               // the scene has a MillingTarget
  double outsideTargets = 0.0;           // m³ removed where no target is
  double targetsInitial = 0.0;           // m³ of material the targets held at the start (their union)
  double overPreparationPenalty = 1.0;   // the largest of the targets' MillingTarget.overPreparationPenalty
  double completed = -1.0;               // s: when every target first reached its completeAt; -1: never
  // m: the deepest voxel cut through, below the volume's original surface
  // straight above it (world +Y: the occlusal direction of an upright tooth).
  double deepestCut = 0.0;
  std::vector<std::pair<std::string, double>> byTissue;  // m³ removed per tissue name ("no tissue": material of none)
  // Removal outside the targets over the material the targets held (0 without targets).
  double overPreparation() const { return targetsInitial > 0.0 ? outsideTargets / targetsInitial : 0.0; }
};

class RegionAccounting {
public:
  // How far from a soft tissue the remaining wall is measured (m): thinner
  // walls are what a teacher looks at, and each cut voxel's search for the
  // nearest surface voxel grows with the cube of it.
  static constexpr double kWallReach = 3e-3;
  // Collects the scene's regions and loaded volumes (in placedVolumes order,
  // the haptic scene's) and measures each region's material. Call before
  // milling starts; throws std::runtime_error for a region naming an unknown tissue.
  explicit RegionAccounting(const Scene& scene) : RegionAccounting(scene, true) {}
  ~RegionAccounting();
  RegionAccounting(const RegionAccounting&) = delete;
  RegionAccounting& operator=(const RegionAccounting&) = delete;

  bool empty() const { return regions_.empty(); }
  // The channel volume i's milled blocks are to be published into
  // (HapticLoop::publishBlocks(i, channel(i))); volumes in placedVolumes order.
  std::size_t volumeCount() const { return volumes_.size(); }
  BlockChannel& channel(std::size_t volume);
  // Counts every block published since the last call; `t` is the run time of
  // the newest frame (s), the time a first violation is stamped with.
  void update(double t);
  // The burr's head at `pose` (world) in the frame at run time `t`: stamps
  // the first entry into a forbidden soft tissue, the depth and the swept
  // voxels. Cheap far from them (a box test); near, a head's worth of voxel
  // reads, made again only once the burr moved a quarter voxel or turned.
  void burrAt(const Pose& pose, const BurrHead& head, double t);
  // Writes removedVolume, fraction, violated, firstViolationTime, depth and sweptVolume.
  void publishFields();
  const std::vector<RegionResult>& results() const { return results_; }
  const RemovalSummary& summary() const { return summary_; }
  // Each region's material before any milling (`initial`), without the
  // snapshot a run counts against: what `check` reports.
  static std::vector<RegionResult> atStart(const Scene& scene);

private:
  struct Shape;
  struct Region;
  struct Volume;
  struct SoftTissue;
  RegionAccounting(const Scene& scene, bool counting);
  void count(std::size_t volume, const BlockUpdate& block, double t);
  void stampViolation(std::size_t region, double t);
  void stampCompletion(double t);
  void findSoftTissues();
  void measureAtStart(std::size_t volume);

  std::vector<std::unique_ptr<Region>> regions_;
  std::vector<std::unique_ptr<Volume>> volumes_;
  std::vector<RegionResult> results_;
  RemovalSummary summary_;
  // Slots of a block's contribution after the regions': outside the targets, then one per tissue name.
  std::size_t outsideSlot_ = 0, tissueSlots_ = 0;
  std::vector<std::unique_ptr<SoftTissue>> soft_;  // one per (forbidden region, volume) with soft voxels
  Pose lastPose_;
  BurrHead lastHead_;
  bool posed_ = false;
};

}  // namespace millsim
