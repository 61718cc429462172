#pragma once
// HapticScene: what a haptic renderer sees of the world — read views of every
// VolumeObject with its accumulated transform, and milling. Built once from
// the Scene on the scene thread, then owned and used by one haptic thread
// (it holds that thread's OpenVDB accessors). Renderers never see the parser
// or the node graph.
//
// The scene's implicit surface is s(p) = max over volumes of (density − iso):
// s > 0 inside material, s = 0 on the iso-surface. Every algorithm works on s,
// so several volumes behave as their union.
#include <memory>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include "millsim/volume/DirtyBlocks.h"
#include "millsim/volume/Milling.h"
#include "millsim/volume/VolumeSampler.h"

namespace millsim {

class Scene;
class VolumeObject;
class PointShell;

class HapticScene {
public:
  struct Volume {
    VolumeObject* node;  // may be null for volumes added directly (tests, tools)
    bool millable;
    VoxelVolume* voxels;
    glm::dmat4 localToWorld;
    glm::dmat4 worldToLocal;
    glm::dmat3 worldToIndexLinear;  // the linear part of world → index
    glm::dvec3 worldToIndexOffset;
    double iso;
    double worldPerLocal;  // uniform scale of the transform (cube root of its determinant)
    VolumeSampler sampler;
    Miller miller;
    // The 8³ blocks changed by the latest mill() call that changed this
    // volume, and a counter bumped by every such call. Consumers on the haptic
    // thread (a renderer's point shell, the graphics publisher) remember the
    // epoch they last saw and update from `changed` when it moved on.
    DirtyBlocks changed;
    std::uint64_t millEpoch = 0;
  };

  HapticScene() = default;
  // Collects every loaded VolumeObject under the scene's Transforms.
  explicit HapticScene(const Scene& scene);
  HapticScene(const HapticScene&) = delete;
  // Adds a volume placed by localToWorld; `node` (optional) supplies the
  // millable flag and receives nothing during the run.
  void addVolume(VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso, VolumeObject* node = nullptr);

  std::size_t volumeCount() const { return volumes_.size(); }
  Volume& volume(std::size_t i) { return *volumes_[i]; }
  const Volume& volume(std::size_t i) const { return *volumes_[i]; }

  // s(p) and its gradient (per metre) at a world point. Outside every volume s < 0.
  double field(const glm::dvec3& world) const;
  glm::dvec3 gradient(const glm::dvec3& world) const;
  bool inside(const glm::dvec3& world) const { return field(world) > 0.0; }
  // Unit outward normal at a point near the surface (zero if undefined).
  glm::dvec3 outwardNormal(const glm::dvec3& world) const;
  // Smallest voxel edge in world units: the natural step for searches.
  double voxelSize() const { return voxelSize_ > 0.0 ? voxelSize_ : 1e-4; }

  // Removes material with a burr sphere at a world point (every millable
  // volume). Returns the volume removed (m³, in each volume's local units).
  // Volumes that changed get a new `changed` list and `millEpoch`.
  double mill(const glm::dvec3& centreWorld, double radius);

private:
  std::vector<std::unique_ptr<Volume>> volumes_;
  double voxelSize_ = 0.0;  // 0 until a volume is added
};

}  // namespace millsim
