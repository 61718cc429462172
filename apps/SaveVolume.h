#pragma once
// --save-volume FILE.vdb for run and replay: the milled volume at the end, as
// an OpenVDB file a VolumeObject url loads back (same voxels, voxel size and
// dimensions; the isoValue and the placement stay in the scene).
#include <filesystem>
#include <string>

#include "millsim/core/Scene.h"
#include "millsim/volume/VolumeObject.h"

namespace millsim::app {

// What --save-volume and --save-mesh share. Before the run: the scene has
// exactly one VolumeObject, or std::invalid_argument "FLAG writes WHAT; the
// scene has N VolumeObjects". After it: that node, holding its volume, or
// std::runtime_error.
void checkOneVolume(const Scene& scene, const std::string& flag, const std::string& what);
const VolumeObject& theSavedVolume(const Scene& scene, const std::string& flag);

// Before the run: one volume to save and a writable .vdb path, or
// std::invalid_argument saying what is wrong.
void checkSaveVolume(const Scene& scene, const std::filesystem::path& file);

// After the run (the haptic thread has stopped): writes it; returns the line to print.
std::string saveVolume(const Scene& scene, const std::filesystem::path& file);

}  // namespace millsim::app
