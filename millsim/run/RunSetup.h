#pragma once
// What every run (replay, millsim run, render, tests) does on the scene thread
// before the first frame: find the device, pick its renderer (or a
// --renderer override), build the haptic scene and compile the algorithm.
#include <memory>
#include <string>

#include "millsim/core/Scene.h"
#include "millsim/run/HapticLoop.h"

namespace millsim {

class HapticsDevice;
class VoxelScene;  // millsim/volume/VoxelScene.h: include it to use run.scene

struct CompiledRun {
  // Out of line: VoxelScene is only declared here, so that the run set-up does
  // not bring OpenVDB into everything that includes it.
  CompiledRun();
  ~CompiledRun();
  CompiledRun(CompiledRun&&) noexcept;
  CompiledRun& operator=(CompiledRun&&) noexcept;

  HapticsDevice* device = nullptr;
  ToolGeometry tool;
  std::unique_ptr<VoxelScene> scene;
  std::unique_ptr<HapticAlgorithm> algorithm;
  LoopSettings settings;
  std::string rendererName;
};

// The first device node of the scene, or null.
HapticsDevice* findDevice(const Scene& scene);

// Throws std::runtime_error with a clear message when the scene has no
// device, the device no renderer, or `rendererOverride` names no renderer
// type (the message lists the ones there are).
CompiledRun compileRun(Scene& scene, const std::string& rendererOverride = {});

// A default-configured algorithm of the registered renderer type `typeName`
// for a compiled run (--renderer uses it; a live swap would hand its result to
// HapticLoop::replaceRenderer, which nothing in the millsim command calls yet).
std::unique_ptr<HapticAlgorithm> compileRenderer(Scene& scene, const std::string& typeName, const CompiledRun& run);

// Copies a frame into the device node's output fields (devicePosition,
// force, mainButton, hapticsRate, …). Scene thread only.
void publishToDevice(HapticsDevice& device, const FrameRecord& r, double rate);

// Sets each VolumeObject's removedVolume to what its Miller has removed so
// far, where it changed (a route may show it). Scene thread only; the
// total is safe to read while the haptic thread mills (Milling.h).
void publishRemovedVolumes(const CompiledRun& run);

}  // namespace millsim
