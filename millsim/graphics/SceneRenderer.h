#pragma once
// SceneRenderer: draws a MillSim scene offscreen with OpenGL (3.3 core on
// OSMesa/llvmpipe) through the same SceneDrawer as the window: each volume's
// iso-surface (incrementally re-meshed as it is milled), the standard Shapes,
// the tool at its drawn pose and Algorithm #1's intersection point as a small
// red sphere, seen from the scene's Viewpoint (or framed, without one) over
// its Background, cut by its ClipPlanes.
//
// Threads: a renderer owns a GL context, which is current on one thread. Create
// it, call it and destroy it on the same thread (the graphics thread of a live
// run). It reads the Scene only in createSceneRenderer(); afterwards it reads
// only the voxels it meshes, in build and volumeChanged() — so in a live run
// pass the graphics side's VolumeReplica volumes, never the haptic thread's.
//
// Live use (graphics thread):
//   RendererOptions o;  o.voxels = {&replica.volume()};      // one per scene volume
//   auto r = createSceneRenderer(scene, o);                  // meshes everything (≈60 ms)
//   loop: r->volumeChanged(0, replica.apply(channel));       // remesh + upload changed chunks only
//         r->render(toolView(tool, latestOutput));  r->readPixels() (or not)
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "millsim/graphics/Image.h"
#include "millsim/graphics/SceneDrawer.h"
#include "millsim/graphics/SceneView.h"
#include "millsim/haptics/HapticsRenderer.h"
#include "millsim/haptics/MillTool.h"
#include "millsim/math/Pose.h"
#include "millsim/volume/DirtyBlocks.h"

namespace millsim {

class Scene;
class VoxelVolume;

inline ToolView toolView(const ToolGeometry& g, const HapticOutput& out) {
  return {g, out.drawnTool, out.hasIntersection, out.intersection};
}

struct RendererOptions {
  int width = 512, height = 512;
  std::string viewpoint;  // DEF name of the Viewpoint to look through; empty: the first one
  // Voxels to mesh in place of each scene VolumeObject's own, in VoxelScene's
  // order (e.g. VolumeReplica volumes in a live run). Empty: the objects' own.
  std::vector<const VoxelVolume*> voxels;
  // Draw a volume from its 2×2×2-averaged mesh where a voxel covers under 1.5
  // pixels (SceneDrawer). False: always every voxel (to compare the two).
  bool levelOfDetail = true;
  // Cap each cut by the volume's section, coloured by tissue (SceneDrawer). False: X3D's open cut.
  bool capCuts = true;
};

using RendererStats = DrawStats;

class SceneRenderer {
public:
  virtual ~SceneRenderer() = default;

  // Adds and meshes another volume (not from the scene); returns its index.
  virtual std::size_t addVolume(const VoxelVolume& voxels, const glm::dmat4& localToWorld, double iso) = 0;
  virtual std::size_t volumeCount() const = 0;
  // The listed 8³ blocks (origins, as VolumeReplica::apply and DirtyBlocks give
  // them) of volume `index` changed: re-mesh and re-upload the chunks they touch.
  virtual void volumeChanged(std::size_t index, const std::vector<BlockOrigin>& blocks) = 0;
  // Re-meshes a whole volume (when which blocks changed is not known).
  virtual void rebuildVolume(std::size_t index) = 0;

  // The scene's drawn fields changed (SceneDrawer::adoptView); false if `fresh` has other volumes.
  virtual bool sceneChanged(const SceneView& fresh) = 0;

  // Camera: starts as the scene's Viewpoint; set it to zoom or rotate.
  virtual void setView(const ViewSpec& view) = 0;
  virtual ViewSpec view() const = 0;
  // The camera of the latest render() (near and far follow the scene and tool).
  virtual Camera camera() const = 0;

  // Draws one frame; without a tool, draws the scene alone.
  virtual void render(const std::optional<ToolView>& tool) = 0;
  // The latest frame: colour (rows from the top) and depth in [0, 1] (rows from the top).
  virtual Image readPixels() = 0;
  virtual std::vector<float> readDepth() = 0;

  virtual RendererStats stats() const = 0;
  virtual std::string glDescription() const = 0;  // GL version and renderer
};

// Reads the scene (SceneView) and meshes its volumes. Throws GraphicsError
// (bad size, no usable OSMesa context, shader failure) and std::invalid_argument
// (no Viewpoint of that DEF name; options.voxels of the wrong length or with a
// different shape than the object's).
std::unique_ptr<SceneRenderer> createSceneRenderer(const Scene& scene, const RendererOptions& options = {});

// Writes an image as an 8-bit RGBA PNG (libpng). Throws GraphicsError naming
// the path when it cannot be written.
void writePng(const Image& image, const std::filesystem::path& path);

}  // namespace millsim
