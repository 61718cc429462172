#pragma once
// RegionAccounting: what the burr removed inside each MillingTarget and
// ForbiddenRegion of a scene, counted on the scene thread from the milled
// blocks the haptic loop publishes (as it does for graphics), so the haptic
// thread pays nothing for assessment. A block's contribution to a region is
// Σ over its voxels inside the region of (φ_start − φ_now) × voxel volume,
// φ the material fraction of docs/algorithms.md "Milling"; a block seen again
// replaces its earlier contribution, so totals never drift.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "millsim/volume/BlockChannel.h"

namespace millsim {

class Scene;
class AssessmentRegion;

struct RegionResult {
  std::string name;
  bool forbidden = false;
  double removed = 0.0;           // m³
  double initial = 0.0;           // m³ of material inside at the start
  double firstViolation = -1.0;   // s; forbidden regions only; -1: never
  double fraction() const { return initial > 0.0 ? removed / initial : 0.0; }
};

class RegionAccounting {
public:
  // Collects the scene's regions and loaded volumes (in placedVolumes order,
  // the haptic scene's) and measures each region's material. Call before
  // milling starts; throws std::runtime_error for a region naming an unknown tissue.
  explicit RegionAccounting(const Scene& scene);
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
  // Writes removedVolume, fraction, violated and firstViolationTime.
  void publishFields();
  const std::vector<RegionResult>& results() const { return results_; }

private:
  struct Shape;
  struct Region;
  struct Volume;
  void count(std::size_t volume, const BlockUpdate& block, double t);

  std::vector<std::unique_ptr<Region>> regions_;
  std::vector<std::unique_ptr<Volume>> volumes_;
  std::vector<RegionResult> results_;
};

}  // namespace millsim
