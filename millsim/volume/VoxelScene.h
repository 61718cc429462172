#pragma once
// VoxelScene: the HapticScene over voxel volumes (OpenVDB) — what a run hands
// its renderer, and what the run itself mills and publishes from. Built on the
// scene thread from the Scene's VolumeObjects (placedVolumes(), the same walk
// graphics uses, so volume i is the same volume on both sides), then owned and
// used by one haptic thread: it holds that thread's OpenVDB accessors.
#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>

#include "millsim/haptics/HapticScene.h"
#include "millsim/volume/DirtyBlocks.h"
#include "millsim/volume/MaterialBlocks.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/VolumeSampler.h"

namespace millsim {

class Scene;
class VolumeObject;
class PointShell;
class TissueMap;

class VoxelScene final : public HapticScene {
public:
  struct Volume {
    VolumeObject* node;  // may be null for volumes added directly (tests, tools)
    // VolumeObject.millable, live: the scene thread may switch it while the
    // haptic thread mills (LiveUpdates).
    std::atomic<bool> millable;
    VoxelVolume* voxels;
    Placement placement;
    glm::dmat3 worldToIndexLinear;  // the linear part of world → index
    glm::dvec3 worldToIndexOffset;
    double indexPerWorld;  // the largest stretch of worldToIndexLinear (voxels per metre)
    VolumeSampler sampler;
    MaterialBlocks material;  // where material may be, for mayHaveMaterialNear
    Miller miller;
    const TissueMap* tissues;  // null: one material of hardness 1
    // The 8³ blocks changed by the latest mill() call that changed this
    // volume, and a counter bumped by every such call. Consumers on the haptic
    // thread (the graphics publisher) remember the epoch they last saw and
    // update from `changed` when it moved on; the point shells collect every
    // call's blocks instead (Shell::pending).
    DirtyBlocks changed;
    std::uint64_t millEpoch = 0;
    // VolumeObject.millingBudget: the densities a frame's stamps may read
    // (0: no limit); what is left over is walked in the next frames (Miller::work).
    long millingBudget = 0;
    // Whether the sampler reads the stamps not yet walked over the grid
    // (VolumeSampler::setPendingCuts): not with a tissue of hardness 0.
    bool feelsPendingCuts = true;
    // worldToIndexLinear is diagonal (a volume scaled and moved, not turned:
    // every shipped lesson) and these are its diagonal: three products
    // instead of nine a sample, the same result for finite points.
    bool axisAligned = false;
    glm::dvec3 worldToIndexScale{0.0};
    glm::dvec3 toIndex(const glm::dvec3& world) const {
      return axisAligned ? world * worldToIndexScale + worldToIndexOffset : worldToIndexLinear * world + worldToIndexOffset;
    }
  };

  VoxelScene();
  // Collects every loaded VolumeObject under the scene's Transforms.
  explicit VoxelScene(const Scene& scene);
  ~VoxelScene() override;
  VoxelScene(const VoxelScene&) = delete;
  VoxelScene& operator=(const VoxelScene&) = delete;

  // Adds a volume placed by localToWorld; `node` (optional) supplies the
  // millable flag, the tissues and caches the point shells between runs.
  // `tissues` (optional, outliving the scene) stands in for a node's.
  void addVolume(VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso, VolumeObject* node = nullptr,
                 const TissueMap* tissues = nullptr);

  Volume& volume(std::size_t i) { return *volumes_[i]; }
  const Volume& volume(std::size_t i) const { return *volumes_[i]; }

  // HapticScene
  std::size_t volumeCount() const override { return volumes_.size(); }
  const Placement& placement(std::size_t i) const override { return volumes_[i]->placement; }
  double field(const glm::dvec3& world) const override;
  glm::dvec3 gradient(const glm::dvec3& world) const override;
  bool mayHaveMaterialNear(const glm::dvec3& world, double radius) const override;
  void focus(const glm::dvec3& world, double reach) override;
  double voxelSize() const override { return voxelSize_ > 0.0 ? voxelSize_ : 1e-4; }
  // Merges the milling the shell has not seen yet (see Shell), then returns it.
  const PointShellQuery& pointShell(std::size_t volume, int scale) override;
  // Builds the shell if it is new (refused while a loop runs: see
  // setLoopRunning); returns an existing one untouched.
  const PointShellQuery& preparePointShell(std::size_t volume, int scale) override;
  // Set by HapticLoop from start() to join(): the haptic thread owns the
  // shells and mills the voxels, so the scene thread may not build a shell.
  void setLoopRunning(bool running) { loopRunning_.store(running, std::memory_order_release); }
  // The same, as the volume room's own type (tests and benchmarks look inside).
  const PointShell& shell(std::size_t volume, int scale);

  // The hardness of the voxel nearest a world point in the first volume that
  // has a tissue there; 1 elsewhere.
  double hardness(const glm::dvec3& world) const override;

  // Removes material with a burr sphere at a world point (every millable
  // volume), within each volume's millingBudget: a stamp the budget does not
  // cover is finished by the next calls, and one that waits for it is
  // replaced by the newer. Returns the volume removed (m³, in each volume's
  // local units). Volumes that changed get a new `changed` list and `millEpoch`.
  double mill(const glm::dvec3& centreWorld, double radius);
  // The same with a burr head (world metres) of the tool with this world
  // orientation (the head's axis is the tool's local +Y). A round head is
  // exactly mill(centre, head.radius).
  double mill(const glm::dvec3& centreWorld, const glm::dquat& toolOrientation, const BurrHead& head);
  // A frame that does not cut: walks on the stamps the budget left, as mill() would.
  double continueMilling();
  // Whether a volume has a stamp left to walk.
  bool millingPending() const;

private:
  // A point shell in use by this scene, and the milling it has not merged yet.
  // mill() only adds the changed blocks to `pending` (O(changed blocks)); the
  // shell merges them when pointShell() asks for it. So a shell nobody looks
  // at (Barbic's coarse fallback, a renderer waiting in a RendererPool) costs
  // a milling frame nothing, and catches up, exactly, when it is next used.
  struct Shell {
    std::size_t volume;
    int scale;
    PointShell* shell;
    std::unique_ptr<PointShell> owned;  // for volumes without a node
    DirtyBlocks pending;
  };

  // Tells v's sampler of the stamps its Miller has not walked to their end.
  static void feelPendingCuts(Volume& v);
  std::vector<std::unique_ptr<Volume>> volumes_;
  std::vector<Shell> shells_;
  std::atomic<bool> loopRunning_{false};
  double voxelSize_ = 0.0;  // 0 until a volume is added
};

}  // namespace millsim
