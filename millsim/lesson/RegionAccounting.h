#pragma once
// RegionAccounting: what the burr removed inside each MillingTarget and
// ForbiddenRegion of a scene, counted on the scene thread from the milled
// blocks the haptic loop publishes (as it does for graphics), so the haptic
// thread pays nothing for assessment. A block's contribution to a region is
// Σ over its voxels inside the region of (φ_start − φ_now) × voxel volume,
// φ the material fraction of docs/algorithms.md "Milling"; a block seen again
// replaces its earlier contribution, so totals never drift.
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
  double fraction() const { return initial > 0.0 ? removed / initial : 0.0; }
};

class RegionAccounting {
public:
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
  void findSoftTissues();

  std::vector<std::unique_ptr<Region>> regions_;
  std::vector<std::unique_ptr<Volume>> volumes_;
  std::vector<RegionResult> results_;
  std::vector<std::unique_ptr<SoftTissue>> soft_;  // one per (forbidden region, volume) with soft voxels
  Pose lastPose_;
  BurrHead lastHead_;
  bool posed_ = false;
};

}  // namespace millsim
