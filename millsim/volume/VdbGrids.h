#pragma once
// Reading every grid of a .vdb file with OpenVDB, bounded: shared by readVdb
// (libmillsim) and millsim-vdb-probe, the process that reads a file first
// (VdbProbeMain.cpp). Includes OpenVDB: only those two see it.
#include <cstdint>
#include <string>

#include <openvdb/openvdb.h>

#include "millsim/volume/VoxelVolume.h"

namespace millsim {

// What one grid may take in memory: a dense float grid of kMaxVoxels is 4 GiB;
// twice that leaves room for the tree.
inline constexpr std::int64_t kMaxGridBytes = std::int64_t(kMaxVoxels) * 8;

// How long reading the file may take, in seconds of CPU time in the probe
// and of wall-clock time in the caller: a minute and a second per megabyte,
// far above a real file's need.
int vdbReadSeconds(const std::string& name);

// Every grid of the file `name`, read now; a grid whose statistics say it is
// larger than a volume may be is refused (VolumeError) before its tree is read.
openvdb::GridPtrVecPtr readVdbGrids(const std::string& name);

}  // namespace millsim
