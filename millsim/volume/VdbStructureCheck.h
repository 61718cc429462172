#pragma once
// A bounds check of a .vdb file's header and metadata before OpenVDB reads
// it. OpenVDB's reader trusts the file's counts and lengths: a metadata
// entry whose name length is corrupt (4 GB) made it allocate that string and
// then loop over garbage entries past the end of the file, 11.7 GB resident
// before the kernel killed the process (found by mutating a small .vdb). Here
// every count, string and value length of the header, the file's metadata,
// the grid descriptors and each grid's metadata must fit in what is left of
// the file, and the descriptors' offsets must lie inside it, in order.
// The trees themselves are OpenVDB's to read (their sizes are checked against
// the grids' described memory in VdbFile.cpp). Internal to millsim/volume
// (listed in cmake/private-headers.txt).
#include <filesystem>
#include <string>

namespace millsim {

// Throws VolumeError naming the file, the offending field, its offset and
// what was expected. A file of a version whose layout is not checked here
// (OpenVDB file versions other than 222-224) is checked up to its header only.
void checkVdbStructure(const std::filesystem::path& file, const std::string& name);

}  // namespace millsim
