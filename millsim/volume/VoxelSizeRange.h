#pragma once
// Voxel sizes a volume may have (m): a micro-CT's micrometre to a clinical
// CT's thickest slices. Outside them a volume is almost always a unit mistake
// (a spacing written in metres where a file's millimetres are read is 1000×
// too small): the tool would meet a speck or a continent, without an error.
// Every reader checks it (checkVolumeShape), and VolumeObject.voxelSize's
// range is the same.

namespace millsim {

inline constexpr double kMinVoxelSize = 1e-6, kMaxVoxelSize = 0.01;

}  // namespace millsim
