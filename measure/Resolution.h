#pragma once
// Cost against resolution (issue 44): the scene's tooth phantom resampled at
// each voxel size h, keeping its extent (dims scale as 1/h), and per size
// what opening the lesson costs (wall time, peak resident memory) and what
// each renderer's frames cost over a procedure (measureProcedure, Procedure.h).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "measure/Procedure.h"

namespace millsim::measure {

// The `--set` overrides that make the scene's first VolumeObject, a phantom
// (its url, and its labelUrl if that is the phantom's labels), the same
// phantom at voxel size h (metres). Throws std::runtime_error naming what the
// scene reads instead. `dims`: the resampled phantom's voxels.
std::vector<LoadOptions::FieldOverride> phantomAtVoxelSize(const std::string& scenePath, double h,
                                                           glm::ivec3* dims = nullptr);

struct ResolutionLoad {
  double voxelSize = 0.0;  // m
  glm::ivec3 dims{0};
  std::uint64_t materialVoxels = 0;  // the densities' active voxels
  double seconds = 0.0;              // wall time of loading the scene: volumes, tissues, regions
  double peakMiB = -1.0;             // peak resident memory while loading (-1: the kernel would not say)
  std::vector<LoadOptions::FieldOverride> overrides;  // what made the scene's phantom this size
};
ResolutionLoad measureLoad(const std::string& scenePath, double h);

// The process's peak resident memory since it began or was last reset
// (VmHWM, MiB; -1 if unreadable), and resetting it to the current resident
// size (/proc/self/clear_refs; false if the kernel refuses).
double peakResidentMiB();
bool resetPeakResident();

}  // namespace millsim::measure
