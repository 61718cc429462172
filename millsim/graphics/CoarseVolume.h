#pragma once
// A volume averaged over f×f×f blocks of another: VolumeMesh's coarser level
// of detail. Coarse voxel i is the mean of fine voxels f·i … f·i + f − 1 along
// each axis (clamped to the fine volume where its size is not a multiple of
// f), summed x fastest, then y, then z.
#include <glm/vec3.hpp>

namespace millsim {

class VoxelVolume;

// The coarse volume's dimensions: every fine voxel in one coarse voxel.
glm::ivec3 coarseDims(glm::ivec3 fine, int factor);
// Averages coarse voxels [from, to] (clamped to the coarse volume) from
// `fine` into `coarse`; air is written as inactive background.
void averageBlocks(const VoxelVolume& fine, VoxelVolume& coarse, int factor, glm::ivec3 from, glm::ivec3 to);
// The whole of averageBlocks into an empty `coarse`, visiting only where
// `fine` holds more than air (its leaves and non-air tiles): the same grid,
// where the whole box read every fine voxel once more — 4 s of the first
// mesh of a tooth at 25 µm, whose box is mostly air. factor 2, 4 or 8 (a
// coarse voxel then lies in one 8³ leaf of the fine grid).
void averageAll(const VoxelVolume& fine, VoxelVolume& coarse, int factor);

}  // namespace millsim
