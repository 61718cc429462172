#pragma once
// HapticScene: the world as a haptic renderer sees it — the implicit surface
// of every volume, where each volume sits, and (for Algorithm #3) its point
// shells. Nothing else: a renderer never sees the node graph, the parser, the
// loop or the voxel storage. The run builds the implementation (VoxelScene,
// over OpenVDB volumes) on the scene thread; one haptic thread then owns it.
//
// The scene's implicit surface is s(p) = max over volumes of (density − iso):
// s > 0 inside material, s = 0 on the iso-surface. Every algorithm works on s,
// so several volumes behave as their union.
#include <cstddef>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace millsim {

class PointShellQuery;  // millsim/haptics/PointShellQuery.h: points and boxes, no voxels

class HapticScene {
public:
  // Where a volume sits in the world.
  struct Placement {
    glm::dmat4 localToWorld{1.0};
    glm::dmat4 worldToLocal{1.0};
    double iso = 0.0;            // density of the iso-surface
    double worldPerLocal = 1.0;  // uniform scale of the transform (cube root of its determinant)
  };

  virtual ~HapticScene() = default;

  virtual std::size_t volumeCount() const = 0;
  virtual const Placement& placement(std::size_t volume) const = 0;

  // s(p) and its gradient (per metre) at a world point. Outside every volume s < 0.
  virtual double field(const glm::dvec3& world) const = 0;
  virtual glm::dvec3 gradient(const glm::dvec3& world) const = 0;
  bool inside(const glm::dvec3& world) const { return field(world) > 0.0; }
  // False only when nothing sampled within `radius` (m) of a world point can be
  // inside material: a cheap cull (a lookup per volume) before sampling a
  // region the tool may be far from. True when in doubt.
  virtual bool mayHaveMaterialNear(const glm::dvec3& world, double radius) const {
    (void)world;
    (void)radius;
    return true;
  }
  // Where the renderer is about to sample most this frame: within `reach`
  // (m) of a world point. A hint for speed only (VoxelScene keeps a dense copy
  // of the voxels there); every point may still be sampled, with the same result.
  virtual void focus(const glm::dvec3& world, double reach) {
    (void)world;
    (void)reach;
  }
  // Unit outward normal at a point near the surface (zero if undefined).
  glm::dvec3 outwardNormal(const glm::dvec3& world) const;
  // Smallest voxel edge in world units: the natural step for searches.
  virtual double voxelSize() const = 0;
  // How hard the material at a world point is to cut (its Tissue's hardness;
  // 1 for material of no tissue, and in air). Renderers divide their feed by
  // it at the burr's leading point (docs/algorithms.md, "Tissue hardness").
  virtual double hardness(const glm::dvec3& world) const {
    (void)world;
    return 1.0;
  }

  // Volume `volume`'s point shell at `scale` (points in its local frame),
  // current with all milling so far: for step(), which brings it up to date
  // without allocating. compile() asks for it with preparePointShell first.
  virtual const PointShellQuery& pointShell(std::size_t volume, int scale) = 0;
  // For compile(), on the scene thread: the shell, built if this is the first
  // request. One that exists is returned as it is, not brought up to date:
  // while a loop runs, the haptic thread owns it (a burr swap compiles while
  // the loop mills). A shell that does not exist cannot be built while a loop
  // runs, since building reads the voxels being milled: that throws
  // std::runtime_error, and the change waits for the next run.
  virtual const PointShellQuery& preparePointShell(std::size_t volume, int scale) { return pointShell(volume, scale); }
};

}  // namespace millsim
